"""The stitched topology of VesselCenterline on N pvserver ranks against one (issue 19, item 2).

    VESSELTOUCH_PLUGIN=<build>/lib/paraview-5.11/plugins/VesselTouch/VesselTouch.so \\
        pvpython Testing/ParaView/clientserver/measure_cs_topology.py --volume tree.nrrd \\
        --ranks 1 2 4 [--lower 500 --upper 65535] [--seed X Y Z]

For each rank count a pvserver starts on 127.0.0.1, reads the volume (each rank its piece) and
runs VesselCenterline thresholded (DistributedExtraction on with more than one rank). Printed:
paths, points, vessel ends, bifurcations and loops (vtouch_skeleton_graph.graph), the shortest
polyline, and the stitch's field arrays (Stitch*); --save PREFIX writes each run's output to
PREFIX_r<ranks>.vtp. The scaling bench's tree:
`scaling_bench.write_tree_nrrd(path, (256, 256, 256))` (Utilities/bench). With --seed (world mm)
the run is seeded (UseSeedPoint: the distributed run codes with the global SS code, its rounds
printed as SeedCodeRounds); without, the distributed run codes with the single run's automatic
roots (RootChoiceRounds, RootChoicePropagations, RootChoiceComponents, RootChoiceRoots: whole
voxel indices, to seed a 1-rank run there with --seed). With --automatic the range is
estimated (AutomaticIntensityRange: the raw modes; without --seed the range from the whole volume,
computed across the ranks) and IntensityRangeUsed is printed; --raw-phantom N writes
VesselPhantom's raw angiogram (ClientServer.DistributedRawSeeded's: 60 segments, 4 clutter
objects, seed 3, float) at N^3 to --volume first; --largest-radius sets LargestVesselRadius (the
ghost margin; ClientServer.DistributedExtraction's phantoms: 3.2); --phantom SHAPE writes the
built-in VesselPhantom of that Shape as ClientServer.DistributedExtraction does (128^3,
RadiusFraction 0.025; 0 = the ring, 4 = the Y, 5 = the tree, 6 = the loop network; use --lower
550 --largest-radius 3.2) to --volume first. Each run prints its UpdatePipeline time (client wall clock, the server's run and
the delivery), the raw modes' refinement over the whole stitched paths (DistributedRefinement*:
pages, rounds, bytes, seconds) and, against the first rank count's run, the farthest point either way (voxels)
and the share of points within 0.1 voxel either way.
A measurement, not a test: nothing is asserted.
"""

import argparse
import os
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path[:0] = [HERE, os.path.dirname(HERE)]
from vtouch_pvserver import ParallelServer, write_float_nrrd  # noqa: E402
from vtouch_skeleton_graph import farthest_point_voxels, graph  # noqa: E402

import numpy as np  # noqa: E402

from paraview import servermanager as sm  # noqa: E402
from paraview import simple  # noqa: E402
from vtkmodules.vtkIOXML import vtkXMLPolyDataWriter  # noqa: E402


def write_raw_phantom(path, n):
    """ClientServer.DistributedRawSeeded's raw angiogram at n^3, as float raw NRRD (built in)."""
    simple.LoadPlugin(os.environ["VESSELTOUCH_PLUGIN"], remote=False, ns=globals())
    phantom = VesselPhantom(Shape=8, Dimensions=[n, n, n], AngiogramSegments=60,  # noqa: F821
                            ClutterCount=4, Seed=3, OutputScalarType=10)
    write_float_nrrd(path, sm.Fetch(phantom))
    simple.Delete(phantom)


def write_phantom(path, shape):
    """The ClientServer.DistributedExtraction phantom `shape` as a float NRRD at `path`."""
    simple.LoadPlugin(os.environ["VESSELTOUCH_PLUGIN"], remote=False, ns=globals())
    phantom = VesselPhantom(Dimensions=[128, 128, 128], RadiusFraction=0.025,  # noqa: F821
                            Shape=shape)
    write_float_nrrd(path, sm.Fetch(phantom))
    simple.Delete(phantom)


def share_within(a, b, reach_voxels=0.1):
    """The fraction of the points of `a` within `reach_voxels` of a point of `b` (1 mm voxels)."""
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    near = 0
    for start in range(0, len(a), 512):
        block = a[start:start + 512]
        d = np.sqrt(((block[:, None, :] - b[None, :, :]) ** 2).sum(axis=2)).min(axis=1)
        near += int((d <= reach_voxels).sum())
    return near / len(a)


def measure(volume, ranks, lower, upper, seed=None, automatic=False, radius=0.0, first=None,
            save=None):
    server = ParallelServer(ranks=ranks)
    server.start()
    try:
        server.connect(os.environ["VESSELTOUCH_PLUGIN"])
        reader = simple.OpenDataFile(volume)
        reader.UpdatePipeline()  # the reader's time is not the filter's
        centerline = simple.VesselCenterline(Input=reader,
                                             AutomaticIntensityRange=1 if automatic else 0,
                                             LowerThreshold=lower, UpperThreshold=upper,
                                             LargestVesselRadius=radius,
                                             DistributedExtraction=1 if ranks > 1 else 0)
        if seed:
            centerline.UseSeedPoint = 1
            centerline.SeedPoint = seed
        start = time.perf_counter()
        centerline.UpdatePipeline()
        seconds = time.perf_counter() - start
        data = sm.Fetch(centerline)
        if save:
            writer = vtkXMLPolyDataWriter()
            writer.SetFileName("%s_r%d.vtp" % (save, ranks))
            writer.SetInputData(data)
            writer.Write()
        g = graph(data, 1.0)
        fd = data.GetFieldData()
        stitch = {fd.GetArrayName(i): fd.GetArray(i).GetTuple(0)[0]
                  for i in range(fd.GetNumberOfArrays())
                  if fd.GetArrayName(i).startswith(("Stitch", "SeedCode", "RootChoice", "Region",
                                                      "ClutterStretches", "ContactStretches",
                                                      "NonTubular", "DistributedRefinement"))}
        roots = fd.GetArray("RootChoiceRoots")
        if roots is not None:
            # Every root voxel of every component (whole index), not only the first.
            stitch["RootChoiceRoots"] = [tuple(int(v) for v in roots.GetTuple(i))
                                         for i in range(roots.GetNumberOfTuples())]
        used = fd.GetArray("IntensityRangeUsed")
        if used is not None:
            stitch["IntensityRangeUsed"] = [used.GetTuple(i)[0]
                                            for i in range(used.GetNumberOfTuples())]
        message = fd.GetAbstractArray("ExtractionMessage")
        if message is not None and message.GetNumberOfValues() and message.GetValue(0):
            print("ranks %d: message %r" % (ranks, message.GetValue(0)))
        shortest = min(len(c) for c in g["chains"]) if g["chains"] else 0
        print("ranks %d: %d paths, %d points, %d ends, %d bifurcations, %d loops, shortest "
              "polyline %d points; %s" % (ranks, data.GetNumberOfCells(), data.GetNumberOfPoints(),
                                          g["ends"], len(g["bifurcations"]), g["cycles"],
                                          shortest, stitch))
        farthest = ""
        if first is not None and len(first) and len(g["points"]):
            farthest = ("; farthest point from the first run %.3f voxel, of it %.3f voxel; "
                        "within 0.1 voxel of it %.1f %%, of its points %.1f %%") % (
                farthest_point_voxels(g["points"], first, 1.0),
                farthest_point_voxels(first, g["points"], 1.0),
                100.0 * share_within(g["points"], first),
                100.0 * share_within(first, g["points"]))
        print("ranks %d: VesselCenterline UpdatePipeline %.2f s%s" % (ranks, seconds, farthest))
        simple.Disconnect()
        return g["points"]
    finally:
        server.stop()


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--volume", required=True)
    parser.add_argument("--ranks", type=int, nargs="+", default=[1, 2, 4])
    parser.add_argument("--lower", type=float, default=500.0)
    parser.add_argument("--upper", type=float, default=65535.0)
    parser.add_argument("--seed", type=float, nargs=3, default=None,
                        help="a seed point (world mm): the seeded mode")
    parser.add_argument("--automatic", action="store_true",
                        help="AutomaticIntensityRange (the raw modes)")
    parser.add_argument("--largest-radius", type=float, default=0.0,
                        help="LargestVesselRadius, mm (0: automatic)")
    parser.add_argument("--raw-phantom", type=int, default=0,
                        help="write the raw phantom at N^3 to --volume first")
    parser.add_argument("--save", default=None,
                        help="write each run's output to SAVE_r<ranks>.vtp (to look at)")
    parser.add_argument("--phantom", type=int, default=None,
                        help="write the built-in phantom of this Shape to --volume first")
    args = parser.parse_args()
    if args.raw_phantom:
        write_raw_phantom(args.volume, args.raw_phantom)
    if args.phantom is not None:
        write_phantom(args.volume, args.phantom)
    if not os.path.exists(args.volume):
        sys.exit("no volume at %s" % args.volume)
    if "VESSELTOUCH_PLUGIN" not in os.environ:
        sys.exit("set VESSELTOUCH_PLUGIN to the plugin's VesselTouch.so")
    first = None
    for ranks in args.ranks:
        points = measure(args.volume, ranks, args.lower, args.upper, args.seed, args.automatic,
                         args.largest_radius, first, args.save)
        first = points if first is None else first


if __name__ == "__main__":
    main()

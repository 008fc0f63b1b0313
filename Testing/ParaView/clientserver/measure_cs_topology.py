"""The stitched topology of VesselCenterline on N pvserver ranks against one (issue 19, item 2).

    VESSELTOUCH_PLUGIN=<build>/lib/paraview-5.11/plugins/VesselTouch/VesselTouch.so \\
        pvpython Testing/ParaView/clientserver/measure_cs_topology.py --volume tree.nrrd \\
        --ranks 1 2 4 [--lower 500 --upper 65535] [--seed X Y Z]

For each rank count a pvserver starts on 127.0.0.1, reads the volume (each rank its piece) and
runs VesselCenterline thresholded (DistributedExtraction on with more than one rank). Printed:
paths, points, vessel ends, bifurcations and loops (vtouch_skeleton_graph.graph), the shortest
polyline, and the stitch's field arrays (Stitch*). The scaling bench's tree:
`scaling_bench.write_tree_nrrd(path, (256, 256, 256))` (Utilities/bench). With --seed (world mm)
the run is seeded (UseSeedPoint: the distributed run codes with the global SS code, its rounds
printed as SeedCodeRounds); without, the distributed run codes with the single run's automatic
roots (RootChoiceRounds, RootChoicePropagations, RootChoiceComponents, RootChoiceRoots: whole
voxel indices, to seed a 1-rank run there with --seed). Each run after the first also prints the
farthest point between its skeleton and the first run's, both ways (voxels: 1 mm voxels), e.g.
`--ranks 1 2 4`: the distributed runs against the single run. With --phantom SHAPE the volume is
first written as ClientServer.DistributedExtraction writes its phantoms (the built-in
VesselPhantom, 128^3, RadiusFraction 0.025; SHAPE 0 = the ring, 4 = the Y, 5 = the tree; use
--lower 550 --largest-radius 3.2, the test's threshold and ghost margin). A measurement, not a test: nothing is asserted.
"""

import argparse
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path[:0] = [HERE, os.path.dirname(HERE)]
from vtouch_pvserver import ParallelServer, write_float_nrrd  # noqa: E402
from vtouch_skeleton_graph import farthest_point_voxels, graph  # noqa: E402

from paraview import servermanager as sm  # noqa: E402
from paraview import simple  # noqa: E402


def measure(volume, ranks, lower, upper, seed=None, first=None, radius=None):
    """Runs and prints one rank count; returns its graph. `first`: an earlier run's graph to
    measure the farthest point against."""
    server = ParallelServer(ranks=ranks)
    server.start()
    try:
        server.connect(os.environ["VESSELTOUCH_PLUGIN"])
        reader = simple.OpenDataFile(volume)
        centerline = simple.VesselCenterline(Input=reader, AutomaticIntensityRange=0,
                                             LowerThreshold=lower, UpperThreshold=upper,
                                             DistributedExtraction=1 if ranks > 1 else 0)
        if radius:
            centerline.LargestVesselRadius = radius  # the ghost margin follows it
        if seed:
            centerline.UseSeedPoint = 1
            centerline.SeedPoint = seed
        centerline.UpdatePipeline()
        data = sm.Fetch(centerline)
        g = graph(data, 1.0)
        fd = data.GetFieldData()
        stitch = {fd.GetArrayName(i): fd.GetArray(i).GetTuple(0)[0]
                  for i in range(fd.GetNumberOfArrays())
                  if fd.GetArrayName(i).startswith(("Stitch", "SeedCode", "RootChoice"))}
        roots = fd.GetArray("RootChoiceRoots")
        if roots is not None:
            # Every root voxel of every component (whole index), not only the first.
            stitch["RootChoiceRoots"] = [tuple(int(v) for v in roots.GetTuple(i))
                                         for i in range(roots.GetNumberOfTuples())]
        message = fd.GetAbstractArray("ExtractionMessage")
        if message is not None and message.GetNumberOfValues() and message.GetValue(0):
            print("ranks %d: message %r" % (ranks, message.GetValue(0)))
        shortest = min(len(c) for c in g["chains"]) if g["chains"] else 0
        print("ranks %d: %d paths, %d points, %d ends, %d bifurcations, %d loops, shortest "
              "polyline %d points; %s" % (ranks, data.GetNumberOfCells(), data.GetNumberOfPoints(),
                                          g["ends"], len(g["bifurcations"]), g["cycles"],
                                          shortest, stitch))
        if first is not None:
            worst = max(farthest_point_voxels(g["points"], first["points"], 1.0),
                        farthest_point_voxels(first["points"], g["points"], 1.0))
            print("ranks %d: farthest point from the first run's skeleton, both ways: %.3f voxel"
                  % (ranks, worst))
        simple.Disconnect()
        return g
    finally:
        server.stop()


def write_phantom(path, shape):
    """The ClientServer.DistributedExtraction phantom `shape` as a float NRRD at `path`."""
    simple.LoadPlugin(os.environ["VESSELTOUCH_PLUGIN"], remote=False, ns=globals())
    phantom = VesselPhantom(Dimensions=[128, 128, 128], RadiusFraction=0.025,  # noqa: F821
                            Shape=shape)
    write_float_nrrd(path, sm.Fetch(phantom))
    simple.Delete(phantom)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--volume", required=True)
    parser.add_argument("--ranks", type=int, nargs="+", default=[1, 2, 4])
    parser.add_argument("--lower", type=float, default=500.0)
    parser.add_argument("--upper", type=float, default=65535.0)
    parser.add_argument("--seed", type=float, nargs=3, default=None,
                        help="a seed point (world mm): the seeded mode")
    parser.add_argument("--largest-radius", type=float, default=None,
                        help="LargestVesselRadius (mm; ClientServer.DistributedExtraction: 3.2)")
    parser.add_argument("--phantom", type=int, default=None,
                        help="first write the built-in phantom of this Shape to --volume")
    args = parser.parse_args()
    if "VESSELTOUCH_PLUGIN" not in os.environ:
        sys.exit("set VESSELTOUCH_PLUGIN to the plugin's VesselTouch.so")
    if args.phantom is not None:
        write_phantom(args.volume, args.phantom)
    if not os.path.exists(args.volume):
        sys.exit("no volume at %s" % args.volume)
    first = None
    for ranks in args.ranks:
        g = measure(args.volume, ranks, args.lower, args.upper, args.seed, first,
                    args.largest_radius)
        first = g if first is None else first


if __name__ == "__main__":
    main()

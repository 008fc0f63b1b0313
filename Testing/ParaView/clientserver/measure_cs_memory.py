"""Peak memory per pvserver rank of VesselCenterline, 1 rank against N ranks (issue 19, item 2).

    VESSELTOUCH_PLUGIN=<build>/lib/paraview-5.11/plugins/VesselTouch/VesselTouch.so \\
        pvpython Testing/ParaView/clientserver/measure_cs_memory.py --size 384 --ranks 1 2

A tree phantom (radius fraction 0.02) is written as a raw float NRRD; for each rank count a
pvserver starts on 127.0.0.1, reads it (VesselTouch's reader: each rank its own extent) and runs
VesselCenterline (thresholded, LargestVesselRadius the phantom's radius). Printed per rank: the
extent it read, the voxel bytes its reader read, its VmHWM from /proc after the run (the peak
resident set of the process, ParaView's libraries included) and the filter's own getrusage peak.
A measurement, not a test: nothing is asserted.

With ``--raw`` the volume is VesselPhantom's raw angiogram (a random vascular tree with tissue,
clutter, bias and noise) and VesselCenterline runs in the raw seeded mode (one click: the range
estimated from a seed on the root vessel, the network grown from it; LargestVesselRadius the
phantom's largest radius, 4 voxels); the region growth's rounds are printed too.
"""

import argparse
import os
import shutil
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path[:0] = [HERE, os.path.dirname(HERE)]
from vtouch_pvserver import (ParallelServer, rank_processes, status_mib,  # noqa: E402
                             write_float_nrrd)
from vtouch_skeleton_graph import graph  # noqa: E402

from paraview import servermanager as sm  # noqa: E402
from paraview import simple  # noqa: E402


def measure(path, ranks, radius_mm, seed=None):
    server = ParallelServer(ranks=ranks)
    server.start()
    try:
        server.connect(os.environ["VESSELTOUCH_PLUGIN"])
        volume = simple.OpenDataFile(path)
        if seed is None:
            mode = dict(AutomaticIntensityRange=0, LowerThreshold=550.0)
        else:
            mode = dict(AutomaticIntensityRange=1, UseSeedPoint=1, SeedPoint=seed)
        centerline = simple.VesselCenterline(Input=volume, LargestVesselRadius=radius_mm,
                                             DistributedExtraction=1, **mode)
        centerline.UpdatePipeline()
        data = sm.Fetch(centerline)
        ranks_pids = rank_processes(server)
        hwm = [status_mib(ranks_pids[r], "VmHWM") for r in sorted(ranks_pids)]
        fd = data.GetFieldData()

        def values(name):
            a = fd.GetArray(name)
            return None if a is None else [a.GetTuple(i) for i in range(a.GetNumberOfTuples())]
        g = graph(data, 1.0)
        print("ranks %d: %d paths, %d points, %d ends, %d bifurcations, %d loops; VmHWM per rank "
              "(MiB): %s" % (ranks, data.GetNumberOfCells(), data.GetNumberOfPoints(), g["ends"],
                             len(g["bifurcations"]), g["cycles"],
                             ", ".join("%.0f" % h for h in hwm)))
        if seed is not None:
            print("  range %s; growth rounds %s, component rounds %s; message %r"
                  % (values("IntensityRangeUsed"), values("RegionGrowthRounds"),
                     values("RegionComponentRounds"),
                     fd.GetAbstractArray("ExtractionMessage").GetValue(0)
                     if fd.GetAbstractArray("ExtractionMessage") else None))
        if values("PieceInputExtents"):
            for r, (e, b, p) in enumerate(zip(values("PieceInputExtents"),
                                             values("PieceReaderVoxelBytesRead"),
                                             values("PiecePeakResidentKiB"))):
                print("  rank %d read extent %s: %.0f MiB of voxels; its run's peak %.0f MiB"
                      % (r, [int(v) for v in e], b[0] / 2 ** 20, p[0] / 1024.0))
            print("  ghost margin %d voxels; cut ends joined %d, unmatched %d; duplicates removed "
                  "%s, band stubs dropped %s, points dropped %s, bifurcations without branch %s"
                  % (values("GhostMarginVoxels")[0][0], values("StitchCutEndsJoined")[0][0],
                     values("StitchCutEndsUnmatched")[0][0], values("StitchDuplicatesRemoved"),
                     values("StitchBandStubsDropped"), values("StitchPointsDropped"),
                     values("StitchBifurcationsWithoutBranch")))
        simple.Disconnect()
    finally:
        server.stop()


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--size", type=int, default=384)
    parser.add_argument("--ranks", type=int, nargs="+", default=[1, 2])
    parser.add_argument("--raw", action="store_true",
                        help="a raw angiogram phantom and the raw seeded mode")
    args = parser.parse_args()
    folder = tempfile.mkdtemp(prefix="vtouch-cs-memory-")
    try:
        simple.LoadPlugin(os.environ["VESSELTOUCH_PLUGIN"], remote=False, ns=globals())
        n = args.size
        if args.raw:
            phantom = VesselPhantom(Dimensions=[n, n, n], Shape=8,  # noqa: F821
                                    OutputScalarType=10)
            seed = [float(x) for x in sm.Fetch(phantom, idx=1).GetPoint(0)]
            radius = 4.0  # AngiogramLargestRadius
        else:
            phantom = VesselPhantom(Dimensions=[n, n, n], RadiusFraction=0.02)  # noqa: F821
            seed, radius = None, 0.02 * n
        path = os.path.join(folder, "phantom.nrrd")
        write_float_nrrd(path, sm.Fetch(phantom))
        simple.Delete(phantom)
        simple.Disconnect()
        print("%s phantom %d^3 float (%.0f MiB), largest radius %.1f voxels%s"
              % ("raw angiogram" if args.raw else "tree", n, 4.0 * n ** 3 / 2 ** 20, radius,
                 "; seed %s" % seed if seed else ""))
        for ranks in args.ranks:
            measure(path, ranks, radius, seed)
    finally:
        shutil.rmtree(folder, ignore_errors=True)


main()

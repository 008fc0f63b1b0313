"""Peak memory per pvserver rank of VesselCenterline, 1 rank against N ranks (issue 19, item 2).

    VESSELTOUCH_PLUGIN=<build>/lib/paraview-5.11/plugins/VesselTouch/VesselTouch.so \\
        pvpython Testing/ParaView/clientserver/measure_cs_memory.py --size 384 --ranks 1 2

A tree phantom (radius fraction 0.02) is written as a raw float NRRD; for each rank count a
pvserver starts on 127.0.0.1, reads it (VesselTouch's reader: each rank its own extent) and runs
VesselCenterline (thresholded, LargestVesselRadius the phantom's radius). Printed per rank: the
extent it read, the voxel bytes its reader read, its VmHWM from /proc after the run (the peak
resident set of the process, ParaView's libraries included) and the filter's own getrusage peak.
A measurement, not a test: nothing is asserted.
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


def measure(path, ranks, radius_mm):
    server = ParallelServer(ranks=ranks)
    server.start()
    try:
        simple.Connect("127.0.0.1", server.port)
        plugin = os.environ["VESSELTOUCH_PLUGIN"]
        simple.LoadPlugin(plugin, remote=True)
        simple.LoadPlugin(plugin, remote=False)
        volume = simple.OpenDataFile(path)
        centerline = simple.VesselCenterline(Input=volume, AutomaticIntensityRange=0,
                                             LowerThreshold=550.0, LargestVesselRadius=radius_mm,
                                             DistributedExtraction=1)
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
        if values("PieceInputExtents"):
            for r, (e, b, p) in enumerate(zip(values("PieceInputExtents"),
                                             values("PieceReaderVoxelBytesRead"),
                                             values("PiecePeakResidentKiB"))):
                print("  rank %d read extent %s: %.0f MiB of voxels; its run's peak %.0f MiB"
                      % (r, [int(v) for v in e], b[0] / 2 ** 20, p[0] / 1024.0))
            print("  ghost margin %d voxels; cut ends joined %d, unmatched %d; duplicates removed "
                  "%s, points dropped %s, bifurcations without branch %s"
                  % (values("GhostMarginVoxels")[0][0], values("StitchCutEndsJoined")[0][0],
                     values("StitchCutEndsUnmatched")[0][0], values("StitchDuplicatesRemoved"),
                     values("StitchPointsDropped"), values("StitchBifurcationsWithoutBranch")))
        simple.Disconnect()
    finally:
        server.stop()


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--size", type=int, default=384)
    parser.add_argument("--ranks", type=int, nargs="+", default=[1, 2])
    args = parser.parse_args()
    folder = tempfile.mkdtemp(prefix="vtouch-cs-memory-")
    try:
        simple.LoadPlugin(os.environ["VESSELTOUCH_PLUGIN"], remote=False, ns=globals())
        n = args.size
        phantom = VesselPhantom(Dimensions=[n, n, n], RadiusFraction=0.02)  # noqa: F821
        path = os.path.join(folder, "tree.nrrd")
        write_float_nrrd(path, sm.Fetch(phantom))
        simple.Delete(phantom)
        simple.Disconnect()
        print("tree phantom %d^3 float (%.0f MiB), radius %.1f voxels"
              % (n, 4.0 * n ** 3 / 2 ** 20, 0.02 * n))
        for ranks in args.ranks:
            measure(path, ranks, 0.02 * n)
    finally:
        shutil.rmtree(folder, ignore_errors=True)


main()

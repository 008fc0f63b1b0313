"""The server's progress as the client sees it during a long VesselCenterline run on a pvserver
(issue 16 item 6, h18q): when each report arrived, and the longest stretch without one.

    VESSELTOUCH_PLUGIN=<build>/lib/paraview-5.11/plugins/VesselTouch/VesselTouch.so \\
        Testing/Utilities/vtouch-xvfb-run pvpython \\
        Testing/ParaView/clientserver/measure_cs_progress.py --size 128 [--seeded]

The run test_cs_remote_cancel.py cancels (the raw-angiogram VesselPhantom, seed 2, as a float NRRD
read in pieces; Automatic off, from LONG_RUN_LOWER up, full resolution, DistributedExtraction on,
a RemoteCancelToken set so the first rank names its cancel port), not cancelled; with --seeded,
seeded at the phantom's root as the panel test's run. Printed: each report the client's progress
handler fired (seconds into the update, percent, text), the longest silence (the update's start
and end included) and the first rank's stage times from the output's field data (the pieces'
runs, the gather, the stitch). A measurement, not a test: nothing is asserted.
"""

import argparse
import os
import shutil
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path[:0] = [HERE, os.path.dirname(HERE)]
from vtouch_pvserver import ParallelServer, write_float_nrrd  # noqa: E402
from vtouch_testing import plugin_path  # noqa: E402
from test_cs_remote_cancel import LONG  # noqa: E402

from paraview import servermanager as sm  # noqa: E402
from paraview import simple  # noqa: E402


def save_and_hash(data, path):
    """Writes `data` to `path` and prints a SHA-256 of its points, lines and every array's values
    in order (h18s: the same hash before and after a change is the same output to the bit)."""
    import hashlib
    from vtkmodules.util.numpy_support import vtk_to_numpy
    from vtkmodules.vtkIOXML import vtkXMLPolyDataWriter
    writer = vtkXMLPolyDataWriter()
    writer.SetFileName(path)
    writer.SetInputData(data)
    writer.Write()
    digest = hashlib.sha256()
    digest.update(vtk_to_numpy(data.GetPoints().GetData()).tobytes())
    lines = data.GetLines()
    digest.update(vtk_to_numpy(lines.GetOffsetsArray()).tobytes())
    digest.update(vtk_to_numpy(lines.GetConnectivityArray()).tobytes())
    for arrays in (data.GetPointData(), data.GetCellData()):
        for k in range(arrays.GetNumberOfArrays()):
            a = arrays.GetAbstractArray(k)
            if a is not None and hasattr(a, "GetNumberOfComponents") and a.IsNumeric():
                digest.update(a.GetName().encode())
                digest.update(vtk_to_numpy(a).tobytes())
    print("output %s: %d points, %d lines, sha256 %s"
          % (path, data.GetNumberOfPoints(), data.GetNumberOfLines(), digest.hexdigest()))
    fd = data.GetFieldData()
    report = [(fd.GetArrayName(k), fd.GetArray(k).GetComponent(0, 0))
              for k in range(fd.GetNumberOfArrays())
              if (fd.GetArrayName(k) or "").startswith("Stitch") and fd.GetArray(k) is not None]
    print("stitch report %s" % report)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--size", type=int, default=128)
    parser.add_argument("--ranks", type=int, default=2)
    parser.add_argument("--seeded", action="store_true")
    parser.add_argument("--save", help="write the stitched output here (.vtp) and print its hash")
    args = parser.parse_args()
    plugin = plugin_path()
    folder = tempfile.mkdtemp(prefix="vtouch-cs-progress-")
    path = os.path.join(folder, "angio.nrrd")
    simple.LoadPlugin(plugin, remote=False, ns=globals())
    phantom = VesselPhantom(Shape="Raw angiogram", Dimensions=[args.size] * 3, Seed=2)  # noqa: F821
    write_float_nrrd(path, sm.Fetch(phantom))
    root = list(sm.Fetch(phantom, idx=1).GetPoint(0))
    simple.Delete(phantom)
    server = ParallelServer(ranks=args.ranks)
    server.start()
    try:
        server.connect(plugin)
        volume = simple.OpenDataFile(path)
        volume.UpdatePipeline()
        settings = dict(LONG)
        if args.seeded:
            settings.update(UseSeedPoint=1, SeedPoint=root)
        centerline = simple.VesselCenterline(Input=volume, DistributedExtraction=1, **settings)
        centerline.GetProperty("RemoteCancelToken").SetElement(0, "measure")
        centerline.UpdateVTKObjects()
        reports = []
        handler = sm.ActiveConnection.Session.GetProgressHandler()
        tag = handler.AddObserver("ProgressEvent", lambda h, e: reports.append(
            (time.monotonic(), h.GetLastProgress(), h.GetLastProgressText())))
        start = time.monotonic()
        centerline.UpdatePipeline()
        end = time.monotonic()
        handler.RemoveObserver(tag)
        data = sm.Fetch(centerline)
        for t, percent, text in reports:
            print("%8.3f s %3d %% %s" % (t - start, percent, text))
        moments = [start] + [t for t, _, _ in reports] + [end]
        longest = max(b - a for a, b in zip(moments, moments[1:]))
        print("run %.2f s, %d paths, %d reports, the longest silence %.2f s (%.0f %% of the run)"
              % (end - start, data.GetNumberOfLines(), len(reports), longest,
                 100.0 * longest / (end - start)))
        fd = data.GetFieldData()
        for name in ("PieceExtractSeconds", "PieceCodeSeconds", "DistributedGatherSeconds",
                     "DistributedStitchSeconds"):
            a = fd.GetArray(name)
            if a is not None:
                print("%s %s" % (name, [round(a.GetComponent(k, 0), 3)
                                        for k in range(a.GetNumberOfTuples())]))
        if args.save:
            save_and_hash(data, args.save)
        simple.Disconnect()
    finally:
        server.stop()
        shutil.rmtree(folder, ignore_errors=True)


if __name__ == "__main__":
    main()

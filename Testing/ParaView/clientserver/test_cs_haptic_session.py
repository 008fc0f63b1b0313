"""Client/server integration test (issue 19, item 1): the volume and VesselCenterline on a 2-rank
pvserver, the haptic session in the client.

Run as ``pvpython test_cs_haptic_session.py`` with VESSELTOUCH_PLUGIN set, on a display
(vtouch-xvfb-run). First, built in (one process), a VesselPhantom's centerline is extracted as the
reference. Then ``mpiexec -np 2 pvserver`` starts on 127.0.0.1 with a free port
(vtouch_pvserver.ParallelServer: every wait timed out, the process group ended, the port freed),
pvpython connects and loads the plugin on both sides from the same file, and:
- the phantom's volume, saved as .vti, opens on the server in pieces (each rank holds part of the
  tree, whose vessels cross the piece boundary);
- VesselCenterline runs on the server; the skeleton delivered to the client (vesseltouch/
  delivery.py: gathered on rank 0, moved to the client) has the built-in run's paths and, within
  0.1 voxel, its points (each rank codes its piece grown by the ghost margin, which on this
  small tree covers the volume; ClientServer.DistributedExtraction tests pieces that do not);
- vesseltouch.logic() returns a session that lives in the client process only (its proxy's
  location is the client) and binds to that skeleton;
- a scripted trace (simulated device, the hand sweeping path 0, RunOffline) runs in the client:
  its log reaches the tracing state with finite forces below the limit;
- the real-time loop starts on its thread in the client and ticks, then stops;
- after Disconnect the server exits within its time-out and the port is free again;
- connected to a server that did not load the plugin, vesseltouch.ExtractCenterlines refuses with
  the reason and what to do, and the server still answers.
Exits non-zero on any failure.
"""

import os
import shutil
import sys
import tempfile

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path[:0] = [HERE, os.path.dirname(HERE)]  # vtouch_pvserver here, vtouch_testing above
from vtouch_pvserver import run_connected, wait_until  # noqa: E402
from vtouch_testing import Check, plugin_path  # noqa: E402

from paraview import servermanager as sm  # noqa: E402
from paraview import simple  # noqa: E402
from paraview.modules.vtkRemotingCore import vtkPVSession  # noqa: E402
from vtkmodules.util.numpy_support import vtk_to_numpy  # noqa: E402

PLUGIN = plugin_path()
CHECK = Check("client/server haptic session")
check = CHECK.true
PHANTOM = {"Shape": "Tree", "Dimensions": [64, 64, 64]}


def paths(polydata):
    """The polylines as a sorted list of (n, first point, last point) plus all points (N x 3)."""
    points = vtk_to_numpy(polydata.GetPoints().GetData()) if polydata.GetPoints() else np.zeros(
        (0, 3))
    lines = polydata.GetLines()
    ids = vtk_to_numpy(lines.GetConnectivityArray()) if lines.GetNumberOfCells() else []
    offsets = vtk_to_numpy(lines.GetOffsetsArray()) if lines.GetNumberOfCells() else [0]
    summary = []
    for a, b in zip(offsets[:-1], offsets[1:]):
        chain = points[ids[a:b]]
        summary.append((int(b - a), tuple(np.round(chain[0], 3)), tuple(np.round(chain[-1], 3))))
    return sorted(summary), points


def builtin_reference(volume_path):
    """The built-in run's centerline; writes the phantom's volume to `volume_path` (.vti, which
    ParaView's reader reads in pieces: on the server each rank holds a part of the tree)."""
    simple.LoadPlugin(PLUGIN, remote=False, ns=globals())
    phantom = VesselPhantom(**PHANTOM)  # noqa: F821 - from the plugin
    simple.SaveData(volume_path, proxy=phantom)
    centerline = VesselCenterline(Input=phantom)  # noqa: F821
    centerline.UpdatePipeline()
    data = sm.Fetch(centerline)
    spacing = sm.Fetch(phantom).GetSpacing()
    return paths(data), min(spacing)


def compare(reference, delivered, voxel_mm):
    (ref_paths, ref_points), (got_paths, got_points) = reference, delivered
    print("built in: %d paths, %d points; client/server: %d paths, %d points"
          % (len(ref_paths), len(ref_points), len(got_paths), len(got_points)))
    check(len(ref_paths) > 0, "the built-in reference has paths")
    check([n for n, _, _ in got_paths] == [n for n, _, _ in ref_paths],
          "the delivered skeleton has the built-in run's paths (point counts %s vs %s)"
          % ([n for n, _, _ in got_paths], [n for n, _, _ in ref_paths]))
    if len(got_points) and len(ref_points):
        # Every delivered point within 0.1 voxel of a reference point, and back.
        def farthest(a, b):
            d = np.sqrt(((a[:, None, :] - b[None, :, :]) ** 2).sum(axis=2)).min(axis=1)
            return float(d.max())
        worst = max(farthest(got_points, ref_points), farthest(ref_points, got_points))
        print("largest point distance: %.4f voxel" % (worst / voxel_mm))
        check(worst <= 0.1 * voxel_mm, "the delivered skeleton is within 0.1 voxel of the built-in "
              "one (%.3f voxel)" % (worst / voxel_mm))


def remote_session(reference, voxel_mm, volume_path):
    import vesseltouch
    from vesseltouch.delivery import is_remote
    check(is_remote(), "the connection is to a separate pvserver")
    volume = simple.OpenDataFile(volume_path)
    volume.UpdatePipeline()
    pieces = sm.Fetch(volume, 1)  # rank 1's piece of the volume
    whole = volume.GetDataInformation().GetNumberOfPoints()
    check(0 < pieces.GetNumberOfPoints() < whole,
          "the volume is read in pieces across the ranks (rank 1 holds %d of %d voxels)"
          % (pieces.GetNumberOfPoints(), whole))
    centerline = simple.VesselCenterline(Input=volume)
    centerline.UpdatePipeline()
    s = vesseltouch.logic()
    location = s.proxy.SMProxy.GetLocation()
    check(location == vtkPVSession.CLIENT,
          "the session proxy lives in the client only (location %#x)" % location)
    s.Bind(centerline)
    compare(reference, paths(s._delivery.client_copy()), voxel_mm)
    s.SetDevice("simulated")
    s.SetHandSweep(path=0, speed_mm_per_s=40.0)
    s.RunOffline(2.0, rate_Hz=1000.0)
    log = s.GetLog()
    states = log["state"]
    force = log["force"]
    check(states is not None and len(states) >= 1900,
          "the scripted trace logged 2 s at 1 kHz in the client (%s rows)"
          % (None if states is None else len(states)))
    if states is not None and force is not None and len(states):
        check(int((states == 1).sum()) > 0, "the agent traced the vessel (state 1 reached)")
        magnitude = np.sqrt((force ** 2).sum(axis=1))
        check(bool(np.isfinite(magnitude).all()), "every force is finite")
        check(float(magnitude.max()) > 0.0, "the trace felt a force (max %.3f N)"
              % float(magnitude.max()))
    # The real-time loop on its thread, in this process.
    s.SetHandSweep(path=0, speed_mm_per_s=40.0)
    s.Start()
    ticked = wait_until(lambda: s.GetStatistics()["ticks"] > 200, 20.0)
    stats = s.GetStatistics()
    s.Stop()
    check(ticked, "the real-time loop ticked in the client (%d ticks)" % stats["ticks"])
    check(not s.IsRunning(), "the session stopped")


def server_without_plugin():
    """A server that never loaded the plugin (its filters are not defined in this session):
    VesselTouch refuses with the reason and what to do, and the connection stays usable."""
    import vesseltouch
    from vesseltouch.connection import server_has_plugin
    check(not server_has_plugin(), "the server is seen without the VesselTouch plugin")
    volume = simple.Wavelet()  # a source every pvserver has
    volume.UpdatePipeline()
    message = ""
    try:
        vesseltouch.ExtractCenterlines(volume)
    except RuntimeError as e:
        message = str(e)
    print("refusal: %s" % message)
    check("has not loaded the VesselTouch plugin" in message and "remote=True" in message,
          "ExtractCenterlines says the server lacks the plugin and what to do (%r)" % message)
    volume.UpdatePipeline(1.0)  # the server still answers
    check(volume.GetDataInformation().GetNumberOfPoints() > 0,
          "the server still works after the refusal")


def main():
    folder = tempfile.mkdtemp(prefix="vtouch-cs-session-")
    volume_path = os.path.join(folder, "tree.vti")
    reference, voxel_mm = builtin_reference(volume_path)
    simple.Disconnect()
    try:
        run_connected(PLUGIN, check, lambda: remote_session(reference, voxel_mm, volume_path))
        run_connected(PLUGIN, check, server_without_plugin, remote_plugin=False)
    finally:
        shutil.rmtree(folder, ignore_errors=True)
    CHECK.finish()


main()

"""Client/server fault test (issue 19, item 6): the pvserver dies while a haptic session runs in
the client.

Run as ``pvpython test_cs_server_dies.py`` with VESSELTOUCH_PLUGIN set, on a display
(vtouch-xvfb-run). A 2-rank pvserver (vtouch_pvserver.run_connected: free port, every wait timed
out, the process group ended, the port checked free) reads a tree phantom saved as .vti in pieces;
VesselCenterline runs on the server and the skeleton is delivered to the client, where
vesseltouch.logic()'s session runs its real-time loop with the simulated device and the hand
sweeping path 0 until the device feels a force. Then the server's whole process group gets
SIGKILL, and:
- the client notices without calling the server (vesseltouch/connection_watch.py): the session's
  status turns to the connection-lost fault (4) within the wait's time-out, and the fault text
  names the lost server and what to do (reconnect and re-extract, or save);
- the force sent to the device is exactly zero and the loop has stopped;
- the session still holds the skeleton, with the same path and point counts as before;
- Start() refuses while the fault is latched, with the reason;
- this process survives: a scripted offline trace runs on the kept skeleton (it reaches the
  tracing state with finite forces), and SaveSkeleton writes it with the delivered point count;
- the server's processes are gone and its port is free (run_connected, after the body).
Exits non-zero on any failure. Prints how long detection took (not asserted: wall clock).
"""

import math
import os
import shutil
import sys
import tempfile
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path[:0] = [HERE, os.path.dirname(HERE)]  # vtouch_pvserver here, vtouch_testing above
import vtouch_pvserver  # noqa: E402
from vtouch_pvserver import wait_until  # noqa: E402
from vtouch_testing import Check, plugin_path  # noqa: E402

from paraview import servermanager as sm  # noqa: E402
from paraview import simple  # noqa: E402

PLUGIN = plugin_path()
CHECK = Check("client/server: the server dies mid-session")
check = CHECK.true
PHANTOM = {"Shape": "Tree", "Dimensions": [48, 48, 48]}
CONNECTION_LOST_FAULT = 4  # vtkVesselTouchHapticSession::CONNECTION_LOST_FAULT


def write_phantom(volume_path):
    """The tree phantom's volume as .vti (read in pieces by the ranks), built in."""
    simple.LoadPlugin(PLUGIN, remote=False, ns=globals())
    phantom = VesselPhantom(**PHANTOM)  # noqa: F821 - from the plugin
    simple.SaveData(volume_path, proxy=phantom)


def device_force_N(session):
    return [float(x) for x in session._info("DeviceForceInfo")]


def kill_mid_session(server, volume_path, folder):
    import vesseltouch
    volume = simple.OpenDataFile(volume_path)
    centerline = simple.VesselCenterline(Input=volume)
    centerline.UpdatePipeline()
    s = vesseltouch.logic()
    s.Bind(centerline)
    before = s.GetStatus()
    print("before: %d paths, %d points" % (before["paths"], before["points"]))
    check(before["points"] > 0 and not before["connection_lost"],
          "the session holds the delivered skeleton before the fault")

    s.SetDevice("simulated")
    s.SetHandSweep(path=0, speed_mm_per_s=40.0)
    s.Start()
    felt = wait_until(lambda: math.hypot(*device_force_N(s)[:2]) > 0.0, 30.0, step_s=0.01)
    check(felt, "the running session sends a force before the fault (%s N)" % device_force_N(s))
    check(s.IsRunning(), "the loop runs in the client before the fault")

    killed_at = time.monotonic()
    server.kill()  # SIGKILL to mpiexec and both pvserver ranks
    noticed = wait_until(lambda: s.GetStatus()["fault"] == CONNECTION_LOST_FAULT, 10.0,
                         step_s=0.005)
    print("connection loss noticed after %.3f s (poll period 0.02 s)"
          % (time.monotonic() - killed_at))
    check(noticed, "the session reports the lost connection (status %s)" % s.GetStatus())
    after = s.GetStatus()
    text = str(after["fault_text"])
    print("fault text: %s" % text)
    uri = sm.ActiveConnection.GetURI()
    check(uri in text and "pvserver" in text,
          "the fault text names the lost server %s (%r)" % (uri, text))
    check("re-extract" in text and "SaveSkeleton" in text,
          "the fault text says what to do: reconnect and re-extract, or save (%r)" % text)
    check(after["connection_lost"] and not after["running"],
          "the loop stopped on the fault (running %s)" % after["running"])
    check(device_force_N(s) == [0.0, 0.0, 0.0],
          "the force sent to the device is exactly zero (%s)" % device_force_N(s))
    check((after["paths"], after["points"]) == (before["paths"], before["points"]),
          "the skeleton stays held: %d paths, %d points (before %d, %d)"
          % (after["paths"], after["points"], before["paths"], before["points"]))

    refused = ""
    try:
        s.Start()
    except RuntimeError as e:
        refused = str(e)
    check("ClearFault" in refused and not s.IsRunning(),
          "Start refuses while the fault is latched, saying why (%r)" % refused)

    # This process goes on: a scripted offline trace on the kept skeleton.
    s.SetHandSweep(path=0, speed_mm_per_s=40.0)
    log = s.RunOffline(2.0, rate_Hz=1000.0)
    states, force = log["state"], log["force"]
    check(states is not None and len(states) >= 1900,
          "the offline trace ran 2 s at 1 kHz after the fault (%s rows)"
          % (None if states is None else len(states)))
    if states is not None and force is not None and len(states):
        check(int((states == 1).sum()) > 0, "the offline trace reached the tracing state")
        check(bool(np.isfinite(force).all()), "every offline force is finite")
    check(s.GetStatus()["points"] == before["points"],
          "the offline trace used the kept skeleton (%d points)" % s.GetStatus()["points"])
    saved = s.SaveSkeleton(os.path.join(folder, "kept.vtp"))
    from vtkmodules.vtkIOXML import vtkXMLPolyDataReader
    reader = vtkXMLPolyDataReader()
    reader.SetFileName(saved)
    reader.Update()
    check(reader.GetOutput().GetNumberOfPoints() >= before["points"] > 0,
          "SaveSkeleton wrote the kept skeleton (%d points)"
          % reader.GetOutput().GetNumberOfPoints())
    check(wait_until(lambda: not server.is_running(), 10.0), "the killed server's processes ended")


def main():
    folder = tempfile.mkdtemp(prefix="vtouch-cs-dies-")
    volume_path = os.path.join(folder, "tree.vti")
    write_phantom(volume_path)
    simple.Disconnect()
    try:
        vtouch_pvserver.run_connected(
            PLUGIN, check, lambda server: kill_mid_session(server, volume_path, folder),
            pass_server=True)
    finally:
        shutil.rmtree(folder, ignore_errors=True)
    CHECK.finish()


main()

"""GUI test (issue 19, item 6): the pvserver dies while the panel's session runs in the client.

The real ParaView starts on an empty scene; a 2-rank pvserver starts on 127.0.0.1 with a free port
(vtouch_pvserver.ParallelServer). The GUI's Python connects to it, loads the plugin on both sides,
extracts a tree phantom's centerline on the server and starts vesseltouch.logic()'s session in the
client on the delivered skeleton (simulated device, the hand sweeping path 0): the panel shows it
running. Then every server process is killed (SIGKILL) and:
- the panel's status line says the connection to that server was lost, the force is zero and
  where the skeleton was saved; the session is stopped (Start enabled, Stop disabled);
- the skeleton file exists with the skeleton's points (VTK XML PolyData);
- ParaView is still running (nothing crashed). ParaView's own reaction comes later and is not
  the panel's: pqServer notices at its next heartbeat and pqCrashRecoveryBehavior then shows
  "Server disconnected!" and ends the application. DASHBOARD_TEST_FROM_CTEST is removed from
  ParaView's environment so that, should the heartbeat come during the test, that dialog waits
  instead of ending ParaView under the test at once. Screenshots are kept
in <build>/Testing/gui-cs-server-lost. Runs with Debian's python3 under vtouch-xvfb-run.
"""

import glob
import os
import shutil
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path[:0] = [HERE, os.path.join(os.path.dirname(HERE), "clientserver"), os.path.dirname(HERE)]
from gui_driver import GuiDriver  # noqa: E402
from vtouch_pvserver import ParallelServer, port_is_free, wait_until  # noqa: E402
from vtouch_testing import Check  # noqa: E402

CHECK = Check('GUI server lost')
check = CHECK.true


SESSION = """
from paraview.simple import *
Connect('127.0.0.1', %(port)d)
LoadPlugin(%(plugin)r, remote=True)
LoadPlugin(%(plugin)r, remote=False)
import vesseltouch
phantom = VesselPhantom(registrationName="Phantom", Shape="Tree", Dimensions=[48, 48, 48])
centerline = VesselCenterline(registrationName="Centerline", Input=phantom)
centerline.UpdatePipeline()
s = vesseltouch.logic()
s.Bind(centerline)
s.SetDevice("simulated")
s.SetHandSweep(path=0, speed_mm_per_s=40.0)
s.Start()
"""


def label(state, name):
    return state.get("widgets", {}).get(name, {}).get("text", "")


def main():
    temp = tempfile.mkdtemp(prefix="vesseltouch-gui-lost-tmp-")
    os.environ.pop("DASHBOARD_TEST_FROM_CTEST", None)  # let ParaView show its dialog
    server = ParallelServer(ranks=2)
    server.start()
    port = server.port
    gui = GuiDriver("gui-cs-server-lost", "empty", check, extra_env={"TMPDIR": temp})
    try:
        if not gui.wait_for_scene():
            return
        gui.python(SESSION % {"port": port, "plugin": os.environ["VESSELTOUCH_PLUGIN"]})
        running = gui.wait_until(
            lambda s: label(s, "sessionStateLabel").startswith("Running"), seconds=60)
        check(running, "the panel shows the session running in the client (%r)"
              % label(gui.state, "sessionStateLabel"))
        gui.screenshot(os.path.join(gui.work, "before_the_loss.png"))

        gui.check_no_unregistered_input()  # the session bound to the delivered copy
        server.kill()
        said = gui.wait_until(lambda s: "was lost" in label(s, "errorLabel"), seconds=30)
        text = label(gui.state, "errorLabel")
        print("status line: %r" % text)
        gui.screenshot(os.path.join(gui.work, "server_lost.png"))
        check(said, "the panel's status line says the connection was lost (%r)" % text)
        check("127.0.0.1:%d" % port in text, "it names the lost server (%r)" % text)
        check("force is zero" in text and "re-extract" in text,
              "it says the force is zero and what to do (%r)" % text)
        fault = gui.widget("faultLabel")
        check("visible" in fault, "the device section's fault line is in the panel's report")
        check(not fault.get("visible", True) or "Device fault" not in fault.get("text", ""),
              "the device section does not call a lost server a device fault (%r)"
              % fault.get("text", ""))
        check(not gui.widget("stopButton").get("enabled", True)
              and gui.widget("startButton").get("enabled", False),
              "the session stopped (Start enabled, Stop disabled)")
        saved = glob.glob(os.path.join(temp, "vesseltouch-skeleton-*.vtp"))
        check(len(saved) == 1, "the skeleton was saved to the temporary folder (%s)" % saved)
        if saved:
            content = open(saved[0], "rb").read()
            check(b"<PolyData" in content and b'NumberOfPoints="0"' not in content,
                  "the saved file is a VTK polydata with points")
            check(saved[0] in text, "the status line says where the skeleton is (%r)" % text)

        check(gui.alive(), "ParaView is still running after the loss (nothing crashed)")
    finally:
        gui.finish()
        code = server.stop()
        check(code is not None, "the server's processes ended")
        check(wait_until(lambda: port_is_free(port), 10.0), "port %d is free again" % port)
        shutil.rmtree(temp, ignore_errors=True)  # the saved skeleton and Open MPI's session files


main()
CHECK.finish()

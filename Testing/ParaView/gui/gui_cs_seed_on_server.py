"""GUI test (issue 19, item 1, in part): a seed picked by a click on the MIP of a volume held by a
2-rank pvserver resolves on the server, then Extract runs there.

The real ParaView starts on an empty scene; a 2-rank pvserver starts on 127.0.0.1 with a free port
(vtouch_pvserver.ParallelServer). The GUI's Python saves a tree phantom as .vti (built in),
connects, loads the plugin on both sides and opens the .vti on the server (read in pieces by the
ranks), shown as a MIP rendered on the server (remote rendering forced). Then, as a user would:
Pick seed, a click on the brightest pixel of the MIP (xdotool through the real X server). None of
the voxels are in the client, so the seed picker probes the click's ray on the server
(pqVesselTouchRemoteRayProbe: ParaView's ProbeLine on the ranks, the samples moved to the client)
and takes the brightest sample's voxel:
- the seed is set (not "No seed"), its value lies in the vessel range the panel chose from the
  data (not background), and no "background" complaint;
- Extract then runs VesselCenterline on the server from that seed and reports centerline paths;
- Start runs the session in the client on the delivered skeleton: it traces, and the agent cone
  shows over the MIP, which is still rendered on the server (RemoteRenderThreshold 0: the view
  reports distributed rendering).
Screenshots in <build>/Testing/gui-cs-seed. Runs with Debian's python3 under vtouch-xvfb-run.
"""

import os
import re
import shutil
import sys
import tempfile

import numpy
from PIL import Image

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path[:0] = [HERE, os.path.join(os.path.dirname(HERE), "clientserver"), os.path.dirname(HERE)]
from gui_driver import GuiDriver  # noqa: E402
from vtouch_pvserver import ParallelServer, port_is_free, wait_until  # noqa: E402
from vtouch_testing import Check  # noqa: E402

CHECK = Check('GUI seed picked on a server volume')
check = CHECK.true


SCENE = """
from paraview.simple import *
import vesseltouch
phantom = VesselPhantom(Shape="Tree", Dimensions=[64, 64, 64])  # built in, before Connect
SaveData(%(vti)r, proxy=phantom)
Delete(phantom)
Connect('127.0.0.1', %(port)d)
LoadPlugin(%(plugin)r, remote=True)
LoadPlugin(%(plugin)r, remote=False)
volume = XMLImageDataReader(registrationName="Volume", FileName=[%(vti)r])
volume.UpdatePipeline()
GetSettingsProxy("RenderViewSettings").RemoteRenderThreshold = 0.0  # render on the server
view = GetActiveViewOrCreate("RenderView")
vesseltouch.ShowAsMIP(volume, view)
view.OrientationAxesVisibility = 0
SetActiveSource(volume)
Render(view)
"""

REMOTE = """
from paraview.simple import *
view = GetActiveView()
Render(view)
with open(%(path)r, "w") as f:
    f.write(str(int(view.GetClientSideObject().GetUseDistributedRenderingForRender())))
"""


def brightest(png):
    """The brightest pixel of the view capture (a vessel of the MIP), as (row, column)."""
    grey = numpy.asarray(Image.open(png).convert("RGB")).astype(int).sum(axis=2)
    return numpy.unravel_index(numpy.argmax(grey), grey.shape), grey.shape


def agent_pixels(png):
    """Strongly coloured pixels that are not the centerlines' orange or the seed's cyan: the
    agent's cone and its force arrow (as gui_extract_workflow counts them)."""
    rgb = numpy.asarray(Image.open(png).convert("RGB")).astype(int)
    r, g, b = rgb[..., 0], rgb[..., 1], rgb[..., 2]
    orange = (r > 170) & (g > 80) & (g < 200) & (b < 90) & (r - g > 40)
    cyan = (r < 60) & (g > 60) & (b > 60) & (numpy.abs(g - b) < 40)
    saturated = rgb.max(axis=2) - rgb.min(axis=2) > 80
    return int(numpy.count_nonzero(saturated & ~orange & ~cyan))


def click_view(gui, pixel, image_shape):
    rect = gui.state["view_rect"]
    x = rect[0] + int(round(pixel[1] * rect[2] / image_shape[1]))
    y = rect[1] + int(round(pixel[0] * rect[3] / image_shape[0]))
    gui.xdotool("mousemove", x, y)
    gui.xdotool("click", 1)


def main():
    folder = tempfile.mkdtemp(prefix="vesseltouch-gui-cs-seed-")
    server = ParallelServer(ranks=2)
    server.start()
    port = server.port
    gui = GuiDriver("gui-cs-seed", "empty", check)
    try:
        if not gui.wait_for_scene():
            return
        gui.python(SCENE % {"port": port, "plugin": os.environ["VESSELTOUCH_PLUGIN"],
                            "vti": os.path.join(folder, "tree.vti")})
        chosen = gui.wait_until(
            lambda s: s["widgets"].get("volumeCombo", {}).get("text") == "Volume", seconds=60)
        check(chosen, "the panel offers the server's volume (%r)" % gui.widget("volumeCombo"))
        gui.run("select", "Volume")
        gui.wait_until(lambda s: s["widgets"].get("upperThreshold", {}).get("value", 0) > 0,
                       seconds=30)
        lower = gui.widget("lowerThreshold").get("value")
        mip = gui.capture("mip_on_server.png")
        if not check(mip is not None, "the server's MIP is captured"):
            return
        pixel, shape = brightest(mip)
        flag = os.path.join(folder, "distributed.txt")
        gui.python(REMOTE % {"path": flag})
        distributed = open(flag).read().strip() if os.path.exists(flag) else "?"
        check(distributed == "1", "the MIP is rendered on the server ranks and composited "
                                  "(distributed rendering: %s)" % distributed)

        gui.run("click", "pickSeedButton")
        click_view(gui, pixel, shape)
        gui.wait_until(lambda s: not s["widgets"]["pickSeedButton"]["checked"], seconds=30)
        seed = gui.widget("seedLabel").get("text", "")
        message = gui.widget("extractMessage").get("text", "")
        print("seed: %r, lower bound of the vessel range %s, message %r" % (seed, lower, message))
        match = re.search(r"value ([-0-9.e+]+)", seed)
        check(match is not None, "the click on the MIP set a seed from the server (%r; %r)"
              % (seed, message))
        if match:
            check(float(match.group(1)) >= float(lower),
                  "the seed's value %s lies in the vessel range (lower bound %s): the brightest "
                  "voxel along the ray, not background" % (match.group(1), lower))
        check("background" not in message, "the seed is not called background (%r)" % message)
        gui.capture("seed_on_server.png")

        check(gui.click_and_wait("extractButton", seconds=180), "Extract ends")
        text = gui.widget("extractMessage").get("text", "")
        print("extract: %r" % text)
        check("centerline path" in text, "Extract from that seed reports paths (%r)" % text)
        after = gui.capture("after_extract.png")
        gui.screenshot(os.path.join(gui.work, "screen_after_extract.png"))

        # Start in the client on the delivered skeleton: the agent over the server's MIP.
        gui.run("click", "startButton")
        check(gui.wait_until(lambda s: s["session"]["running"], seconds=20),
              "Start runs the session in the client")
        check(gui.wait_until(lambda s: s["actions"]["actionVesselTouchShowAgent"]["checked"]),
              "the agent is drawn while the session runs")
        traced = gui.wait_until(
            lambda s: gui.widget("sessionStateLabel").get("text", "").startswith(
                "Running: tracing"), seconds=30)
        gui.python(REMOTE % {"path": flag})
        distributed = open(flag).read().strip() if os.path.exists(flag) else "?"
        check(distributed == "1", "still rendered on the server while tracing (%s)" % distributed)
        cone = gui.capture("agent_over_remote_mip.png")
        gui.screenshot(os.path.join(gui.work, "screen_tracing.png"))
        count = agent_pixels(cone) if cone else -1
        print("agent pixels while running: %d (after Extract: %d); traced: %s"
              % (count, agent_pixels(after) if after else -1, traced))
        check(count > 20, "the agent cone shows over the server's MIP (%d pixels)" % count)
        gui.run("click", "stopButton")
        gui.check_no_unregistered_input()
    finally:
        gui.finish()
        code = server.stop()
        check(code is not None, "the server exited")
        check(wait_until(lambda: port_is_free(port), 10.0), "port %d is free again" % port)
        shutil.rmtree(folder, ignore_errors=True)


main()
CHECK.finish()

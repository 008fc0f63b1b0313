"""GUI test: the clinician's centerline workflow in the real ParaView, like a user would run it.

Scene: the phantom tree as a MIP, a 2D wavelet image ("Flat") and a PNG ("Png") opened by
ParaView's reader. Checks (issue 20 items 4, 7, 8, 9):
- 2D inputs are not offered as volumes; selecting one says why beside the chooser, and the MIP
  action is disabled with that reason in its tooltip;
- Extract with no seed says "pick a seed first" beside Extract (not under Start);
- a seed clicked on background (the darkest spot of the volume in the view) is reported;
- a seed clicked on the brightest vessel in the view, then Extract: the centerlines appear in the
  view at once, in a colour that is not grey (the pixels of ParaView's own capture), the used
  intensity range is shown and lies inside the data's range, the progress bar is full;
- the picked seed is marked in the view; Clear removes the seed and its marker;
- Start then Stop: no agent cone left in the view;
- a failing Extract (the range set above the seed's value, Automatic off): a message beside
  Extract, the progress bar back to 0, and no centerline pixels left in the view.
"""

import os
import sys

import numpy
from PIL import Image

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from gui_driver import run_test  # noqa: E402
from gui_pixels import cyan_pixels as seed_pixels  # noqa: E402
from gui_pixels import orange_pixels as coloured_pixels  # noqa: E402


def agent_pixels(png):
    """Strongly coloured pixels that are not the centerlines' orange or the seed's cyan: the
    agent's cone and its force arrow."""
    rgb = numpy.asarray(Image.open(png).convert("RGB")).astype(int)
    r, g, b = rgb[..., 0], rgb[..., 1], rgb[..., 2]
    orange = (r > 170) & (g > 80) & (g < 200) & (b < 90) & (r - g > 40)
    cyan = (r < 60) & (g > 60) & (b > 60) & (numpy.abs(g - b) < 40)  # the seed's marker
    saturated = rgb.max(axis=2) - rgb.min(axis=2) > 80
    return int(numpy.count_nonzero(saturated & ~orange & ~cyan))


def brightest_and_darkest(png):
    """The brightest pixel of the volume's footprint (a vessel), and a pixel near the footprint's
    top-left corner (the tree's branches do not reach it: background), as (row, column)."""
    rgb = numpy.asarray(Image.open(png).convert("RGB")).astype(int)
    grey = rgb.sum(axis=2)
    background = grey[2, 2]
    # The volume's projection: its background voxels show faintly over the view's background.
    rows, cols = numpy.nonzero(numpy.abs(grey - background) > 2)
    r0, r1, c0, c1 = rows.min(), rows.max(), cols.min(), cols.max()
    window = grey[r0:r1, c0:c1]
    bright = numpy.unravel_index(numpy.argmax(window), window.shape)
    dark = (r0 + (r1 - r0) // 12, c0 + (c1 - c0) // 12)
    return (bright[0] + r0, bright[1] + c0), dark


def click_view(gui, pixel, image_shape):
    """Clicks the view at an image pixel (row, column) of a capture of the whole view."""
    rect = gui.state["view_rect"]
    x = rect[0] + int(round(pixel[1] * rect[2] / image_shape[1]))
    y = rect[1] + int(round(pixel[0] * rect[3] / image_shape[0]))
    gui.xdotool("mousemove", x, y)
    gui.xdotool("click", 1)


def body(gui, check):
    gui.run("state")
    items = gui.widget("volumeCombo").get("items")
    check(items == ["Phantom"], "only the 3D volume is offered (%r)" % items)

    # 2D inputs: refused with the reason beside the chooser and on the MIP action.
    for name in ("Flat", "Png"):
        gui.run("select", name)
        message = gui.widget("volumeMessage")
        check(message.get("visible") and "2D image" in message.get("text", ""),
              "selecting %s says it is a 2D image (%r)" % (name, message.get("text")))
        mip = gui.state["actions"].get("actionVesselTouchShowMIP", {})
        check(mip.get("enabled") is False and "2D" in mip.get("tooltip", ""),
              "the MIP action is disabled for %s, with why (%r)" % (name, mip))
        reply = gui.command("trigger", "actionVesselTouchShowMIP")
        check(reply is not None and not reply["ok"], "the MIP action cannot run on %s" % name)
    gui.run("select", "Phantom")
    check(not gui.widget("volumeMessage").get("visible"), "no complaint about the 3D volume")
    mip = gui.state["actions"].get("actionVesselTouchShowMIP", {})
    check(mip.get("enabled") is True, "the MIP action is enabled on the volume")

    # The range fields are bounded by the data's range, with a default from its upper tail.
    lower, upper = gui.widget("lowerThreshold"), gui.widget("upperThreshold")
    check(lower.get("minimum") < lower.get("value") < upper.get("value") <= upper.get("maximum"),
          "the default range lies inside the data's (%r, %r)" % (lower, upper))

    # Extract with no seed: the reason beside Extract, nothing under Start.
    gui.run("click", "extractButton")
    text = gui.widget("extractMessage").get("text", "")
    check("seed first" in text, "Extract with no seed asks for one beside Extract (%r)" % text)
    check(gui.widget("errorLabel").get("text", "") == "", "nothing shown under Start")

    before = gui.capture("before.png")
    shape = numpy.asarray(Image.open(before)).shape
    bright, dark = brightest_and_darkest(before)

    # A seed on background is reported.
    gui.run("click", "pickSeedButton")
    click_view(gui, dark, shape)
    gui.wait_until(lambda s: not s["widgets"]["pickSeedButton"]["checked"], seconds=5)
    text = gui.widget("extractMessage").get("text", "")
    check("background" in text, "a seed on background is reported (%r, seed %r)"
          % (text, gui.widget("seedLabel").get("text")))

    # A seed on the brightest vessel, then Extract: the view shows the centerlines at once.
    gui.run("click", "pickSeedButton")
    click_view(gui, bright, shape)
    gui.wait_until(lambda s: not s["widgets"]["pickSeedButton"]["checked"], seconds=5)
    check("background" not in gui.widget("extractMessage").get("text", ""),
          "a seed on the vessel is not called background (%r)" % gui.widget("extractMessage"))
    marked = gui.capture("seed_marker.png")
    count = seed_pixels(marked) if marked else 0
    check(count > 10, "the seed is marked in the view (%d pixels)" % count)
    check(gui.click_and_wait("extractButton"), "Extract ends")
    text = gui.widget("extractMessage").get("text", "")
    check("centerline path" in text, "Extract reports the paths beside it (%r)" % text)
    check(gui.widget("extractProgress").get("value") == 100, "progress is full after success")
    after = gui.capture("after_extract.png")
    count = coloured_pixels(after) if after else 0
    print("centerline pixels after Extract: %d (before: %d)" % (count, coloured_pixels(before)))
    check(count > 150, "the centerlines are drawn in colour at once (%d pixels)" % count)
    lower, upper = gui.widget("lowerThreshold"), gui.widget("upperThreshold")
    check(lower["minimum"] <= lower["value"] <= upper["value"] <= upper["maximum"],
          "the range used lies in the data's range (%r, %r)" % (lower, upper))
    gui.screenshot(os.path.join(gui.work, "screen_after_extract.png"))

    # Start on the extracted centerlines, then Stop: the agent goes with the session.
    gui.run("click", "startButton")
    check(gui.wait_until(lambda s: s["session"]["running"], seconds=10), "Start runs the session")
    check(gui.wait_until(lambda s: s["actions"]["actionVesselTouchShowAgent"]["checked"]),
          "the agent is drawn while the session runs")
    gui.run("click", "stopButton")
    check(gui.wait_until(lambda s: not s["session"]["running"], seconds=10), "Stop stops it")
    check(gui.wait_until(lambda s: not s["actions"]["actionVesselTouchShowAgent"]["checked"]),
          "the agent display is switched off after Stop")
    stopped = gui.capture("after_stop.png")
    count = agent_pixels(stopped) if stopped else -1
    check(count == 0, "no cone or force arrow left in the view after Stop (%d pixels)" % count)

    # A failing Extract: the range above every voxel of the vessel.
    gui.run("check", "automaticRange", 0)
    gui.run("set", "lowerThreshold", upper["maximum"])
    gui.run("set", "upperThreshold", upper["maximum"])
    check(gui.click_and_wait("extractButton"), "the failing Extract ends")
    message = gui.widget("extractMessage")
    check(message.get("visible") and "centerline path" not in message.get("text", ""),
          "a failed Extract says why beside Extract (%r)" % message.get("text"))
    check(gui.widget("extractProgress").get("value") == 0,
          "the progress bar is not full after a failure (%r)" % gui.widget("extractProgress"))
    failed = gui.capture("after_failed_extract.png")
    count = coloured_pixels(failed) if failed else -1
    check(count == 0, "no stale centerline left in the view after a failed Extract (%d)" % count)

    # Clear forgets the seed and its marker.
    gui.run("click", "clearSeedButton")
    check(gui.widget("seedLabel").get("text") == "No seed", "Clear forgets the seed")
    cleared = gui.capture("seed_cleared.png")
    count = seed_pixels(cleared) if cleared else -1
    check(count == 0, "no seed marker after Clear (%d pixels)" % count)


def main():
    work_png = os.path.join(os.environ.get("TMPDIR", "/tmp"), "vesseltouch-flat-%d.png" % os.getpid())
    Image.fromarray(numpy.tile(numpy.arange(64, dtype=numpy.uint8) * 4, (64, 1))).convert(
        "RGB").save(work_png)
    try:
        run_test("gui_extract_workflow", "volume+2d", body, {"VESSELTOUCH_SCENE_PNG": work_png})
    finally:
        os.remove(work_png)


main()

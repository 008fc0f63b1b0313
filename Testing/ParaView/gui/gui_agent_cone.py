"""GUI test: the C++ agent display in the real ParaView, under Xvfb (vtouch-xvfb-run).

ParaView starts with the plugin and gui_agent_cone_scene.py (the helix as a MIP, the haptic session
with the simulated device and a hand sweep, started); VESSELTOUCH_GUI_AGENT=1 checks the toolbar's
"Agent" action, so pqVesselTouchAgentDisplay draws the agent. The display reports (JSON, twice a
second) its counters, the agent's state and display position and where the view is on the screen.

Checks: the display runs bound to the session; the agent reaches the tracing state; agent-only
(cached) frames are drawn and the volume is not re-rendered for each of them; a screenshot of the
root window, cropped to the render view, shows red pixels next to blue ones (the cone and its blue
base) on or next to bright MIP (vessel) pixels, near the reported agent position; a camera drag is
pushed to the session and re-renders the MIP, and agent-only frames resume. Runs with Debian's
python3 (NumPy, matplotlib).
"""

import json
import os
import sys
import time

import matplotlib.image
import numpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from gui_agent_common import ParaViewRun  # noqa: E402

failures = []


def check(condition, message):
    if not condition:
        failures.append(message)
        print("FAIL: " + message, flush=True)
    return condition


def masks(image):
    """Red (cone sides), blue (cone base) and bright grey (MIP vessel) pixel masks."""
    rgb = image[..., :3].astype(int)
    r, g, b = rgb[..., 0], rgb[..., 1], rgb[..., 2]
    red = (r > 110) & (r > 2 * g + 20) & (r > 2 * b + 20)
    blue = (b > 110) & (b > 2 * r + 20) & (b > 2 * g + 10)
    grey = (r > 90) & (abs(r - g) < 25) & (abs(g - b) < 25)
    return red, blue, grey


def dilate(mask, radius):
    out = numpy.zeros_like(mask)
    h, w = mask.shape
    for dy in range(-radius, radius + 1):
        for dx in range(-radius, radius + 1):
            ys = slice(max(dy, 0), h + min(dy, 0))
            yd = slice(max(-dy, 0), h + min(-dy, 0))
            xs = slice(max(dx, 0), w + min(dx, 0))
            xd = slice(max(-dx, 0), w + min(-dx, 0))
            out[yd, xd] |= mask[ys, xs]
    return out


def analyse(png, report):
    """(ok, text): red next to blue, on/near bright vessel pixels, near the reported agent."""
    image = matplotlib.image.imread(png)
    if image.dtype != numpy.uint8:
        image = (image * 255.0).round().astype(numpy.uint8)
    ratio = report.get("device_pixel_ratio", 1.0)
    x0, y0 = int(report["view_screen_x"] * ratio), int(report["view_screen_y"] * ratio)
    w, h = int(report["view_width"] * ratio), int(report["view_height"] * ratio)
    view = image[y0:y0 + h, x0:x0 + w]
    red, blue, grey = masks(view)
    touching = red & dilate(blue, 2)  # red pixels adjacent to blue ones: the cone and its base
    if touching.sum() < 3:
        return False, "red pixels next to blue: %d (red %d, blue %d)" % (
            touching.sum(), red.sum(), blue.sum())
    rows, cols = numpy.nonzero(touching)
    row, col = float(rows.mean()), float(cols.mean())
    near = grey & dilate(touching, 12)
    agent_col, agent_row = report["agent_x_px"], h - 1 - report["agent_y_px"]
    distance = ((row - agent_row) ** 2 + (col - agent_col) ** 2) ** 0.5
    text = ("red-blue pixels %d at (%.0f, %.0f), bright vessel pixels within 12 px: %d, "
            "reported agent at (%.0f, %.0f), %.1f px away" % (
                touching.sum(), col, row, near.sum(), agent_col, agent_row, distance))
    return near.sum() >= 3 and distance < 60.0, text


run = ParaViewRun("gui_agent", {"VESSELTOUCH_GUI_AGENT": "1"}, check)
best = first = before = dragged = final = None
try:
    if run.wait_for_scene():
        run.dismiss_dialogs()
        # Screenshots while the agent traces, until one shows the cone's base (the helix runs
        # away from the viewer on half of each turn).
        attempts = 0
        deadline = time.time() + 60
        while time.time() < deadline and attempts < 20 and run.app.poll() is None:
            time.sleep(1.0)
            report = run.report()
            if report is None or report.get("state") != 1:
                continue
            first = first or report
            attempts += 1
            run.xdotool("key", "Escape")  # any stray dialog
            png = run.screenshot("window_%02d.png" % attempts)
            if png is None:
                continue
            ok, text = analyse(png, report)
            print("screenshot %d: %s" % (attempts, text), flush=True)
            if ok:
                best = (png, text, report)
                break
        # A camera drag in the view: the camera goes to the session, the MIP is rendered again
        # and agent-only frames resume over the new image.
        before = run.report()
        if before is not None and run.app.poll() is None:
            x = before["view_screen_x"] + before["view_width"] // 2
            y = before["view_screen_y"] + before["view_height"] // 2
            for step in (("mousemove", x, y), ("mousedown", 1), ("mousemove", x + 20, y + 5),
                         ("mousemove", x + 40, y + 10), ("mouseup", 1)):
                run.xdotool(*step)
                time.sleep(0.2)
            # No fixed wait: the report (written about twice a second) shows the pushed camera,
            # the MIP rendered again and agent-only frames over it, within a minute.
            dragged = run.wait_for_report(
                lambda r: (r["camera_pushes"] > before["camera_pushes"]
                           and r["full_renders"] > before["full_renders"]
                           and r["cached_frames"] > before["cached_frames"]), seconds=60)
            dragged = dragged or run.report()
        final = run.report()
finally:
    artifacts = run.finish()

check(final is not None, "the agent display wrote its report")
if final is not None:
    print("agent display: %s" % json.dumps(final, sort_keys=True))
    check(final.get("enabled") is True, "the agent display is enabled")
    check(final.get("session") is True, "the agent display is bound to the session")
    check(final.get("camera_pushes", 0) >= 1, "the view's camera was pushed to the session")
    check(first is not None, "the agent reached the tracing state")
    full, cached = final.get("full_renders", 0), final.get("cached_frames", 0)
    check(full >= 1, "the MIP was rendered and captured (%d)" % full)
    check(cached >= 10, "agent-only frames were drawn over the cached MIP (%d)" % cached)
    check(cached >= 5 * full, "the volume was not re-rendered per agent frame (%d full, %d cached)"
          % (full, cached))
    print("frame times: agent-only %.1f ms (mean), full scene render %.1f ms (last)"
          % (final.get("cached_frame_ms_mean", 0.0), final.get("full_scene_render_ms_last", 0.0)))
check(best is not None, "a screenshot shows the red cone with its blue base on a vessel")
check(before is not None and dragged is not None, "reports before and after a camera drag")
if before is not None and dragged is not None:
    check(dragged["camera_pushes"] > before["camera_pushes"],
          "the dragged camera was pushed to the session (%d -> %d)"
          % (before["camera_pushes"], dragged["camera_pushes"]))
    check(dragged["full_renders"] > before["full_renders"],
          "the MIP was rendered again after the drag (%d -> %d)"
          % (before["full_renders"], dragged["full_renders"]))
    check(dragged["cached_frames"] > before["cached_frames"],
          "agent-only frames resumed after the drag (%d -> %d)"
          % (before["cached_frames"], dragged["cached_frames"]))

if failures:
    print("GUI agent test: %d failure(s); artifacts in %s" % (len(failures), artifacts))
    sys.exit(1)
print("GUI agent test passed (%s); artifacts in %s" % (best[1], artifacts))

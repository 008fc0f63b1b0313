"""GUI test: the mouse as the haptic session's pointer device, in the real ParaView under Xvfb.

ParaView starts with the plugin and gui_agent_cone_scene.py with VESSELTOUCH_SCENE_DEVICE=pointer
(the helix as a MIP, the session on its centerline with the POINTER device, started);
VESSELTOUCH_GUI_TRACE_MOUSE=1 checks the toolbar's "Trace with mouse" and VESSELTOUCH_GUI_AGENT=1
its "Agent" (whose JSON report gives the session's cursor and where the view is on the screen).

Checks, moving the real X pointer with xdotool: moving right and up over the view moves the
session's cursor right and up (pixels, bottom-left origin) by about as much (pseudo-haptic gain in
[0.2, 2]); a left drag while tracing does not rotate the camera (no camera push); a click leaves
the session running. Runs with Debian's python3.
"""

import json
import os
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from gui_agent_common import ParaViewRun  # noqa: E402

failures = []


def check(condition, message):
    if not condition:
        failures.append(message)
        print("FAIL: " + message, flush=True)
    return condition


def settled_report(run, after, seconds=30):
    """The first report, among those written after report number ``after``, that shows the
    session's cursor where the one before it showed it: ParaView has handled the pointer events
    sent before ``after`` was read (a report is written from its event loop, which reads the X
    events too) and the haptic loop has moved the cursor. The agent display writes a report about
    twice a second when the machine is idle, much less often under load: waiting a fixed time
    read a report older than the moves (the test's flakiness)."""
    deadline = time.time() + seconds
    previous = None
    while time.time() < deadline:
        report = run.report()
        if report is not None and report.get("sequence", 0) > after + 1:
            cursor = (report["cursor_x_px"], report["cursor_y_px"])
            if (previous is not None and report["sequence"] > previous["sequence"] and
                    cursor == (previous["cursor_x_px"], previous["cursor_y_px"])):
                return report
            if previous is None or report["sequence"] > previous["sequence"]:
                previous = report
        time.sleep(0.1)
    check(False, "no settled report within %d s (last %r)" % (seconds, previous))
    return previous or run.report() or {}


def cursor_after(run, *steps):
    for step in steps:
        run.xdotool(*step)
        time.sleep(0.15)
    # xdotool returns once the X server has the event; a report numbered past the one current
    # now was written after ParaView read it.
    current = run.report() or {}
    report = settled_report(run, current.get("sequence", 0))
    return report, (report.get("cursor_x_px", 0.0), report.get("cursor_y_px", 0.0))


run = ParaViewRun("gui_pointer", {"VESSELTOUCH_GUI_AGENT": "1", "VESSELTOUCH_GUI_TRACE_MOUSE": "1",
                                  "VESSELTOUCH_SCENE_DEVICE": "pointer"}, check)
moves = {}
try:
    if run.wait_for_scene():
        run.dismiss_dialogs()
        ready = run.wait_for_report(lambda r: r.get("running") and r.get("device_type") == 1
                                    and "view_screen_x" in r)
        if check(ready is not None, "the session runs the pointer device"):
            x = ready["view_screen_x"] + ready["view_width"] // 2
            y = ready["view_screen_y"] + ready["view_height"] // 2
            # The session's cursor moves by mouse *motion* (it starts at the centre of the
            # viewport the session had at Start, which may since have shrunk: the cursor then
            # sits on the right edge): first 60 px left, so that it is well inside.
            start, c0 = cursor_after(run, *[("mousemove", x - d, y) for d in (0, 20, 40, 60)])
            x -= 60
            right, c1 = cursor_after(run, *[("mousemove", x + d, y) for d in (10, 20, 30, 40)])
            up, c2 = cursor_after(run, *[("mousemove", x + 40, y - d) for d in (10, 20, 30, 40)])
            moves = {"start": c0, "right": c1, "up": c2}
            print("session cursor (px): %s" % json.dumps(moves), flush=True)
            check(8.0 <= c1[0] - c0[0] <= 80.0 and abs(c1[1] - c0[1]) <= 12.0,
                  "40 px right moves the cursor right: %.1f, %.1f" % (c1[0] - c0[0], c1[1] - c0[1]))
            check(8.0 <= c2[1] - c1[1] <= 80.0 and abs(c2[0] - c1[0]) <= 12.0,
                  "40 px up moves the cursor up: %.1f, %.1f" % (c2[0] - c1[0], c2[1] - c1[1]))
            # A left drag while tracing is the pointer's, not the camera's.
            dragged, _ = cursor_after(run, ("mousedown", 1), ("mousemove", x + 10, y - 30),
                                      ("mousemove", x - 20, y - 20), ("mouseup", 1))
            check(dragged["camera_pushes"] == up["camera_pushes"],
                  "a left drag while tracing leaves the camera alone (%d -> %d pushes)"
                  % (up["camera_pushes"], dragged["camera_pushes"]))
            clicked, _ = cursor_after(run, ("click", 1))
            check(clicked.get("running") is True, "the session still runs after a click")
finally:
    artifacts = run.finish()

if failures:
    print("GUI pointer test: %d failure(s); artifacts in %s" % (len(failures), artifacts))
    sys.exit(1)
print("GUI pointer test passed (%s); artifacts in %s" % (json.dumps(moves), artifacts))

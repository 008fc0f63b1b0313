"""Benchmark: the haptic loop's timing while the user drags the camera in the real ParaView GUI
(issue 20 item 6). Run under Testing/Utilities/vtouch-xvfb-run by Utilities/bench/run_bench.py
(section "gui"), or by hand:

    Testing/Utilities/vtouch-xvfb-run /usr/bin/python3 Testing/ParaView/gui/bench_camera_drag.py \
        --json out.json [--seconds 4]

with VESSELTOUCH_PARAVIEW, VESSELTOUCH_PLUGIN_DIR, VESSELTOUCH_TEST_DRIVER_DIR and VESSELTOUCH_BINARY_DIR set (run_bench.py
sets them). The scene of gui_scene.py "tracing" (the phantom as a MIP, the session running with the
pointer device, "Trace with mouse" on). Two phases of the same length, each on a freshly
restarted session (its loop statistics start at zero): "idle" (the mouse traces slowly) and
"drag" (middle-button pans, right-button zooms and Ctrl + left rotations, back to back, through
the real X server). Writes flat keys gui.<phase>.{p50,p99,max}_period_error_us, overruns,
achieved_hz, ticks, plus the camera pushes the agent display made during the drag and the view-model builds they
caused in the session (one per push, issue 18 item 2).
"""

import argparse
import json
import os
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from gui_driver import GuiDriver  # noqa: E402


def restart(gui):
    gui.python("import vesseltouch\n"
               "s = vesseltouch.logic()\n"
               "s.Stop()\n"
               "s.Start()\n")
    gui.wait_until(lambda s: s["session"]["running"], seconds=10)


def phase(gui, seconds, drag):
    start = time.time()  # the statistics start with the restart
    restart(gui)
    rect = gui.state["view_rect"]
    x, y = rect[0] + rect[2] // 2, rect[1] + rect[3] // 2
    gui.xdotool("mousemove", x, y)
    step = 0
    while time.time() - start < seconds:
        step += 1
        if not drag:
            gui.xdotool("mousemove", x + 20 * ((step % 8) - 4), y)
            time.sleep(0.05)
            continue
        kind = step % 3
        button = {0: 2, 1: 3, 2: 1}[kind]  # pan, zoom, rotate (Ctrl + left)
        if kind == 2:
            gui.xdotool("keydown", "ctrl")
        gui.xdotool("mousedown", button)
        for k in range(1, 11):
            gui.xdotool("mousemove", x + 6 * k * (1 if step % 2 else -1), y + 3 * k)
            time.sleep(0.02)
        gui.xdotool("mouseup", button)
        if kind == 2:
            gui.xdotool("keyup", "ctrl")
        gui.xdotool("mousemove", x, y)
    reply = gui.command("state")
    elapsed = time.time() - start  # the ticks counted up to the state's reading
    session = reply["state"]["session"] if reply else {}
    return session, elapsed


def agent_report(gui):
    try:
        with open(gui.env["VESSELTOUCH_AGENT_REPORT"]) as f:
            return json.load(f)
    except (OSError, ValueError):
        return {}


def agent_counts(gui, seconds=20.0):
    """The agent display's camera pushes and the session's view-model builds up to now: from the
    first report written after this call (the GUI thread rewrites it about twice a second, less
    often on a loaded machine; a stale one read too early made the drag's pushes look like 0)."""
    seen = agent_report(gui).get("sequence", -1)
    deadline = time.time() + seconds
    report = agent_report(gui)
    while report.get("sequence", -1) <= seen + 1 and time.time() < deadline:
        time.sleep(0.1)
        report = agent_report(gui)
    return report.get("camera_pushes", 0), report.get("view_model_builds", 0)


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--json", required=True)
    parser.add_argument("--seconds", type=float, default=4.0)
    args = parser.parse_args()
    problems = []

    def check(condition, message):
        if not condition:
            problems.append(message)
            print("bench_camera_drag: " + message, file=sys.stderr, flush=True)
        return condition

    gui = GuiDriver("bench_camera_drag", "tracing", check)
    results = {}
    try:
        if gui.wait_for_scene() and gui.wait_until(lambda s: s["session"]["running"]):
            gui.run("check", "actionVesselTouchTraceWithMouse", 1)
            time.sleep(1.0)
            for name, drag in (("idle", False), ("drag", True)):
                pushes, builds = agent_counts(gui)
                session, elapsed = phase(gui, args.seconds, drag)
                check(session.get("running") and session.get("fault") == 0,
                      "the session ran through the %s phase (%r)" % (name, session))
                ticks = session.get("ticks", 0)
                results.update({
                    "gui.%s.max_period_error_us" % name: session.get("period_error_max_us"),
                    "gui.%s.p99_period_error_us" % name: session.get("period_error_p99_us"),
                    "gui.%s.overruns" % name: session.get("overruns"),
                    "gui.%s.ticks" % name: ticks,
                    "gui.%s.achieved_hz" % name: ticks / elapsed if elapsed > 0 else 0.0,
                    "gui.%s.fault" % name: session.get("fault"),
                    "gui.%s.realtime_scheduling" % name: int(bool(
                        session.get("realtime_scheduling"))),
                })
                if drag:
                    pushes_after, builds_after = agent_counts(gui)
                    results["gui.drag.camera_pushes"] = pushes_after - pushes
                    results["gui.drag.view_model_builds"] = builds_after - builds
                    check(results["gui.drag.camera_pushes"] > 0,
                          "the drags moved the camera and it was pushed to the session")
    finally:
        gui.finish()
    with open(args.json, "w") as f:
        json.dump(results, f, indent=1, sort_keys=True)
    print(json.dumps(results, indent=1, sort_keys=True))
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())

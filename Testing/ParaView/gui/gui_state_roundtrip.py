"""GUI test: state files with the panel open and a session running (issue 20, item 12).

The user picks a seed on the brightest vessel, extracts centerlines (automatic range), starts the
session and saves the state (File > Save State, as .pvsm and as a Python .py state). Then, the
session still running, they clear the seed, switch the automatic range off and change the range,
and load the .pvsm (File > Load State) into the running session. ParaView adds the state's
pipeline beside the existing one; VesselTouch keeps one session: the old one stops (force to
zero) and goes away, the panel shows the loaded volume, seed (and its marker), range, Automatic
choice and centerlines, its session is the loaded one (not running until Start), exactly one
"VesselTouchSession" is registered, and vesseltouch.logic() in the GUI's Python returns it.

Then Edit > Reset Session as a user does it (panel open, the loaded session running; issue 20
item 4: it once crashed in ParaView's view-layout code after a state round trip), and the state
loaded into the empty session: the panel comes back once more and the session starts.

Finally the Python state saved from the GUI, which writes BlendMode = 'Maximum Intensity' for the
MIP, runs in a fresh pvpython that loads the plugin (and never runs ShowAsMIP): the MIP's
representation has blend mode 1.
"""

import json
import os
import subprocess
import sys

import numpy
from PIL import Image

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from gui_driver import run_test  # noqa: E402

PANEL_VALUES = ("seedLabel", "lowerThreshold", "upperThreshold", "volumeCombo", "automaticRange")


def hidden_session_checks(gui, check, when):
    """Issue 20 item 13: the session is a registered source (saved in state files) that the
    Pipeline Browser does not list, while it lists the other sources."""
    gui.wait_until(lambda s: "VesselTouchSession" not in s.get("pipeline_browser", []), seconds=5)
    rows, sources = gui.state.get("pipeline_browser", []), gui.state.get("sources", [])
    check("VesselTouchSession" in sources and "VesselTouchSession" not in rows,
          "%s: the session is registered but not in the Pipeline Browser (%r, %r)"
          % (when, sources, rows))
    others = [name for name in sources if name != "VesselTouchSession"]
    check(others and all(name in rows for name in others),
          "%s: the browser lists the other sources (%r)" % (when, rows))


def python_logic(gui, name):
    """What vesseltouch.logic() returns in the GUI's Python shell (its proxy's global id, whether
    it runs) and the sessions registered under the shared name."""
    out = os.path.join(gui.work, name + ".json")
    gui.python("import json\n"
               "import vesseltouch\n"
               "from paraview import servermanager\n"
               "s = vesseltouch.logic()\n"
               "registered = servermanager.ProxyManager().GetProxies('sources', "
               "'VesselTouchSession')\n"
               "json.dump({'global_id': s.proxy.GetGlobalID(), 'running': s.IsRunning(),\n"
               "           'registered': [p.GetGlobalID() for p in registered]},\n"
               "          open(%r, 'w'))\n" % out)
    try:
        with open(out) as f:
            return json.load(f)
    except (OSError, ValueError):
        return {}


def panel_restored_checks(gui, check, saved, when):
    check(gui.widget("seedLabel").get("text") == saved["seedLabel"]["text"],
          "%s: the same seed (%r, saved %r)" % (when, gui.widget("seedLabel").get("text"),
                                               saved["seedLabel"]["text"]))
    check(gui.widget("clearSeedButton").get("enabled") is True,
          "%s: the seed's marker is back (Clear is enabled)" % when)
    check(gui.widget("volumeCombo").get("text") == saved["volumeCombo"]["text"],
          "%s: the same volume (%r)" % (when, gui.widget("volumeCombo").get("text")))
    check(gui.widget("automaticRange").get("checked") == saved["automaticRange"]["checked"],
          "%s: the same Automatic choice" % when)
    for name in ("lowerThreshold", "upperThreshold"):
        check(abs(gui.widget(name).get("value", -1) - saved[name]["value"]) < 1e-6,
              "%s: %s restored (%r, saved %r)" % (when, name, gui.widget(name).get("value"),
                                                 saved[name]["value"]))
    check("state file" in gui.widget("extractMessage").get("text", ""),
          "%s: the panel says the centerlines come from the state (%r)"
          % (when, gui.widget("extractMessage").get("text")))
    # The panel's volume and centerlines are the loaded ones, and the session uses them.
    session = gui.state["session"]
    check(session["input_global_id"] == gui.state.get("panel_centerline_global_id") != 0,
          "%s: the session runs on the panel's centerlines (%r, %r)"
          % (when, session["input_global_id"], gui.state.get("panel_centerline_global_id")))
    check(gui.state.get("panel_centerline_input_global_id") ==
          gui.state.get("panel_volume_global_id") != 0,
          "%s: the centerlines are the panel's volume's" % when)


def start_from_panel(gui, check, when):
    gui.run("click", "startButton")
    check(gui.wait_until(lambda s: s["session"]["running"], seconds=10),
          "%s: the session starts from the panel" % when)
    check(gui.state["session"]["skeleton_paths"] > 0,
          "%s: it runs on the loaded centerlines (%r paths)"
          % (when, gui.state["session"]["skeleton_paths"]))


def python_state_loads_in_pvpython(gui, check, state_py):
    """The GUI's Python state in a fresh pvpython that loaded the plugin (LoadPlugin, as its
    VesselPhantom needs) and never ran ShowAsMIP."""
    text = open(state_py).read()
    check("'Maximum Intensity'" in text,
          "the GUI's Python state names the MIP's blend mode (%s)"
          % [line.strip() for line in text.splitlines() if "BlendMode" in line])
    probe = os.path.join(gui.work, "probe_state.py")
    with open(probe, "w") as f:
        f.write("import json, sys\n"
                "from paraview import simple\n"
                "simple.LoadPlugin(%r, ns=globals())\n"
                "exec(open(%r).read())\n"
                "reps = [r for r in simple.GetRepresentations().values()\n"
                "        if r.GetProperty('BlendMode') is not None\n"
                "        and r.Representation == 'Volume']\n"
                "print('PROBE=' + json.dumps([r.SMProxy.GetProperty('BlendMode').GetElement(0)\n"
                "                             for r in reps]))\n"
                % (os.environ["VESSELTOUCH_PLUGIN"], state_py))
    env = dict(os.environ)
    env["HOME"] = os.path.join(gui.work, "home")
    run = subprocess.run([env["VESSELTOUCH_PVPYTHON"], probe],
                         env=env, capture_output=True, text=True, timeout=240)
    output = run.stdout + run.stderr
    with open(os.path.join(gui.work, "pvpython_state.log"), "w") as f:
        f.write(output)
    check(run.returncode == 0, "the Python state runs in a fresh pvpython with the plugin "
          "(code %s): %s" % (run.returncode, output[-1500:]))
    probe_lines = [line for line in output.splitlines() if line.startswith("PROBE=")]
    modes = json.loads(probe_lines[-1][len("PROBE="):]) if probe_lines else []
    check(modes and all(mode == 1 for mode in modes),
          "its MIP has blend mode 1, maximum intensity (%r)" % modes)


def body(gui, check):
    view = gui.capture("view.png")
    grey = numpy.asarray(Image.open(view).convert("L")).astype(int)
    row, col = numpy.unravel_index(numpy.argmax(grey), grey.shape)
    gui.run("click", "pickSeedButton")
    rect = gui.state["view_rect"]
    gui.xdotool("mousemove", rect[0] + int(col * rect[2] / grey.shape[1]),
                rect[1] + int(row * rect[3] / grey.shape[0]))
    gui.xdotool("click", 1)
    gui.wait_until(lambda s: "mm" in s["widgets"]["seedLabel"]["text"], seconds=5)
    gui.click_and_wait("extractButton")
    gui.run("click", "startButton")
    gui.wait_until(lambda s: s["session"]["running"], seconds=10)
    hidden_session_checks(gui, check, "before saving")
    saved = {name: gui.widget(name) for name in PANEL_VALUES}
    old = dict(gui.state["session"], volume=gui.state.get("panel_volume_global_id"),
               centerline=gui.state.get("panel_centerline_global_id"))
    check(old["registered"] == [old["global_id"]], "one session before saving (%r)" % old)
    check("centerline path" in gui.widget("extractMessage").get("text", ""), "extracted")
    state = os.path.join(gui.work, "session.pvsm")
    gui.run("savestate", state)
    state_py = os.path.join(gui.work, "session_state.py")
    gui.run("savestate", state_py)
    # ParaView asks for the Python state's options in a modal dialog, which holds the driver's
    # replies until it is answered; under load it appeared after the 5 s once waited here, and
    # the test then timed out at 600 s with ParaView waiting on it.
    gui.answer_dialog("Python State Options", "Return", seconds=120,
                      unless=lambda: os.path.exists(state_py))
    check(gui.wait_until(lambda s: os.path.exists(state_py), seconds=20),
          "the Python state was written")

    # The user changes things while the session runs...
    gui.run("click", "clearSeedButton")
    gui.run("check", "automaticRange", 0)
    gui.run("set", "lowerThreshold", saved["upperThreshold"]["value"])
    check(gui.state["session"]["running"], "the session still runs before the load")
    # ...and loads the state into the running session (File > Load State).
    gui.run("loadstate", state, seconds=120)  # synchronous: the state rebuilds the pipeline
    check(gui.alive(), "ParaView survives loading a state into a running session")
    loaded = gui.wait_until(lambda s: "mm" in s["widgets"]["seedLabel"]["text"]
                            and len(s["session"]["registered"]) == 1
                            and s["session"]["global_id"] != old["global_id"], seconds=20)
    check(loaded, "the panel follows the loaded state (%r, %r)"
          % (gui.widget("seedLabel").get("text"), gui.state.get("session")))
    session = gui.state["session"]
    check(session["registered"] == [session["global_id"]],
          "exactly one session is registered, the panel's (%r, panel %r, old %r)"
          % (session["registered"], session["global_id"], old["global_id"]))
    check(not session["running"] and not any(session["registered_running"]),
          "the old session stopped and the loaded one waits for Start (%r)" % session)
    check(gui.widget("startButton").get("enabled") is True, "Start is enabled after the load")
    check(gui.state.get("panel_volume_global_id") not in (0, old["volume"]),
          "the panel's volume is the loaded one (%r, old %r)"
          % (gui.state.get("panel_volume_global_id"), old["volume"]))
    check(gui.state.get("panel_centerline_global_id") not in (0, old["centerline"]),
          "the panel's centerlines are the loaded ones")
    panel_restored_checks(gui, check, saved, "loaded into a running session")
    hidden_session_checks(gui, check, "after loading")
    logic = python_logic(gui, "logic_after_load")
    check(logic.get("global_id") == session["global_id"],
          "vesseltouch.logic() returns the loaded session (%r, panel %r)"
          % (logic, session["global_id"]))
    check(logic.get("registered") == [session["global_id"]] and logic.get("running") is False,
          "Python sees one session, stopped (%r)" % logic)
    start_from_panel(gui, check, "loaded into a running session")

    # Edit > Reset Session as a user does it: panel open, the loaded session running.
    gui.run("trigger", "actionDelete_All")
    check(gui.answer_dialog("Delete All", "Return", seconds=60.0),
          "Reset Session asked for confirmation")
    check(gui.wait_until(lambda s: not s.get("sources"), seconds=15, reply_seconds=120),
          "Reset Session removed the pipeline (%r)" % gui.state.get("sources"))
    check(gui.alive(), "ParaView survives Edit > Reset Session after a state round trip")
    check(gui.state["session"]["exists"] is False and gui.state["session"]["registered"] == [],
          "no session after the reset (%r)" % gui.state.get("session"))

    # The state into the empty session: the panel comes back once more.
    gui.run("loadstate", state, seconds=120)  # synchronous: the state rebuilds the pipeline
    restored = gui.wait_until(lambda s: "mm" in s["widgets"]["seedLabel"]["text"]
                              and s["session"]["exists"], seconds=20)
    check(restored, "the seed comes back with the state (%r)" % gui.widget("seedLabel"))
    check(len(gui.state["session"]["registered"]) == 1,
          "one session after loading into the reset session (%r)" % gui.state["session"])
    panel_restored_checks(gui, check, saved, "loaded after Reset Session")
    hidden_session_checks(gui, check, "after Reset Session and loading")
    start_from_panel(gui, check, "loaded after Reset Session")
    gui.run("click", "stopButton")
    check(gui.alive(), "ParaView is running at the end")

    python_state_loads_in_pvpython(gui, check, state_py)


run_test("gui_state_roundtrip", "phantom", body)

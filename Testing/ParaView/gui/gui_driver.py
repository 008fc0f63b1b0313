"""Drives the real ParaView GUI with the VesselTouch plugin, for the GUI tests, under the display
given by $DISPLAY (run under Testing/Utilities/vtouch-xvfb-run).

ParaView starts with the plugin and gui_scene.py (VESSELTOUCH_SCENE chooses what it opens); the
panel's test driver (pqVesselTouchTestDriver, VESSELTOUCH_GUI_DRIVER) runs the commands this
module writes, as a user's action would run (a menu action triggered, a button clicked, a spin box
edited), and answers with the panel's widgets, the pipeline and the session's status. Mouse
interaction in the view goes through the real X server (xdotool). Runs with Debian's python3.
"""

import json
import os
import shutil
import signal
import subprocess
import tempfile
import time

from gui_paraview import paraview_command


class GuiDriver:
    """ParaView running gui_scene.py with ``scene``; ``check(condition, message)`` records
    failures. ``command(...)`` returns the driver's reply (None when ParaView died)."""

    def __init__(self, name, scene, check, extra_env=None):
        self.name = name
        self.check = check
        self.work = tempfile.mkdtemp(prefix="vesseltouch-%s-" % name)
        self.commands = os.path.join(self.work, "driver")
        os.makedirs(self.commands)
        home = os.path.join(self.work, "home")
        os.makedirs(os.path.join(home, ".config", "ParaView"))
        with open(os.path.join(home, ".config", "ParaView", "ParaView-UserSettings.json"),
                  "w") as f:
            json.dump({"settings": {"GeneralSettings": {"ShowWelcomeDialog": 0}}}, f)
        self.env = dict(os.environ)
        self.env.update({
            "HOME": home,
            "XDG_RUNTIME_DIR": self.work,
            "VESSELTOUCH_GUI_DRIVER": self.commands,
            "VESSELTOUCH_SCENE": scene,
            "VESSELTOUCH_DONE_FLAG": os.path.join(self.work, "done"),
            "VESSELTOUCH_AGENT_REPORT": os.path.join(self.work, "agent.json"),
        })
        self.env.update(extra_env or {})
        script = os.path.join(os.path.dirname(os.path.abspath(__file__)), "gui_scene.py")
        command = paraview_command(self.env, script)
        self.log = open(os.path.join(self.work, "paraview.log"), "w")
        self.app = subprocess.Popen(command, env=self.env, stdout=self.log,
                                    stderr=subprocess.STDOUT)
        self.sequence = 0
        self.state = {}

    def alive(self):
        return self.app.poll() is None

    def check_no_unregistered_input(self):
        """ParaView's GUI said nothing about an unregistered proxy on an input (pqPipelineFilter's
        "Some proxy is added as input but was not registered"), and its Output Messages window,
        which opens on such a report, stayed closed. Uses the state of the last command."""
        self.command("state")
        messages = self.state.get("messages", []) + self.state.get("output_messages", [])
        unregistered = [m for m in messages if "was not registered" in m]
        self.check(not unregistered, "no unregistered proxy on an input reported (%s)" % unregistered)
        displayed = self.state.get("output_messages", [])
        self.check(self.state.get("output_messages_visible") is False,
                   "ParaView's Output Messages window stayed closed (it shows: %s)" % displayed[-5:])

    def wait_for_scene(self, seconds=150):
        flag = self.env["VESSELTOUCH_DONE_FLAG"]
        deadline = time.time() + seconds
        while time.time() < deadline and not os.path.exists(flag):
            if not self.check(self.alive(), "ParaView exited early (%s)" % self.app.poll()):
                return False
            time.sleep(0.5)
        if not self.check(os.path.exists(flag), "the scene script finished in time"):
            return False
        status = open(flag).read()
        if not self.check(status.startswith("ok"), "the scene script succeeded: " + status):
            return False
        # ParaView's welcome dialog opens a while after start-up and takes the mouse: wait for
        # it (a few seconds at most) and close it.
        deadline = time.time() + 8.0
        while time.time() < deadline:
            reply = self.command("dismiss", "Welcome")
            if reply is None or reply["ok"]:
                break
            time.sleep(0.3)
        return self.command("resize", 1280, 1000) is not None

    def command(self, *words, seconds=30):
        """Runs one driver command; returns its reply, with the state in self.state."""
        self.sequence += 1
        line = " ".join(str(w) for w in words)
        path = os.path.join(self.commands, "cmd-%d.txt" % self.sequence)
        with open(path + ".tmp", "w") as f:
            f.write(line + "\n")
        os.rename(path + ".tmp", path)
        reply_path = os.path.join(self.commands, "reply-%d.json" % self.sequence)
        deadline = time.time() + seconds
        while time.time() < deadline:
            if not self.alive():
                self.check(False, "ParaView died (code %s) during '%s'" % (self.app.poll(), line))
                return None
            if os.path.exists(reply_path):
                with open(reply_path) as f:
                    reply = json.load(f)
                self.state = reply["state"]
                return reply
            time.sleep(0.1)
        self.check(False, "no reply to '%s' within %d s" % (line, seconds))
        return None

    def run(self, *words, **kwargs):
        """command() that records a failure when the driver reports one."""
        reply = self.command(*words, **kwargs)
        if reply is not None:
            self.check(reply["ok"], "'%s': %s" % (" ".join(map(str, words)), reply["error"]))
        return reply

    def python(self, code):
        """Runs ``code`` in the GUI's Python (as the Python Shell's Run Script)."""
        path = os.path.join(self.work, "snippet-%d.py" % (self.sequence + 1))
        with open(path, "w") as f:
            f.write(code)
        return self.run("python", path)

    def widget(self, name):
        return self.state.get("widgets", {}).get(name, {})

    def wait_until(self, predicate, seconds=20, period=0.3, reply_seconds=30):
        """Polls the state until predicate(state) holds; returns whether it did. A queued action
        (trigger) holds the replies until it is over: ``reply_seconds`` bounds that wait."""
        deadline = time.time() + seconds
        while time.time() < deadline:
            if self.command("state", seconds=reply_seconds) is None:
                return False
            if predicate(self.state):
                return True
            time.sleep(period)
        return False

    def click_and_wait(self, button, seconds=120):
        """Clicks a button that starts a background run (Extract, Preview) and waits until the
        panel says it ended (Cancel disabled again); returns whether it did in time."""
        self.run("click", button)
        return self.wait_until(
            lambda s: not s["widgets"].get("cancelButton", {}).get("enabled", False),
            seconds=seconds, period=0.2)

    def xdotool(self, *args):
        subprocess.run(["xdotool"] + [str(a) for a in args], env=self.env, check=False)

    def dismiss_dialogs(self, seconds=6.0):
        """Closes ParaView's welcome dialog or any other stray modal dialog."""
        if not shutil.which("xdotool"):
            return
        deadline = time.time() + seconds
        while time.time() < deadline:
            found = subprocess.run(["xdotool", "search", "--onlyvisible", "--name", "Welcome"],
                                   env=self.env, capture_output=True, text=True, check=False)
            if not found.stdout.strip():
                break
            self.xdotool("key", "Escape")
            time.sleep(0.5)

    def answer_dialog(self, title, key, seconds=60.0, unless=None):
        """Waits for a window titled ``title``, presses ``key`` in it until it closes, and says
        whether it appeared. Ends at once when ``unless()`` holds (the dialog's work is done).
        A modal dialog holds the driver's replies until it closes. On a loaded machine it may
        take far more than a few seconds to appear, and a key sent as it maps can be lost (the
        dialog then stays open and ParaView waits on it: GUI.StateRoundTripRestoresPanel timed
        out so twice), so the key is sent again while the dialog shows."""
        deadline = time.time() + seconds
        answered = 0  # keys sent
        while time.time() < deadline:
            if unless is not None and unless():
                return answered > 0
            found = subprocess.run(["xdotool", "search", "--onlyvisible", "--name", title],
                                   env=self.env, capture_output=True, text=True, check=False)
            windows = found.stdout.split()
            if not windows:
                if answered:
                    if answered > 1:
                        print("'%s' closed after %d keys" % (title, answered), flush=True)
                    return True  # closed by the key
                time.sleep(0.3)
                continue
            self.xdotool("windowactivate", "--sync", windows[-1])
            self.xdotool("key", "--window", windows[-1], key)
            answered += 1
            time.sleep(0.7)
        return answered > 0

    def screenshot(self, path):
        """The whole screen (the main window) as PNG, through the X server."""
        subprocess.run(["import", "-window", "root", path], env=self.env, check=False)
        return path if os.path.exists(path) else None

    def capture(self, name):
        """The active render view's image (ParaView's own capture), as PNG in the work dir."""
        path = os.path.join(self.work, name)
        reply = self.run("capture", path)
        return path if reply and reply["ok"] and os.path.exists(path) else None

    def finish(self):
        """Stops ParaView and copies the artifacts to <build>/Testing/<name>; returns the path."""
        self.check(self.alive(), "ParaView is still running at the end")
        self.app.send_signal(signal.SIGTERM)
        try:
            self.app.wait(20)
        except subprocess.TimeoutExpired:
            self.app.kill()
        self.log.close()
        artifacts = os.path.join(self.env["VESSELTOUCH_BINARY_DIR"], "Testing", self.name)
        shutil.rmtree(artifacts, ignore_errors=True)
        os.makedirs(artifacts, exist_ok=True)
        for name in os.listdir(self.work):
            if name.endswith((".png", ".log", ".json", ".pvsm")):
                shutil.copy(os.path.join(self.work, name), artifacts)
        if self.state:
            with open(os.path.join(artifacts, "last_state.json"), "w") as f:
                json.dump(self.state, f, indent=1)
        shutil.rmtree(self.work, ignore_errors=True)
        return artifacts


def run_test(name, scene, body, extra_env=None):
    """Runs ``body(driver, check)`` on a fresh ParaView; exits 1 on any failure."""
    import sys
    failures = []

    def check(condition, message):
        if not condition:
            failures.append(message)
            print("FAIL: " + message, flush=True)
        return condition

    driver = GuiDriver(name, scene, check, extra_env)
    try:
        if driver.wait_for_scene():
            body(driver, check)
    finally:
        artifacts = driver.finish()
    if failures:
        print("%s: %d failure(s); artifacts in %s" % (name, len(failures), artifacts))
        sys.exit(1)
    print("%s passed; artifacts in %s" % (name, artifacts))

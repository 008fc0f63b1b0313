"""Shared by the agent and pointer GUI tests: start the real ParaView with the plugin and
gui_agent_cone_scene.py on $DISPLAY, read the agent display's JSON report, collect artifacts."""

import json
import os
import shutil
import signal
import subprocess
import tempfile
import time

from gui_paraview import paraview_command


class ParaViewRun:
    """ParaView running the scene script with ``extra_env``; ``check(condition, message)``
    records failures."""

    def __init__(self, name, extra_env, check):
        self.name = name
        self.check = check
        self.work = tempfile.mkdtemp(prefix="vesseltouch-%s-" % name)
        home = os.path.join(self.work, "home")
        os.makedirs(os.path.join(home, ".config", "ParaView"))
        with open(os.path.join(home, ".config", "ParaView", "ParaView-UserSettings.json"),
                  "w") as f:
            json.dump({"settings": {"GeneralSettings": {"ShowWelcomeDialog": 0}}}, f)
        self.env = dict(os.environ)
        self.env.update({
            "HOME": home,
            "XDG_RUNTIME_DIR": self.work,
            "VESSELTOUCH_AGENT_REPORT": os.path.join(self.work, "agent.json"),
            "VESSELTOUCH_DONE_FLAG": os.path.join(self.work, "done"),
        })
        self.env.update(extra_env)
        scene = os.path.join(os.path.dirname(os.path.abspath(__file__)),
                             "gui_agent_cone_scene.py")
        command = paraview_command(self.env, scene)
        self.log = open(os.path.join(self.work, "paraview.log"), "w")
        self.app = subprocess.Popen(command, env=self.env, stdout=self.log,
                                    stderr=subprocess.STDOUT)

    def wait_for_scene(self, seconds=150):
        flag = self.env["VESSELTOUCH_DONE_FLAG"]
        deadline = time.time() + seconds
        while time.time() < deadline and not os.path.exists(flag):
            if not self.check(self.app.poll() is None,
                              "ParaView exited early with code %s" % self.app.poll()):
                return False
            time.sleep(0.5)
        if not self.check(os.path.exists(flag), "the scene script finished in time"):
            return False
        status = open(flag).read()
        return self.check(status.startswith("ok"), "the scene script succeeded: " + status)

    def report(self):
        try:
            with open(self.env["VESSELTOUCH_AGENT_REPORT"]) as f:
                return json.load(f)
        except (OSError, ValueError):
            return None

    def wait_for_report(self, predicate, seconds=30):
        deadline = time.time() + seconds
        while time.time() < deadline:
            report = self.report()
            if report is not None and predicate(report):
                return report
            time.sleep(0.5)
        return None

    def xdotool(self, *args):
        if shutil.which("xdotool"):
            subprocess.run(["xdotool"] + [str(a) for a in args], env=self.env, check=False)

    def dismiss_dialogs(self, seconds=10.0):
        """Closes ParaView's welcome dialog (modal: it would take the mouse), which a timer
        opens some time after start-up; Escape once more for any other stray dialog."""
        if not shutil.which("xdotool"):
            return
        deadline = time.time() + seconds
        seen = False
        while time.time() < deadline:
            found = subprocess.run(["xdotool", "search", "--onlyvisible", "--name", "Welcome"],
                                   env=self.env, capture_output=True, text=True, check=False)
            if found.stdout.strip():
                seen = True
                self.xdotool("key", "Escape")
            elif seen:
                break  # seen and closed
            time.sleep(0.5)
        self.xdotool("key", "Escape")
        time.sleep(0.3)

    def screenshot(self, name):
        png = os.path.join(self.work, name)
        subprocess.run(["import", "-window", "root", png], env=self.env, check=False)
        return png if os.path.exists(png) else None

    def finish(self):
        """Stops ParaView and copies the artifacts to <build>/Testing/<name>; returns the path."""
        self.check(self.app.poll() is None, "ParaView is still running")
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
            if name.endswith((".png", ".log", ".json")):
                shutil.copy(os.path.join(self.work, name), artifacts)
        shutil.rmtree(self.work, ignore_errors=True)
        return artifacts

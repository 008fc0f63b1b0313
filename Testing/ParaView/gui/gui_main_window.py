"""GUI test: the real ParaView, with the VesselTouch plugin and the main job's start-up script,
on the display given by $DISPLAY (run it under Testing/Utilities/vtouch-xvfb-run).

Checks that the MIP in the render view is not blank and that the VesselTouch dock panel exists,
is visible and shows the active dataset and the build's versions. Runs with Debian's python3.
"""

import json
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import time

import matplotlib.image

from gui_paraview import paraview_command

failures = []


def check(condition, message):
    if not condition:
        failures.append(message)
        print("FAIL: " + message, flush=True)


work = tempfile.mkdtemp(prefix="vesseltouch-gui-")
home = os.path.join(work, "home")
os.makedirs(os.path.join(home, ".config", "ParaView"))
# A fresh user: no saved window layout, no welcome dialog in the way of the screenshot.
with open(os.path.join(home, ".config", "ParaView", "ParaView-UserSettings.json"), "w") as f:
    json.dump({"settings": {"GeneralSettings": {"ShowWelcomeDialog": 0}}}, f)

env = dict(os.environ)
env.update({
    "HOME": home,
    "XDG_RUNTIME_DIR": work,
    "VESSELTOUCH_GUI_REPORT": os.path.join(work, "panel.json"),
    "VESSELTOUCH_DONE_FLAG": os.path.join(work, "done"),
    "VESSELTOUCH_OUTPUT_DIR": os.path.join(work, "out"),
})
startup = os.path.join(env["VESSELTOUCH_SOURCE_DIR"], "Utilities", "vesseltouch_startup.py")
command = paraview_command(env, startup)
log = open(os.path.join(work, "paraview.log"), "w")
app = subprocess.Popen(command, env=env, stdout=log, stderr=subprocess.STDOUT)
try:
    deadline = time.time() + 180
    while time.time() < deadline and not os.path.exists(env["VESSELTOUCH_DONE_FLAG"]):
        check(app.poll() is None, "ParaView exited early with code %s" % app.poll())
        if failures:
            break
        time.sleep(0.5)
    check(os.path.exists(env["VESSELTOUCH_DONE_FLAG"]), "the start-up script finished in time")
    if os.path.exists(env["VESSELTOUCH_DONE_FLAG"]):
        status = open(env["VESSELTOUCH_DONE_FLAG"]).read()
        check(status.startswith("ok"), "the start-up script succeeded: " + status)
    # No fixed wait: the panel has written its report and the window is drawn (a screenshot that
    # is not blank), however long a loaded machine takes, up to a minute.
    root_png = os.path.join(work, "window.png")
    grabbed = False
    deadline = time.time() + 60
    while time.time() < deadline and app.poll() is None:
        if shutil.which("xdotool"):
            subprocess.run(["xdotool", "key", "Escape"], env=env, check=False)  # stray dialog
        grab = subprocess.run(["import", "-window", "root", root_png], env=env, check=False)
        grabbed = grab.returncode == 0 and os.path.exists(root_png)
        if (grabbed and os.path.exists(env["VESSELTOUCH_GUI_REPORT"])
                and float(matplotlib.image.imread(root_png).std()) > 0.05):
            break
        time.sleep(0.5)
    check(grabbed, "screenshot of the whole window")
    check(app.poll() is None, "ParaView is still running after the scene was set up")
finally:
    app.send_signal(signal.SIGTERM)
    try:
        app.wait(20)
    except subprocess.TimeoutExpired:
        app.kill()
    log.close()

# The dock panel, as the running widget reported itself.
report_path = env["VESSELTOUCH_GUI_REPORT"]
check(os.path.exists(report_path), "the VesselTouch dock panel was created")
if os.path.exists(report_path):
    panel = json.load(open(report_path))
    check(panel.get("title") == "VesselTouch", "panel title: %r" % panel.get("title"))
    check(panel.get("visible") is True, "panel visible")
    check(panel.get("dataset") == "VesselPhantom1", "panel shows the active dataset: %r"
          % panel.get("dataset"))
    check("128 x 128 x 128" in panel.get("summary", ""), "panel summary: %r" % panel.get("summary"))
    versions = panel.get("versions", {})
    for component in ("VesselTouch", "ParaView", "VTK", "ITK", "Qt", "hidapi"):
        check(bool(versions.get(component)), "panel shows the %s version" % component)

# The MIP in the render view.
view_png = os.path.join(env["VESSELTOUCH_OUTPUT_DIR"], "screenshot.png")
check(os.path.exists(view_png), "render view screenshot written")
if os.path.exists(view_png):
    pixels = matplotlib.image.imread(view_png)
    grey = pixels[:, :, :3].mean(axis=2) if pixels.ndim == 3 else pixels
    bright = float((grey > 0.25).mean())
    check(0.005 < bright < 0.5, "the MIP shows vessels (bright fraction %.4f)" % bright)
    check(float(grey.std()) > 0.03, "the MIP has contrast (std %.3f)" % grey.std())
if os.path.exists(os.path.join(work, "window.png")):
    window = matplotlib.image.imread(os.path.join(work, "window.png"))
    check(float(window.std()) > 0.05, "the ParaView window is not blank")

artifacts = os.path.join(env["VESSELTOUCH_BINARY_DIR"], "Testing", "gui")
os.makedirs(artifacts, exist_ok=True)
for name in ("window.png", "paraview.log", "panel.json"):
    if os.path.exists(os.path.join(work, name)):
        shutil.copy(os.path.join(work, name), artifacts)
if os.path.exists(view_png):
    shutil.copy(view_png, os.path.join(artifacts, "view.png"))
shutil.rmtree(work, ignore_errors=True)

if failures:
    print("GUI test: %d failure(s); artifacts in %s" % (len(failures), artifacts))
    sys.exit(1)
print("GUI test passed; artifacts in %s" % artifacts)

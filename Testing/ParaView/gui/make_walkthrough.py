"""Takes the screenshots of Docs/USING.md (the clinician's walkthrough) from the real ParaView GUI
under Xvfb, on the shared TOF-MRA (circle of Willis):

    Testing/Utilities/vtouch-xvfb-run /usr/bin/python3 Testing/ParaView/gui/make_walkthrough.py \
        Docs/using

with VESSELTOUCH_PARAVIEW, VESSELTOUCH_PLUGIN_DIR, VESSELTOUCH_TEST_DRIVER_DIR and VESSELTOUCH_BINARY_DIR set (as ctest sets
them; see Testing/ParaView/CMakeLists.txt). Each step is done as a user does it (the toolbar's
actions, the panel's buttons, clicks in the view through the X server) and the screen is saved.
"""

import os
import sys
import time

import numpy
from PIL import Image

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from gui_driver import GuiDriver  # noqa: E402

DATA = os.path.join(os.environ.get("VESSELTOUCH_SHARED_DATA", "/work/shared/data"),
                    "tof-mra-willis", "chris_MRA.nii.gz")


def shot(gui, out, name):
    gui.run("render")  # the view's widget on the screen, not only its last offscreen frame
    time.sleep(1.5)  # let the widgets and the view repaint
    path = os.path.join(out, name)
    gui.screenshot(path)
    Image.open(path).convert("RGB").crop((0, 0, 1280, 1000)).save(path, optimize=True)
    print("wrote", path, flush=True)


def brightest(png):
    grey = numpy.asarray(Image.open(png).convert("L")).astype(int)
    return numpy.unravel_index(numpy.argmax(grey), grey.shape), grey.shape


def main():
    out = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else "Docs/using")
    os.makedirs(out, exist_ok=True)
    problems = []

    def check(condition, message):
        if not condition:
            problems.append(message)
            print("make_walkthrough: " + message, file=sys.stderr, flush=True)
        return condition

    gui = GuiDriver("walkthrough", "empty", check)
    try:
        if not gui.wait_for_scene():
            return 1
        gui.python("from paraview import simple\n"
                   "mra = simple.OpenDataFile(%r, registrationName='chris_MRA.nii.gz')\n"
                   "mra.UpdatePipeline()\n"
                   "simple.SetActiveSource(mra)\n" % DATA)
        gui.wait_until(lambda s: s["widgets"].get("volumeCombo", {}).get("items"))
        shot(gui, out, "01_open.png")
        gui.run("trigger", "actionVesselTouchShowMIP")
        shot(gui, out, "02_mip.png")
        view = gui.capture("view.png")
        (row, col), shape = brightest(view)
        gui.run("click", "pickSeedButton")
        rect = gui.state["view_rect"]
        gui.xdotool("mousemove", rect[0] + int(col * rect[2] / shape[1]),
                    rect[1] + int(row * rect[3] / shape[0]))
        gui.xdotool("click", 1)
        gui.wait_until(lambda s: "mm" in s["widgets"]["seedLabel"]["text"], seconds=5)
        shot(gui, out, "03_seed.png")
        check(gui.click_and_wait("previewButton"), "the preview ends")
        check("Preview" in gui.widget("extractMessage").get("text", ""),
              "preview: %r" % gui.widget("extractMessage").get("text"))
        shot(gui, out, "04_preview.png")
        # The panel while Extract runs in the background (its progress bar and Cancel).
        gui.run("click", "extractButton")
        if check(gui.widget("cancelButton").get("enabled"), "Extract runs in the background"):
            gui.run("render")  # the view without the preview, as the next idle render draws it
            time.sleep(0.3)  # a progress report or two
            path = os.path.join(out, "05_extracting.png")
            gui.screenshot(path)
            Image.open(path).convert("RGB").crop((0, 0, 1280, 1000)).save(path, optimize=True)
            print("wrote", path, flush=True)
        gui.wait_until(lambda s: not s["widgets"]["cancelButton"]["enabled"], seconds=120)
        check("centerline path" in gui.widget("extractMessage").get("text", ""),
              "extraction: %r" % gui.widget("extractMessage").get("text"))
        shot(gui, out, "06_extract.png")
        gui.run("set", "deviceComboBox", "Mouse (pseudo-haptics)")
        gui.run("click", "startButton")
        gui.wait_until(lambda s: s["session"]["running"], seconds=10)
        gui.run("check", "actionVesselTouchTraceWithMouse", 1)
        x, y = rect[0] + rect[2] // 2, rect[1] + rect[3] // 2
        for d in range(0, 80, 4):
            gui.xdotool("mousemove", x + d, y + d // 3)
            time.sleep(0.05)
        shot(gui, out, "07_tracing.png")
        gui.run("click", "stopButton")
    finally:
        gui.finish()
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())

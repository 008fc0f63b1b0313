"""GUI test: Extract and Preview run in the background, in the real ParaView, like a user runs
them (issue 16 item 6).

Scene: a raw-angiogram VesselPhantom of 256^3 voxels ("Angio": a random tree in noisy tissue with
plates and blobs at vessel intensity) as a MIP. The seed is the tree's root (the driver's "seed"
verb: the picker's report of a pick there). Checks:
- Extract (automatic range) returns at once with Cancel enabled, ends with the centerlines, and
  the pipeline's VesselCenterline took the background run's output without recomputing;
- the session started on them; an Extract that takes long (Automatic off, the range from the
  tissue's level up, the filter's DownsampleFactor 1: the whole tissue coded at full resolution):
  while it runs the view renders a camera drag (the capture changes), the panel answers, the
  session's tick count advances and the progress bar moves;
- Cancel mid-way: "Cancelled." beside Extract within seconds, the old centerlines still bound to
  the running session (same paths) and drawn in the view;
- Extract again while one runs: the first is cancelled, the second runs (one Cancel stops it);
- Preview: the candidate region in magenta over the MIP (the view's pixels), the estimated range
  in the fields, nothing new in the Pipeline Browser; clicking again hides it, Extract hides it;
- deleting the volume mid-extraction and Edit > Reset Session mid-extraction: no crash, the run
  is dropped, the panel still works;
- a shaded volume (bias field +/- 60 %): Preview and Extract say that the shading was corrected.
"""

import json
import os
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from gui_driver import run_test  # noqa: E402
from gui_pixels import magenta_pixels, orange_pixels  # noqa: E402

import numpy  # noqa: E402
from PIL import Image  # noqa: E402


def python_value(gui, code, name):
    """Runs ``code`` in the GUI's Python; it sets ``result``, which comes back through a file."""
    path = os.path.join(gui.work, name + ".json")
    gui.python(code + "\nimport json\nwith open(%r, 'w') as f:\n    json.dump(result, f)\n" % path)
    try:
        with open(path) as f:
            return json.load(f)
    except (OSError, ValueError):
        return None


def running(gui):
    return gui.widget("cancelButton").get("enabled") is True


def seed_at_root(gui, check, source):
    root = python_value(gui, "from paraview import simple, servermanager\n"
                        "truth = servermanager.Fetch(simple.FindSource(%r), idx=1)\n"
                        "result = list(truth.GetPoint(0))\n" % source, "root_" + source)
    if not check(root is not None, "the phantom's root point"):
        return False
    gui.run("seed", *root)
    return check("mm" in gui.widget("seedLabel").get("text", ""),
                 "the seed is set (%r)" % gui.widget("seedLabel"))


def set_full_resolution(gui, on):
    """The VesselCenterline filters' DownsampleFactor (a Properties panel setting): 1 codes the
    full-resolution mask, 0 (the default) chooses. Then a render (ParaView re-runs a shown filter
    for it)."""
    gui.python("from paraview import simple\n"
               "for proxy in simple.GetSources().values():\n"
               "    if proxy.GetXMLName() == 'VesselCenterline':\n"
               "        proxy.DownsampleFactor = %d\n"
               "simple.Render()\n" % (1 if on else 0))
    gui.run("render")


def start_long_extraction(gui, check, lower=300.0):
    """An Extract that takes tens of seconds, for the test to cancel: Automatic off with the range
    from the tissue's level up, so the whole tissue is the vessel mask, coded at full resolution
    (ParaView re-runs the shown filter once for the property, before the test's run)."""
    set_full_resolution(gui, True)
    gui.run("check", "automaticRange", 0)
    gui.run("set", "lowerThreshold", lower)
    gui.run("click", "extractButton")
    return check(running(gui), "the long Extract runs in the background (the reply came while "
                 "it runs: %r)" % gui.widget("extractMessage").get("text"))


def drag_in_view(gui):
    rect = gui.state["view_rect"]
    x, y = rect[0] + rect[2] // 2, rect[1] + rect[3] // 2
    gui.xdotool("mousemove", x, y)
    gui.xdotool("mousedown", 1)
    for step in range(1, 9):
        gui.xdotool("mousemove", x + 12 * step, y + 3 * step)
        time.sleep(0.03)
    gui.xdotool("mouseup", 1)


START = time.time()


def step(number):
    print("step %d at %.1f s" % (number, time.time() - START), flush=True)


def body(gui, check):
    gui.run("state")
    check(gui.widget("volumeCombo").get("text") == "Angio", "the angiogram is the chosen volume")
    browser_before = list(gui.state.get("pipeline_browser", []))
    if not seed_at_root(gui, check, "Angio"):
        return

    step(1)
    # 1. Extract in the background: the reply comes while it runs; then the centerlines.
    gui.run("click", "extractButton")
    check(running(gui), "Extract returns at once with Cancel enabled (%r)"
          % gui.widget("extractMessage").get("text"))
    check(gui.wait_until(lambda s: not running(gui), seconds=120, period=0.2), "Extract ends")
    text = gui.widget("extractMessage").get("text", "")
    check("centerline path" in text, "Extract reports the paths (%r)" % text)
    check(gui.widget("extractProgress").get("value") == 100, "the progress bar is full")
    handed = python_value(gui, "from paraview import simple\n"
                          "f = simple.FindSource('VesselCenterline1')\n"
                          "f.UpdatePropertyInformation()\n"
                          "result = [f.GetPropertyValue('LastRunPrecomputedInfo'),\n"
                          "          f.GetClientSideObject().GetOutput().GetNumberOfCells()]\n",
                          "handoff")
    check(handed is not None and handed[0] == 1 and handed[1] > 0,
          "the pipeline's VesselCenterline returned the background run's output without "
          "recomputing (%r)" % handed)
    paths = handed[1] if handed else 0

    step(2)
    # 2. A session on them.
    gui.run("click", "startButton")
    check(gui.wait_until(lambda s: s["session"]["running"], seconds=10), "the session runs")
    check(gui.wait_until(lambda s: s["session"]["skeleton_paths"] == paths, seconds=10),
          "the session has the centerlines (%r, %d)" % (gui.state["session"], paths))

    step(3)
    # 3. A long Extract: the GUI renders and answers, the session runs, the progress moves.
    if not start_long_extraction(gui, check):
        return
    before = gui.capture("during_before_drag.png")
    ticks0 = gui.state["session"]["ticks"]
    drag_in_view(gui)
    gui.run("render")
    after = gui.capture("during_after_drag.png")
    if before and after:
        a = numpy.asarray(Image.open(before)).astype(int)
        b = numpy.asarray(Image.open(after)).astype(int)
        changed = int(numpy.count_nonzero(numpy.abs(a - b).sum(axis=2) > 30))
        check(changed > 500, "the view rendered the camera drag while extracting (%d pixels "
              "changed)" % changed)
    time.sleep(1.0)
    gui.run("state")
    check(running(gui), "still extracting after the drag")
    ticks1 = gui.state["session"]["ticks"]
    check(gui.state["session"]["running"] and ticks1 > ticks0 + 100,
          "the session's loop ran while extracting (ticks %r -> %r)" % (ticks0, ticks1))
    progress = gui.widget("extractProgress").get("value")
    check(0 < progress < 100, "the progress bar shows the run's progress (%r)" % progress)

    step(4)
    # 4. Cancel: prompt, the old centerlines stay bound and drawn.
    t0 = time.time()
    gui.run("click", "cancelButton")
    stopped = gui.wait_until(lambda s: not running(gui), seconds=30, period=0.1)
    check(stopped, "Cancel stops the extraction")
    print("Cancel took %.2f s" % (time.time() - t0), flush=True)
    text = gui.widget("extractMessage").get("text", "")
    check(text.startswith("Cancelled"), "'Cancelled' beside Extract (%r)" % text)
    check(gui.state["session"]["running"] and gui.state["session"]["skeleton_paths"] == paths,
          "the session runs on the previous centerlines (%r)" % gui.state["session"])
    kept = python_value(gui, "from paraview import simple\n"
                        "o = simple.FindSource('VesselCenterline1').GetClientSideObject()\n"
                        "result = o.GetOutput().GetNumberOfCells()\n", "kept")
    check(kept == paths, "the filter still holds the previous centerlines (%r)" % kept)
    drawn = gui.capture("after_cancel.png")
    count = orange_pixels(drawn) if drawn else 0
    check(count > 150, "the previous centerlines are still drawn (%d pixels)" % count)

    step(5)
    # 5. Extract while one runs, with another range: the first is cancelled, the second runs.
    gui.run("click", "extractButton")
    check(running(gui), "the first long run started")
    gui.run("set", "lowerThreshold", 310.0)
    gui.run("click", "extractButton")
    check(running(gui), "the second run goes on")
    time.sleep(0.5)
    gui.run("state")
    check(running(gui) and not gui.widget("extractMessage").get("text", "").startswith("Cancel"),
          "the first run was replaced without a message (%r)"
          % gui.widget("extractMessage").get("text"))
    gui.run("click", "cancelButton")
    check(gui.wait_until(lambda s: not running(gui), seconds=30, period=0.1),
          "one Cancel stops the second run")

    step(6)
    # 6. Preview: the candidate region in magenta, the estimated range, nothing in the browser.
    set_full_resolution(gui, False)
    gui.run("check", "automaticRange", 1)
    gui.run("click", "stopButton")
    plain = gui.capture("before_preview.png")
    gui.run("click", "previewButton")
    check(gui.wait_until(lambda s: not running(gui), seconds=120, period=0.2), "Preview ends")
    text = gui.widget("extractMessage").get("text", "")
    check("Preview" in text and "voxels" in text, "Preview says what it shows (%r)" % text)
    check(gui.widget("previewButton").get("checked") is True, "Preview stays pressed")
    shown = gui.capture("preview.png")
    magenta = magenta_pixels(shown) if shown else 0
    check(magenta > 300 and magenta > 10 * (magenta_pixels(plain) + 1),
          "the candidate region is drawn in magenta over the MIP (%d pixels, %d before)"
          % (magenta, magenta_pixels(plain) if plain else -1))
    browser = gui.state.get("pipeline_browser", [])
    check(sorted(browser) == sorted(browser_before + ["VesselCenterline1"]),
          "Preview adds nothing to the Pipeline Browser (%r)" % browser)
    gui.run("click", "previewButton")
    hidden = gui.capture("preview_hidden.png")
    check(hidden is not None and magenta_pixels(hidden) < 20,
          "clicking Preview again hides it (%d pixels)" % (magenta_pixels(hidden) if hidden else -1))
    gui.run("click", "previewButton")
    check(gui.wait_until(lambda s: not running(gui), seconds=120, period=0.2), "Preview again")
    check(gui.click_and_wait("extractButton"), "Extract after Preview ends")
    check(gui.widget("previewButton").get("checked") is False, "Extract took the preview away")
    extracted = gui.capture("extract_after_preview.png")
    check(extracted is not None and magenta_pixels(extracted) < 20,
          "no magenta left after Extract (%d)" % (magenta_pixels(extracted) if extracted else -1))

    step(7)
    # 7. Delete the volume while an extraction runs.
    if start_long_extraction(gui, check):
        gui.python("from paraview import simple\n"
                   "for name in ('VesselTouchSession', 'VesselCenterline1', 'Angio'):\n"
                   "    proxy = simple.FindSource(name)\n"
                   "    if proxy is not None:\n"
                   "        simple.Delete(proxy)\n")
        check(gui.wait_until(lambda s: "Angio" not in s.get("sources", []), seconds=15),
              "the volume was deleted (%r)" % gui.state.get("sources"))
        check(gui.wait_until(lambda s: not running(gui), seconds=30),
              "the run ended with its volume")
        check(gui.alive(), "ParaView survives deleting the volume mid-extraction")

    step(8)
    # 8. Edit > Reset Session while an extraction runs, on a new volume.
    gui.python("from paraview import simple\n"
               "import vesseltouch\n"
               "v = simple.VesselPhantom(registrationName='Angio2', Shape='Raw angiogram',\n"
               "                         Dimensions=[160, 160, 160], Seed=2,\n"
               "                         NoiseStandardDeviation=50)\n"
               "vesseltouch.ShowAsMIP(v)\n"
               "simple.SetActiveSource(v)\n"
               "simple.Render()\n")
    check(gui.wait_until(lambda s: s["widgets"]["volumeCombo"].get("text") == "Angio2"),
          "the new volume is chosen")
    if seed_at_root(gui, check, "Angio2") and gui.click_and_wait("extractButton") and \
            start_long_extraction(gui, check):
        gui.run("trigger", "actionDelete_All")
        check(gui.answer_dialog("Delete All", "Return"), "Reset Session asked for confirmation")
        check(gui.wait_until(lambda s: "Angio2" not in s.get("sources", []), seconds=15),
              "Reset Session removed the pipeline (%r)" % gui.state.get("sources"))
        check(gui.wait_until(lambda s: not running(gui), seconds=30),
              "the run ended with the session")
        check(gui.alive(), "ParaView survives Edit > Reset Session mid-extraction")
        gui.run("state")
        check(gui.widget("volumeCombo").get("items") == [], "the chooser is empty after it")

    step(9)
    # 9. A shaded volume (the phantom's bias field at +/- 60 %: an MR coil's falling
    # sensitivity): Preview and Extract say that the shading was corrected and in which units
    # the range is (session 21, vtouch::ShadingField).
    gui.python("from paraview import simple\n"
               "import vesseltouch\n"
               "v = simple.VesselPhantom(registrationName='Shaded', Shape='Raw angiogram',\n"
               "                         Dimensions=[128, 128, 128], Seed=1,\n"
               "                         NoiseStandardDeviation=20, BiasAmplitude=0.6)\n"
               "vesseltouch.ShowAsMIP(v)\n"
               "simple.SetActiveSource(v)\n"
               "simple.Render()\n")
    check(gui.wait_until(lambda s: s["widgets"]["volumeCombo"].get("text") == "Shaded"),
          "the shaded volume is chosen")
    gui.run("check", "automaticRange", 1)
    if seed_at_root(gui, check, "Shaded"):
        gui.run("click", "previewButton")
        check(gui.wait_until(lambda s: not running(gui), seconds=120, period=0.2),
              "Preview of the shaded volume ends")
        text = gui.widget("extractMessage").get("text", "")
        check("Preview" in text and "Shading corrected" in text and "seed's intensities" in text,
              "Preview says the shading was corrected (%r)" % text)
        gui.run("click", "previewButton")
        check(gui.click_and_wait("extractButton"), "Extract of the shaded volume ends")
        text = gui.widget("extractMessage").get("text", "")
        check("centerline path" in text and "Shading corrected" in text,
              "Extract says the shading was corrected (%r)" % text)
        gui.capture("shaded_extracted.png")
    check(gui.alive(), "ParaView is running at the end")


run_test("gui_background_extract", "angiogram", body)

"""Start-up script of the main job: opens the built-in phantom as a MIP.

Runs inside the ParaView GUI (``paraview --script=...``, plugin loaded with ``--plugins``) and in
pvpython/pvbatch (headless). Environment:
  VESSELTOUCH_PLUGIN       plugin library to load when it is not loaded yet (headless runs)
  VESSELTOUCH_OUTPUT_DIR   if set: write screenshot.png (the render view) and report.txt there
  VESSELTOUCH_DONE_FLAG    if set: a file written last, when the scene is ready
  VESSELTOUCH_VIEW_SIZE    view size in pixels for the screenshot, "800x600" by default
"""

import os
import sys
import time
import traceback


def _ensure_plugin(simple):
    try:
        simple.VesselPhantom  # noqa: B018 (present once the plugin is loaded)
        return "already loaded"
    except AttributeError:
        pass
    path = os.environ.get("VESSELTOUCH_PLUGIN")
    if not path:
        raise RuntimeError("the VesselTouch plugin is not loaded and VESSELTOUCH_PLUGIN is not set")
    simple.LoadPlugin(path, ns=vars(simple))
    return path


def _report_lines(vesseltouch, phantom, rep, view, seconds):
    info = phantom.GetDataInformation(0)
    line_info = phantom.GetDataInformation(1)
    extent = info.GetExtent()
    scalars = info.GetPointDataInformation().GetAttributeInformation(0)
    lines = ["VesselTouch main job report", ""]
    lines += ["%-12s %s" % (k + ":", v) for k, v in sorted(vesseltouch.build_info().items())]
    lines += [
        "",
        "dataset:     %s (%s)" % ("VesselPhantom1", phantom.Shape),
        "volume:      %d x %d x %d voxels, %s in [%g, %g]" % (
            extent[1] - extent[0] + 1, extent[3] - extent[2] + 1, extent[5] - extent[4] + 1,
            scalars.GetName(), *scalars.GetComponentRange(0)),
        "centerline:  %d polylines, %d points" % (
            line_info.GetNumberOfCells(), line_info.GetNumberOfPoints()),
        "display:     %s, blend mode %d (1 = maximum intensity)" % (
            rep.Representation, vesseltouch.mip.BlendMode(rep)),
        "view:        %d x %d pixels" % tuple(view.ViewSize),
        "set-up time: %.2f s" % seconds,
    ]
    return lines


def main():
    from paraview import simple

    start = time.time()
    plugin = _ensure_plugin(simple)
    import vesseltouch

    view = simple.GetActiveViewOrCreate("RenderView")
    size = os.environ.get("VESSELTOUCH_VIEW_SIZE", "800x600").lower().split("x")
    output_dir = os.environ.get("VESSELTOUCH_OUTPUT_DIR")
    if output_dir:
        view.ViewSize = [int(size[0]), int(size[1])]
    phantom, rep = vesseltouch.OpenDefaultScene(view)
    seconds = time.time() - start

    if output_dir:
        os.makedirs(output_dir, exist_ok=True)
        screenshot = os.path.join(output_dir, "screenshot.png")
        simple.SaveScreenshot(screenshot, view, ImageResolution=[int(size[0]), int(size[1])])
        lines = _report_lines(vesseltouch, phantom, rep, view, seconds)
        lines += ["plugin:      %s" % plugin, "screenshot:  %s" % screenshot]
        with open(os.path.join(output_dir, "report.txt"), "w") as report:
            report.write("\n".join(lines) + "\n")
        print("\n".join(lines))
    flag = os.environ.get("VESSELTOUCH_DONE_FLAG")
    if flag:
        with open(flag, "w") as done:
            done.write("ok\n")


try:
    main()
except Exception:  # report clearly, and make headless runs fail
    traceback.print_exc()
    flag = os.environ.get("VESSELTOUCH_DONE_FLAG")
    if flag:
        with open(flag, "w") as done:
            done.write("error\n" + traceback.format_exc())
    if not hasattr(sys, "ps1") and os.environ.get("VESSELTOUCH_OUTPUT_DIR"):
        sys.exit(1)

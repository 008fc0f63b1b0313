"""Show as MIP: Volume representation with blend mode 1, a grey map, and a non-blank image."""

import os
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from vtouch_testing import Check, image_statistics, plugin_path  # noqa: E402

from paraview import simple  # noqa: E402

check = Check("MIP")
simple.LoadPlugin(plugin_path(), ns=globals())
import vesseltouch  # noqa: E402

view = simple.CreateView("RenderView")
view.ViewSize = [400, 300]
phantom = VesselPhantom(Shape="Helix", Dimensions=[64, 64, 64])  # noqa: F821
rep = vesseltouch.ShowAsMIP(phantom, view)
check.equal(rep.Representation, "Volume", "representation")
check.equal(vesseltouch.mip.BlendMode(rep), 1, "blend mode is maximum intensity")
check.equal(rep.BlendMode, "Maximum Intensity", "the blend mode's name tells the truth")
check.equal(rep.ColorArrayName[1], "Intensity", "coloured by the scalars")

with tempfile.TemporaryDirectory() as tmp:
    png = os.path.join(tmp, "mip.png")
    view.Background = [0, 0, 0]
    view.UseColorPaletteForBackground = 0
    simple.SaveScreenshot(png, view, ImageResolution=[400, 300])
    bright, spread = image_statistics(png)
check.true(0.01 < bright < 0.5, "the MIP shows vessels, not a blank or saturated image (%.3f bright)"
           % bright)
check.true(spread > 10, "the MIP has contrast (grey std %.1f)" % spread)

# The default scene of the main job.
phantom2, rep2 = vesseltouch.OpenDefaultScene(view)
check.equal(phantom2.Shape, "Tree", "default scene phantom")
check.equal(vesseltouch.mip.BlendMode(rep2), 1, "default scene is a MIP")

# A polyline is not an image: a clear error, no representation change.
try:
    vesseltouch.ShowAsMIP(phantom, view, port=1)
    check.true(False, "ShowAsMIP on a polyline must raise")
except ValueError as error:
    check.true("image" in str(error), "clear message for a non-image: %s" % error)

check.finish()

"""Show as MIP: Volume representation with blend mode 1, a grey map, and a non-blank image.

A Python state of a MIP (what File > Save State writes as .py: `BlendMode = 'Maximum Intensity'`)
runs in a fresh pvpython that loaded the plugin and never ran ShowAsMIP: the plugin names blend
mode 1 in the Volume representation's definition when it loads (issue 20, item 11's follow-up)."""

import json
import os
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from vtouch_testing import Check, image_statistics, plugin_path, run_pvpython  # noqa: E402

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

# A Python state of the MIP, as the GUI's File > Save State (.py) writes it.
from paraview import smstate  # noqa: E402

for source in list(simple.GetSources().values()):
    if source is not phantom:
        simple.Hide(source, view)
state_text = smstate.get_state()
check.true("BlendMode = 'Maximum Intensity'" in state_text,
           "the Python state names the MIP's blend mode (%s)"
           % [line.strip() for line in state_text.splitlines() if "BlendMode" in line])
probe = r"""
import json
from paraview import simple
%s
exec(open(%r).read())
reps = [r for r in simple.GetRepresentations().values()
        if r.GetProperty("BlendMode") is not None and r.Representation == "Volume"]
print("PROBE=" + json.dumps([r.SMProxy.GetProperty("BlendMode").GetElement(0) for r in reps]))
"""
with tempfile.TemporaryDirectory() as tmp:
    state_py = os.path.join(tmp, "mip_state.py")
    with open(state_py, "w") as f:
        f.write(state_text)
    # A fresh pvpython: the plugin loaded (as a user does before running a state that uses its
    # sources), vesseltouch never imported, ShowAsMIP never run.
    code, output = run_pvpython(probe % ("simple.LoadPlugin(%r, ns=globals())" % plugin_path(),
                                         state_py), timeout=180)
    lines = [line for line in output.splitlines() if line.startswith("PROBE=")]
    check.equal(code, 0, "the Python state loads in a fresh pvpython: %s" % output[-1500:])
    modes = json.loads(lines[-1][len("PROBE="):]) if lines else []
    check.true(modes and all(mode == 1 for mode in modes),
               "its MIP is maximum intensity: %r" % modes)
    # Without the plugin's naming (no plugin loaded) the same line is refused: what the plugin
    # fixes. The state's own sources need the plugin, so this runs only the blend-mode line.
    code, output = run_pvpython(
        "from paraview import simple\n"
        "rep = simple.Show(simple.Wavelet())\n"
        "rep.SetRepresentationType('Volume')\n"
        "rep.BlendMode = 'Maximum Intensity'\n")
    check.true(code != 0 and "Maximum Intensity" in output,
               "without the plugin ParaView refuses the name (code %s)" % code)

check.finish()

"""The README's scripting example as code: the fenced block marked ```python vesseltouch-example.

Both the README test (Testing/ParaView/test_readme_example.py, build tree) and the package test
(package/load_unpacked.py, unpacked CPack archive) run exactly this block, so the README cannot
drift from what works. The block loads the plugin from the build tree's path; the tests put the
plugin under test in its place.
"""

import re

#: The plugin path the README's example names (relative to the checkout, as after run.sh).
README_PLUGIN = "build/lib/paraview-5.11/plugins/VesselTouch/VesselTouch.so"

#: Checks appended to the example: it must leave these names behind, with these properties.
CHECKS = r'''
import numpy as _np
assert isinstance(log["force"], _np.ndarray) and log["force"].shape == (len(log["time"]), 2)
assert log["position"].shape == (len(log["time"]), 3)
assert (log["state"] == 1).mean() > 0.5, "the example traces a vessel"
assert _np.isfinite(log["force"]).all() and _np.abs(log["force"]).max() > 0.01
assert stats["ticks"] > 0 and stats["nominal_rate_Hz"] == 1000.0
assert vesseltouch.logic() is s, "the example drives the panel's session"
assert set(measures) >= {"force_magnitude", "force_along_travel", "depth_mm"}
print("README EXAMPLE OK", len(log["time"]), "ticks")
'''


def extract(readme_path, plugin_path):
    """The example's code with ``plugin_path`` loaded instead of the README's build path."""
    text = open(readme_path, encoding="utf-8").read()
    blocks = re.findall(r"^```python vesseltouch-example\n(.*?)^```", text, re.M | re.S)
    if len(blocks) != 1:
        raise RuntimeError("%s: expected one ```python vesseltouch-example block, found %d"
                           % (readme_path, len(blocks)))
    code = blocks[0]
    if code.count(README_PLUGIN) != 1:
        raise RuntimeError("the README example must load %r once" % README_PLUGIN)
    return code.replace(README_PLUGIN, plugin_path)

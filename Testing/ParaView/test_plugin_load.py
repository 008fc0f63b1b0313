"""The plugin loads by path (twice), through PV_PLUGIN_PATH, through the built tree's plugin
configuration file, and into a pvpython without a display, without crashing."""

import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from vtouch_testing import Check, plugin_path, run_pvpython  # noqa: E402

from paraview import simple  # noqa: E402

check = Check("plugin load")
path = plugin_path()

simple.LoadPlugin(path, ns=globals())
check.true("VesselPhantom" in globals(), "LoadPlugin puts VesselPhantom in the namespace")
simple.LoadPlugin(path, ns=globals())  # a second load must be harmless
phantom = VesselPhantom(Dimensions=[16, 16, 16])  # noqa: F821
phantom.UpdatePipeline()
check.equal(phantom.GetDataInformation(0).GetNumberOfPoints(), 16 ** 3, "phantom after two loads")

import vesseltouch  # noqa: E402  (embedded in the plugin)
info = vesseltouch.build_info()
for component in ("VesselTouch", "ParaView", "VTK", "ITK", "hidapi"):
    check.true(bool(info.get(component)), "build_info has a %s version: %r" % (component, info))
check.true(info["VTK"].startswith("9.2"), "built against ParaView's VTK 9.2: %r" % info["VTK"])

probe = ("from paraview.simple import *\n"
         "p = VesselPhantom(Dimensions=[16, 16, 16], RadiusFraction=0.1); p.UpdatePipeline()\n"
         "print('POINTS', p.GetDataInformation(0).GetNumberOfPoints())\n")

# PV_PLUGIN_PATH: plugins in those folders load when pvpython starts.
rc, out = run_pvpython(probe, env={"PV_PLUGIN_PATH": os.path.dirname(path)})
check.true(rc == 0 and "POINTS 4096" in out, "PV_PLUGIN_PATH loads the plugin (rc %d):\n%s" % (rc, out))

# The built tree's plugin configuration file lists the plugin; load it by name from there.
config = os.environ["VESSELTOUCH_PLUGIN_CONFIG"]
check.true(os.path.exists(config), "plugin configuration file exists: %s" % config)
rc, out = run_pvpython("from paraview.simple import *\n"
                       "LoadDistributedPlugin('VesselTouch', ns=globals())\n" + probe,
                       env={"PV_PLUGIN_CONFIG_FILE": config})
check.true(rc == 0 and "POINTS 4096" in out, "PV_PLUGIN_CONFIG_FILE + LoadDistributedPlugin (rc %d):\n%s"
           % (rc, out))

# No display at all: loading and computing must not crash (rendering is not attempted).
rc, out = run_pvpython("from paraview.simple import *\nLoadPlugin(%r, ns=globals())\n%s" % (path, probe),
                       env={"DISPLAY": ""})
check.true(rc == 0 and "POINTS 4096" in out, "load without a display (rc %d):\n%s" % (rc, out))

check.finish()

"""The extension download: unpack the CPack .tar.gz into a temporary folder, check what it holds
(the plugin and its VTK module, the plugin configuration file, the Python package, the .ui
layouts, the device presets, README and INSTALL notes), then load the plugin from there into a
clean pvpython (nothing from the build tree on any path) and run the README's scripting example
(package/readme_example.py) from the unpacked README."""

import glob
import os
import subprocess
import sys
import tarfile
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import readme_example  # noqa: E402
from package_archive import newest_archive  # noqa: E402

archive_path = newest_archive()

#: What the package must hold (globs relative to its top folder).
REQUIRED = (
    "INSTALL.md",
    "README.md",
    "lib/paraview-5.11/plugins/VesselTouch.xml",
    "lib/paraview-5.11/plugins/VesselTouch/VesselTouch.so",
    "lib/paraview-5.11/plugins/VesselTouch/libvtkVesselTouchLogic*.so*",
    "share/VesselTouch/python/vesseltouch/__init__.py",
    "share/VesselTouch/python/vesseltouch/session.py",
    "share/VesselTouch/python/vesseltouch/centerlines.py",
    "share/VesselTouch/ServerManager/VesselTouchHapticSession.xml",
    "share/VesselTouch/UI/qVesselTouchForceLawWidget.ui",
    "share/VesselTouch/UI/qVesselTouchLoopStatsWidget.ui",
    "share/VesselTouch/Presets/openffboard-2axis.json",
)


def plugin_embeds_python(plugin):
    """The plugin carries the vesseltouch package itself (PYTHON_MODULES embeds the sources)."""
    data = open(plugin, "rb").read()
    return b"def ExtractCenterlines" in data and b"def logic" in data


with tempfile.TemporaryDirectory(prefix="vesseltouch-package-") as tmp:
    with tarfile.open(archive_path) as archive:
        archive.extractall(tmp)
    plugins = glob.glob(os.path.join(tmp, "*", "lib", "paraview-5.11", "plugins", "VesselTouch",
                                     "VesselTouch.so"))
    if len(plugins) != 1:
        sys.exit("the package does not hold exactly one VesselTouch.so: %r" % plugins)
    root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.dirname(os.path.dirname(plugins[0])))))
    missing = [p for p in REQUIRED if not glob.glob(os.path.join(root, p))]
    if missing:
        sys.exit("the package lacks %s" % ", ".join(missing))
    # The development install (headers, static libraries, CMake package) is for other host
    # adapters: it is installed with --component Development only, never into the download.
    development = [p for p in ("include", "lib/cmake", "lib/libVesselTouch*.a")
                   if glob.glob(os.path.join(root, p))]
    if development:
        sys.exit("the download carries the development install: %s" % ", ".join(development))
    if not plugin_embeds_python(plugins[0]):
        sys.exit("the packaged plugin does not embed the vesseltouch Python package")

    smoke = ("from paraview.simple import *\n"
             "LoadPlugin(%r, ns=globals())\n"
             "import vesseltouch\n"
             "p = VesselPhantom(Dimensions=[32, 32, 32])\n"
             "rep = vesseltouch.ShowAsMIP(p)\n"
             "Render()\n"
             "assert vesseltouch.mip.BlendMode(rep) == 1\n"
             "Delete(GetActiveView())\n"  # pvpython under Xvfb crashes at exit with a live view
             "print('LOADED', vesseltouch.version(), p.GetDataInformation(0).GetNumberOfPoints())\n"
             % plugins[0])
    example = readme_example.extract(os.path.join(root, "README.md"), plugins[0])
    env = {k: v for k, v in os.environ.items() if not k.startswith(("VESSELTOUCH_", "PV_PLUGIN"))}
    env["LD_LIBRARY_PATH"] = ""
    env["PYTHONPATH"] = ""
    pvpython = os.environ.get("VESSELTOUCH_PVPYTHON", "pvpython")
    for name, code, expected in (("smoke", smoke, ("LOADED", "32768")),
                                 ("README example", example + readme_example.CHECKS,
                                  ("README EXAMPLE OK",))):
        result = subprocess.run([pvpython, "-c", code], cwd=tmp, stdout=subprocess.PIPE,
                                stderr=subprocess.STDOUT, env=env, universal_newlines=True,
                                timeout=240)
        print("--- %s (exit %d)\n%s" % (name, result.returncode, result.stdout))
        if result.returncode != 0 or not all(e in result.stdout for e in expected):
            sys.exit("the unpacked plugin did not run the %s cleanly (exit %d)"
                     % (name, result.returncode))
        if name == "README example" and "build/lib" in result.stdout:
            sys.exit("the README example reached into the build tree")
print("package test passed:", os.path.basename(archive_path))

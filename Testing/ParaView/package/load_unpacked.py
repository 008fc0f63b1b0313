"""The extension download: unpack the CPack .tar.gz into a temporary folder and load the plugin
from there into a clean pvpython (nothing from the build tree on any path)."""

import glob
import os
import subprocess
import sys
import tarfile
import tempfile

package_dir = os.environ["VESSELTOUCH_PACKAGE_DIR"]
archives = sorted(glob.glob(os.path.join(package_dir, "VesselTouch-*.tar.gz")))
if not archives:
    sys.exit("no VesselTouch-*.tar.gz in %s" % package_dir)

with tempfile.TemporaryDirectory(prefix="vesseltouch-package-") as tmp:
    with tarfile.open(archives[-1]) as archive:
        archive.extractall(tmp)
    plugins = glob.glob(os.path.join(tmp, "*", "lib", "paraview-5.11", "plugins", "VesselTouch",
                                     "VesselTouch.so"))
    if len(plugins) != 1:
        sys.exit("the package does not hold exactly one VesselTouch.so: %r" % plugins)
    root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.dirname(os.path.dirname(plugins[0])))))
    for required in ("INSTALL.md", "lib/paraview-5.11/plugins/VesselTouch.xml"):
        if not os.path.exists(os.path.join(root, required)):
            sys.exit("the package lacks %s" % required)
    code = ("from paraview.simple import *\n"
            "LoadPlugin(%r, ns=globals())\n"
            "import vesseltouch\n"
            "p = VesselPhantom(Dimensions=[32, 32, 32])\n"
            "rep = vesseltouch.ShowAsMIP(p)\n"
            "Render()\n"
            "assert vesseltouch.mip.BlendMode(rep) == 1\n"
            "print('LOADED', vesseltouch.version(), p.GetDataInformation(0).GetNumberOfPoints())\n"
            % plugins[0])
    env = {k: v for k, v in os.environ.items() if not k.startswith(("VESSELTOUCH_", "PV_PLUGIN"))}
    env["LD_LIBRARY_PATH"] = ""
    result = subprocess.run([os.environ.get("VESSELTOUCH_PVPYTHON", "pvpython"), "-c", code],
                            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, env=env,
                            universal_newlines=True, timeout=120)
    print(result.stdout)
    if result.returncode != 0 or "LOADED" not in result.stdout or "32768" not in result.stdout:
        sys.exit("the unpacked plugin did not load and run (exit %d)" % result.returncode)
print("package test passed:", os.path.basename(archives[-1]))

"""The extension download carries no test code (issue 18, item 4): unpack the CPack .tar.gz and
check that it holds no file of the GUI tests' VesselTouchTestDriver plugin, and that no shared library in it defines or names a test class (the GUI test driver, the panel
self-test, the fake HID transport, the hooks' plugin) or reads a test hook's environment variable
(VESSELTOUCH_GUI_*, VESSELTOUCH_AGENT_REPORT). `nm -D` lists each library's dynamic symbols and
the raw bytes are searched for the names, so a symbol and a string are both caught."""

import glob
import os
import subprocess
import sys
import tarfile
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from package_archive import newest_archive  # noqa: E402


#: Names that only test code has.
TEST_NAMES = (
    "pqVesselTouchTestDriver",
    "pqVesselTouchTestHooks",
    "pqVesselTouchPanelSelfTest",
    "FakeHidTransport",
    "FakeHidDevice",
    "VesselTouchTestDriver",
    "VESSELTOUCH_GUI_",
    "VESSELTOUCH_AGENT_REPORT",
    "VESSELTOUCH_DONE_FLAG",
)
#: Files that must not be in the download (globs relative to its top folder).
FORBIDDEN_FILES = ("**/VesselTouchTestDriver*",)

failures = []
with tempfile.TemporaryDirectory(prefix="vesseltouch-package-") as work:
    archive_path = newest_archive()
    with tarfile.open(archive_path) as archive:
        archive.extractall(work)
    tops = os.listdir(work)
    if len(tops) != 1:
        sys.exit("expected one top folder in %s, found %s" % (archive_path, tops))
    top = os.path.join(work, tops[0])
    for pattern in FORBIDDEN_FILES:
        for path in glob.glob(os.path.join(top, pattern), recursive=True):
            failures.append("the package holds %s" % os.path.relpath(path, top))
    libraries = [p for p in glob.glob(os.path.join(top, "**", "*.so*"), recursive=True)
                 if os.path.isfile(p) and not os.path.islink(p)]
    if not any(os.path.basename(p) == "VesselTouch.so" for p in libraries):
        failures.append("the package holds no VesselTouch.so")
    for library in libraries:
        name = os.path.relpath(library, top)
        symbols = subprocess.run(["nm", "-D", "-C", "--defined-only", library],
                                 capture_output=True, text=True, check=True).stdout
        with open(library, "rb") as f:
            data = f.read()
        found = len(failures)
        for test_name in TEST_NAMES:
            if test_name in symbols:
                failures.append("%s defines a symbol named %s" % (name, test_name))
            elif test_name.encode() in data:
                failures.append("%s contains the string %s" % (name, test_name))
        print("%s: %d dynamic symbols, %s" % (name, symbols.count("\n"),
              "test code found" if len(failures) > found else "no test code"))

for failure in failures:
    print("FAIL: " + failure)
sys.exit(1 if failures else 0)

"""The extension download the package tests read: the newest VesselTouch-*.tar.gz that
Package.Create wrote into $VESSELTOUCH_PACKAGE_DIR."""

import glob
import os
import sys


def newest_archive():
    package_dir = os.environ["VESSELTOUCH_PACKAGE_DIR"]
    archives = sorted(glob.glob(os.path.join(package_dir, "VesselTouch-*.tar.gz")))
    if not archives:
        sys.exit("no VesselTouch-*.tar.gz in %s" % package_dir)
    return archives[-1]

"""Small helpers shared by the pvpython tests (imported from the test folder)."""

import os
import subprocess
import sys


class Check:
    """Collects failures so a test reports every broken expectation, then exits non-zero."""

    def __init__(self, name):
        self.name = name
        self.failures = []
        self.count = 0

    def true(self, condition, message):
        """Records the check; returns `condition`, so a caller can skip what depends on it."""
        self.count += 1
        if not condition:
            self.failures.append(message)
            print("FAIL: " + message, flush=True)
        return condition

    def equal(self, actual, expected, message):
        self.true(actual == expected, "%s: got %r, expected %r" % (message, actual, expected))

    def near(self, actual, expected, tolerance, message):
        self.true(abs(actual - expected) <= tolerance,
                  "%s: got %r, expected %r +/- %r" % (message, actual, expected, tolerance))

    def finish(self):
        if self.failures:
            print("%s: %d of %d checks failed" % (self.name, len(self.failures), self.count))
            sys.exit(1)
        print("%s: all %d checks passed" % (self.name, self.count))
        if self.count == 0:
            sys.exit("no check ran")


def plugin_path():
    path = os.environ.get("VESSELTOUCH_PLUGIN")
    if not path or not os.path.exists(path):
        sys.exit("VESSELTOUCH_PLUGIN does not name the built plugin: %r" % path)
    return path


def test_volume_writer():
    """The ITK test volume writer (Testing/Logic/IO/vtouchWriteTestVolume): from
    VESSELTOUCH_TEST_VOLUME_WRITER, or beside the plugin's build tree."""
    path = os.environ.get("VESSELTOUCH_TEST_VOLUME_WRITER")
    if not path:
        # <build>/lib/paraview-5.11/plugins/VesselTouch/VesselTouch.so -> <build>
        build = os.path.abspath(os.path.join(os.path.dirname(plugin_path()), *[os.pardir] * 4))
        path = os.path.join(build, "Testing", "Logic", "IO", "vtouchWriteTestVolume")
    if not os.access(path, os.X_OK):
        raise RuntimeError("test volume writer not found: %s (set VESSELTOUCH_TEST_VOLUME_WRITER)"
                           % path)
    return path


def run_pvpython(code, env=None, timeout=120):
    """Runs `code` in a fresh pvpython; returns (exit code, stdout + stderr)."""
    full_env = dict(os.environ)
    full_env.update(env or {})
    result = subprocess.run([os.environ.get("VESSELTOUCH_PVPYTHON", "pvpython"), "-c", code],
                            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, env=full_env,
                            timeout=timeout, universal_newlines=True)
    return result.returncode, result.stdout


def image_statistics(png_path):
    """(fraction of pixels brighter than 25 % grey, standard deviation of the grey level)."""
    from paraview.vtk.util.numpy_support import vtk_to_numpy
    from vtkmodules.vtkIOImage import vtkPNGReader
    reader = vtkPNGReader()
    reader.SetFileName(png_path)
    reader.Update()
    image = reader.GetOutput()
    pixels = vtk_to_numpy(image.GetPointData().GetScalars()).astype(float)
    grey = pixels[:, :3].mean(axis=1) if pixels.ndim == 2 else pixels
    return float((grey > 64).mean()), float(grey.std())

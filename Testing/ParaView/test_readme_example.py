"""The README's "Scripting" example runs as written (in a fresh pvpython, with the built plugin)
and leaves a log, trace measures and loop statistics behind (see package/readme_example.py).
Then, in this process, the parts of the Python API the example only touches: logic() adopts the
"VesselTouchSession" proxy whoever registered it and replaces a deleted one; ExtractCenterlines
with a seed and an upper threshold; SaveLog as CSV; the camera frame from explicit matrices."""

import os
import subprocess
import sys
import tempfile

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, here)
sys.path.insert(0, os.path.join(here, "package"))
from vtouch_testing import Check, plugin_path  # noqa: E402
import readme_example  # noqa: E402

check = Check("README example")
readme = os.path.join(os.environ.get("VESSELTOUCH_SOURCE_DIR", os.path.join(here, "..", "..")),
                      "README.md")
code = readme_example.extract(readme, plugin_path())
check.true("vesseltouch.ExtractCenterlines(" in code and "vesseltouch.logic()" in code,
           "the example extracts centerlines and uses the shared session")
with tempfile.TemporaryDirectory(prefix="vesseltouch-readme-") as work:  # SaveLog writes here
    result = subprocess.run([os.environ.get("VESSELTOUCH_PVPYTHON", "pvpython"), "-c",
                             code + readme_example.CHECKS], cwd=work, stdout=subprocess.PIPE,
                            stderr=subprocess.STDOUT, universal_newlines=True, timeout=240)
    status, output = result.returncode, result.stdout
    print(output)
    check.true(os.path.exists(os.path.join(work, "vesseltouch-trace.npz")),
               "the example saved its log")
check.equal(status, 0, "the example exits cleanly")
check.true("README EXAMPLE OK" in output, "the example's results pass the checks")
check.true("Traceback" not in output, "no Python error")

# --- logic(): the session the panel shows. ---
import numpy  # noqa: E402
from paraview import servermanager, simple  # noqa: E402

simple.LoadPlugin(plugin_path(), ns=globals())
import vesseltouch  # noqa: E402

pxm = servermanager.ProxyManager()
check.true(pxm.GetProxy("sources", vesseltouch.SESSION_NAME) is None, "no session at start")
# As the panel does from C++: a proxy registered under the name, created elsewhere.
panel_made = vesseltouch.HapticSession(registrationName=vesseltouch.SESSION_NAME).proxy
shared = vesseltouch.logic()
check.true(shared.proxy.SMProxy.__this__ == panel_made.SMProxy.__this__,
           "logic() adopts the registered VesselTouchSession proxy")
check.true(vesseltouch.logic() is shared, "logic() returns one object while the proxy lives")
simple.Delete(panel_made)
fresh = vesseltouch.logic()
check.true(fresh is not shared and pxm.GetProxy("sources", vesseltouch.SESSION_NAME) is not None,
           "after Delete, logic() registers a new session")
simple.ResetSession()
simple.LoadPlugin(plugin_path(), ns=globals())
pxm = servermanager.ProxyManager()
after_reset = vesseltouch.logic()
check.true(after_reset is not fresh and pxm.GetProxy("sources", vesseltouch.SESSION_NAME)
           is not None, "after ResetSession, logic() registers a new session")
check.equal(after_reset.GetLastError(), "", "the new session works")

# --- ExtractCenterlines: seed and thresholds. ---
volume = VesselPhantom(Shape="Tree", Dimensions=[64, 64, 64], NoiseStandardDeviation=0.0)  # noqa: F821
whole = vesseltouch.ExtractCenterlines(volume, lower=550)
check.equal(whole.LowerThreshold, 550.0, "lower threshold set")
check.true(whole.GetDataInformation().GetNumberOfPoints() > 20, "the tree has a centerline")
analytic = servermanager.Fetch(volume, idx=1)
seeded = vesseltouch.ExtractCenterlines(volume, seed=analytic.GetPoint(0), lower=550, upper=1e6)
check.true(seeded.UseSeedPoint == 1 and list(seeded.SeedPoint) == list(analytic.GetPoint(0)),
           "the seed point is used")
check.true(seeded.GetDataInformation().GetNumberOfPoints() > 20, "the seeded tree is extracted")
default = vesseltouch.ExtractCenterlines(volume)
estimated = vesseltouch.centerlines.IntensityRangeUsed(default)
check.true(default.AutomaticIntensityRange == 1 and 400.0 < estimated[0] < 700.0,
           "default: the range is estimated (lower %g, half maximum)" % estimated[0])
shading = vesseltouch.centerlines.ShadingCorrection(default)
check.true(shading is not None and not shading["corrected"] and shading["message"],
           "an unshaded volume is left as it is (%r)" % shading)
shaded = VesselPhantom(Shape="Raw angiogram", Dimensions=[96, 96, 96], Seed=1,  # noqa: F821
                       BiasAmplitude=0.6)
shaded_lines = vesseltouch.ExtractCenterlines(
    shaded, seed=servermanager.Fetch(shaded, idx=1).GetPoint(0))
shading = vesseltouch.centerlines.ShadingCorrection(shaded_lines)
check.true(shading["corrected"] and shading["gain_span"][0] < 1.0 <= shading["gain_span"][1]
           and shaded_lines.GetDataInformation().GetNumberOfPoints() > 100,
           "a shaded raw angiogram is corrected before its range (%r)" % shading)
check.true(vesseltouch.centerlines.ShadingCorrection(whole) is None,
           "no shading report when the range is given (%r)"
           % vesseltouch.centerlines.ShadingCorrection(whole))
try:
    vesseltouch.ExtractCenterlines(whole)
    check.true(False, "a polydata input raises")
except ValueError:
    check.true(True, "a polydata input raises")

# --- Bind, SaveLog (CSV), GetCameraFrame from matrices. ---
s = after_reset.Bind(whole)
check.true(s.GetStatus()["paths"] >= 1, "Bind reads the centerline into the session")
s.SetDevice("simulated")
s.SetHandSweep(path=0, speed_mm_per_s=60.0)
log = s.RunOffline(0.5)
with tempfile.TemporaryDirectory() as work:
    csv = s.SaveLog(os.path.join(work, "log.csv"), log)
    table = numpy.genfromtxt(csv, delimiter=",", names=True)
    check.equal(len(table), 500, "CSV: one row per tick")
    check.true({"time", "force_0", "force_1", "position_2", "depth_mm"} <= set(table.dtype.names),
               "CSV columns: %s" % (table.dtype.names,))
frame = s.GetCameraFrame()
from vtkmodules.vtkRenderingCore import vtkCamera  # noqa: E402
camera = vtkCamera()
camera.SetPosition(*frame[0])
camera.SetFocalPoint(*[p + 100.0 * f for p, f in zip(frame[0], frame[3])])
camera.SetViewUp(*frame[2])
s.SetCameraMatrices(camera.GetModelViewTransformMatrix(),
                    camera.GetProjectionTransformMatrix(1.0, -1, 1), size=(400, 400))
explicit = s.GetCameraFrame()
for a, b, name in zip(frame, explicit, ("position", "right", "up", "forward")):
    check.true(float(numpy.abs(numpy.subtract(a, b)).max()) < 1e-6,
               "camera frame from matrices: %s" % name)
check.true(bool(numpy.isfinite(s.GetTraceMeasures(log)["depth_mm"]).all()), "depths finite")
check.finish()

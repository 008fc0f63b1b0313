"""The one table of haptic parameters (Logic/Haptics/vtouchHapticParameters.def) seen from Python:
every parameter goes Python -> proxy property -> the C++ session's HapticParameters (read back
through AppliedHapticParametersInfo); the proxy's defaults are the C++ defaults; out-of-range
values are refused with a message naming the parameter, value, range and unit, from Python and
from the VTK facade, and the old value stays; state files carry every parameter to the C++
session; a session whose every parameter is written from the table's defaults (as the panel
writes them) renders the same forces as one left at its defaults, and one default drifted by
5 % does not."""

import atexit
import json
import os
import shutil
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from vtouch_testing import Check, plugin_path, run_pvpython  # noqa: E402

from paraview import simple  # noqa: E402

check = Check("HapticParameters")
simple.LoadPlugin(plugin_path(), ns=globals())
import vesseltouch  # noqa: E402
import numpy  # noqa: E402

phantom = VesselPhantom(Shape="Helix", Dimensions=[48, 48, 48])  # noqa: F821
session = vesseltouch.HapticSession(phantom)
names = session.HapticParameterNames()
described = session.DescribeHapticParameters()
applied = session.GetHapticParameters()
check.true(len(names) >= 40, "the session lists the table's parameters (%d)" % len(names))
check.true("IdleDwell" in names and "ProxyKappaLow" in names and "TracerRule" in names,
           "parameters without a hand-written property before are there too")


def other_value(name, entry):
    """A value in the parameter's range other than its default (whole numbers for integers)."""
    low, high = entry["range"]
    default = entry["default"]
    if session.proxy.SMProxy.GetProperty(name).GetClassName() == "vtkSMIntVectorProperty":
        return default + 1.0 if default < high else default - 1.0
    return 0.5 * (default + high) if default < high else 0.5 * (low + default)


# Defaults: the proxy's (generated XML) and the C++ struct's are the same numbers.
for name in names:
    check.equal(applied[name], described[name]["default"], "%s: C++ default = proxy default" % name)

# Python -> proxy -> HapticParameters, one parameter at a time, then back to its default.
for name in names:
    entry = described[name]
    value = other_value(name, entry)
    session.SetHapticParameters(**{name: value})
    now = session.GetHapticParameters()
    check.equal(now[name], value, "%s reaches the C++ HapticParameters" % name)
    check.equal(float(session.proxy.SMProxy.GetProperty(name).GetElement(0)), value, "%s on the proxy" % name)
    others = [n for n in names if n != name and now[n] != described[n]["default"]]
    check.equal(others, [], "setting %s changes nothing else" % name)
    session.SetHapticParameters(**{name: entry["default"]})

# Out of range from Python: ValueError with the session's message; the old value stays.
session.SetHapticParameters(LdgfLambda=0.02)
for bad, expected in (({"LdgfLambda": 20.0}, ["LdgfLambda = 20 mm", "[0, 10 mm]"]),
                      ({"ForceLaw": 7}, ["ForceLaw = 7", "[0, 4]"]),
                      ({"ProxyTangentDrag": 2}, ["ProxyTangentDrag = 2"]),
                      ({"TracerRule": 0.5}, ["TracerRule = 0.5", "whole number"])):
    try:
        session.SetHapticParameters(**bad)
        check.true(False, "%r refused" % bad)
    except ValueError as error:
        for text in expected:
            check.true(text in str(error), "%r: the message says %r (%s)" % (bad, text, error))
name = "LdgfLambda"
check.equal(session.GetHapticParameters()[name], 0.02, "the refused LdgfLambda kept 0.02")
check.equal(float(session.proxy.SMProxy.GetProperty(name).GetElement(0)), 0.02,
            "the proxy property went back to the value the session kept")
try:
    session.SetZoom(50.0)
    check.true(False, "SetZoom(50) refused")
except ValueError as error:
    check.true("Zoom = 50" in str(error) and "[0.1, 10]" in str(error), "zoom message: %s" % error)
try:
    session.SetHapticParameters(NoSuchParameter=1.0)
    check.true(False, "an unknown name is refused")
except ValueError as error:
    check.true("NoSuchParameter" in str(error), "unknown name message: %s" % error)

# The VTK facade itself, as the GUI's properties panel or a state file reaches it: the property
# set directly (no Python check), pushed, and ParaView calls SetHapticParameter("Zoom", 0.01).
zoom = session.proxy.SMProxy.GetProperty("Zoom")
zoom.SetElement(0, 0.01)
session.proxy.SMProxy.UpdateVTKObjects()
check.equal(session.GetHapticParameters()["Zoom"], 1.0, "the facade refuses Zoom 0.01, keeps 1")
message = session.GetLastError()
check.true("Zoom = 0.01" in message and "[0.1, 10]" in message and "stays 1" in message,
           "the facade's message names value, range and kept value: %s" % message)
zoom.SetElement(0, 1.0)
session.proxy.SMProxy.UpdateVTKObjects()

# State files: every parameter back in the C++ session of a fresh pvpython.
chosen = {"LdgfLambda": 0.02, "IdleDwell": 3.0, "ProxyKappaLow": 0.2, "TracerRule": 1,
          "ProxyTickAtBifurcations": 1, "ReleaseButtonMask": 4, "Zoom": 2.5}
session.SetHapticParameters(**chosen)
simple.RenameSource("ParameterSession", session.proxy)
state_folder = tempfile.mkdtemp(prefix="vesseltouch-parameters-")
atexit.register(shutil.rmtree, state_folder, True)
state = os.path.join(state_folder, "parameters.pvsm")
simple.SaveState(state)
reader = r"""
import json
from paraview import simple
simple.LoadPlugin(%r, ns=globals())
simple.LoadState(%r)
s = simple.FindSource("ParameterSession")
s.UpdatePropertyInformation()
print("APPLIED=" + json.dumps(s.GetProperty("AppliedHapticParametersInfo").GetData()))
""" % (plugin_path(), state)
code, output = run_pvpython(reader)
check.equal(code, 0, "LoadState in a fresh pvpython (output: %s)" % output[-2000:])
line = [l for l in output.splitlines() if l.startswith("APPLIED=")]
check.true(bool(line), "the loader printed the loaded session's parameters")
if line:
    text = json.loads(line[-1][len("APPLIED="):])
    loaded = {k: float(v) for k, v in (p.split("=", 1) for p in str(text).split())}
    for name, value in chosen.items():
        check.equal(loaded.get(name), float(value), "%s restored into the C++ session" % name)

# Same defaults, same forces: every parameter written from the table's defaults (what the
# panel's writeToProxy does with its default values) against a session left at its defaults.
def forces(configure):
    s = vesseltouch.HapticSession(phantom)
    configure(s)
    s.SetHandSweep(path=0, speed_mm_per_s=60.0)
    log = s.RunOffline(1.5, rate_Hz=1000.0)
    simple.Delete(s.proxy)
    return numpy.asarray(log["force"])


left = forces(lambda s: None)
written = forces(lambda s: s.SetHapticParameters(
    **{n: e["default"] for n, e in s.DescribeHapticParameters().items()}))
drifted = forces(lambda s: s.SetHapticParameters(ZoneGain=0.95))
check.true(numpy.abs(left).max() > 0.05, "the trace renders a force (max %.3f N)"
           % numpy.abs(left).max())
check.true(numpy.array_equal(left, written), "defaults written from the table: identical forces")
check.true(not numpy.array_equal(left, drifted), "a 5 % drift of one default would show")

check.finish()

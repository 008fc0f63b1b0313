"""The shared haptic session in ParaView state files: the "VesselTouchSession" proxy that
vesseltouch.logic() creates (and the dock panel binds to) is registered, so SaveState writes its
properties and LoadState, in a fresh pvpython, brings them back under the same name with the
same centerline input; the panel re-syncs its widgets from these values on state load.

A state loaded into a running session (issue 20, item 12): ParaView adds the state's proxies
beside the existing ones, so a second "VesselTouchSession" appears. The old session stops as soon
as the loaded one is registered (force to zero), vesseltouch.logic() returns the loaded one (not
running), and the old one is deleted: exactly one session stays registered."""

import atexit
import json
import os
import shutil
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from vtouch_testing import Check, plugin_path, run_pvpython  # noqa: E402

from paraview import servermanager, simple  # noqa: E402

check = Check("SessionState")
simple.LoadPlugin(plugin_path(), ns=globals())
import vesseltouch  # noqa: E402

phantom = VesselPhantom(Shape="Helix", Dimensions=[48, 48, 48])  # noqa: F821
session = vesseltouch.logic()
check.true(simple.FindSource("VesselTouchSession") is not None,
           "logic() registers the session as VesselTouchSession")
session.SetCenterline(phantom)
session.SetForceLaw("ChangeOfHeight", k=0.7, lambda_mm=0.02)
session.SetZoom(2.5)
session.SetForceZones(zero_below=0.1, saturate_above=0.6)
session.SetDevice("pointer")
session.SetMaxForce(2.0)

expected = {"ForceLaw": 1, "ChangeOfHeightLambda": 0.02, "ZoneGain": 0.7, "Zoom": 2.5,
            "ZoneZeroBelow": 0.1, "ZoneSaturateAbove": 0.6, "DeviceType": 1, "MaxForce": 2.0}
force = session.proxy.GetProperty("DeviceForceInfo")
check.true(force is not None, "the session has DeviceForceInfo")
if force is not None:
    session.proxy.UpdatePropertyInformation()
    check.equal(list(force.GetData()), [0.0, 0.0, 0.0], "no device open: zero device force")

work = tempfile.mkdtemp(prefix="vesseltouch-state-")
atexit.register(shutil.rmtree, work, True)
state = os.path.join(work, "session.pvsm")
simple.SaveState(state)
check.true(os.path.exists(state), "state written")
text = open(state).read()
check.true('name="VesselTouchSession"' in text, "the state names the session")

# Load it into a fresh pvpython and read the session back.
reader = r"""
import json, sys
from paraview import simple
simple.LoadPlugin(%r, ns=globals())
simple.LoadState(%r)
s = simple.FindSource("VesselTouchSession")
out = {"found": s is not None}
if s is not None:
    for name in %r:
        out[name] = s.GetProperty(name).SMProperty.GetElement(0)
    s.UpdatePropertyInformation()
    out["applied"] = s.GetProperty("AppliedHapticParametersInfo").GetData()
    inp = s.Input
    out["input_xml"] = inp.GetXMLName() if inp is not None else None
    out["input_port"] = getattr(inp, "Port", 0) if inp is not None else None
print("STATE=" + json.dumps(out, default=str))
""" % (plugin_path(), state, list(expected))
code, output = run_pvpython(reader)
check.equal(code, 0, "LoadState in a fresh pvpython (output: %s)" % output[-2000:])
line = [l for l in output.splitlines() if l.startswith("STATE=")]
check.true(bool(line), "the loader printed the session")
if line:
    loaded = json.loads(line[-1][len("STATE="):])
    check.true(loaded.get("found"), "LoadState restores VesselTouchSession")
    for name, value in expected.items():
        got = loaded.get(name)
        if isinstance(got, list):
            got = got[0] if got else None
        check.true(got is not None and abs(float(got) - value) < 1e-9,
                   "%s restored: %r (expected %r)" % (name, got, value))
    applied = dict(p.split("=", 1) for p in str(loaded.get("applied", "")).split())
    for name, value in expected.items():
        if name in applied:  # the haptic parameters: in the C++ session too, not only the proxy
            check.true(abs(float(applied[name]) - value) < 1e-9,
                       "%s reaches the loaded C++ session: %r" % (name, applied[name]))
    check.true(len(applied) >= 40, "the loaded session reports its haptic parameters")
    check.equal(loaded.get("input_xml"), "VesselPhantom", "the centerline input restored")
    check.equal(loaded.get("input_port"), 1, "port 1 (the analytic centerline)")

# --- LoadState into a running session -----------------------------------------------------
session.SetDevice("simulated")
session.Bind(phantom)
session.Start()
check.true(session.IsRunning(), "the session runs before the load")
session.SetZoom(1.0)  # changed after saving: the loaded session has 2.5
old_proxy = session.proxy
simple.LoadState(state)
pxm = servermanager.ProxyManager()
registered = pxm.GetProxies("sources", "VesselTouchSession")
check.equal(len(registered), 2, "LoadState adds the state's session beside the running one")
check.true(not vesseltouch.HapticSession(proxy=old_proxy).IsRunning(),
           "the old session stopped when the loaded one was registered (before logic())")
loaded = vesseltouch.logic()
check.true(loaded.proxy.SMProxy.__this__ != old_proxy.SMProxy.__this__,
           "logic() returns the loaded session, not the old one")
registered = pxm.GetProxies("sources", "VesselTouchSession")
check.equal([p.SMProxy.__this__ for p in registered], [loaded.proxy.SMProxy.__this__],
            "exactly one session is registered: the loaded one")
check.true(pxm.SMProxyManager.GetProxyName("sources", old_proxy.SMProxy) in (None, ""),
           "the old session is no longer registered")
check.true(not loaded.IsRunning(), "the loaded session waits for Start()")
for name, value in expected.items():
    got = loaded.proxy.GetProperty(name).SMProperty.GetElement(0)
    check.true(abs(float(got) - value) < 1e-9, "loaded %s: %r (expected %r)" % (name, got, value))
check.true(vesseltouch.logic() is loaded, "logic() keeps returning the loaded session")
loaded.SetDevice("simulated")
loaded.Bind(loaded.proxy.Input)
loaded.Start()
check.true(loaded.IsRunning() and loaded.GetStatus()["paths"] > 0,
           "the loaded session starts on the loaded centerline (%r)" % loaded.GetStatus())
loaded.Stop()

check.finish()

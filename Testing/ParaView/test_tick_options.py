"""The haptic tick's options of issue 17 from Python: each is set through the vesseltouch API
(SetTracerRule, SetContact, SetForceSmoothing, SetForceLaw, SetConstraintProxy, SetIdleGate: thin
calls over SetHapticParameters), read back from what the C++ pipeline holds (GetHapticParameters:
vtouch::HapticParameters after the proxy pushed them, AppliedHapticParametersInfo), and a few are
felt on scripted traces of the phantom helix (tick marks, field force, the slope force budget,
the per-axis smoothing). The defaults are the parameter table's (DescribeHapticParameters). No
wall-clock assertions."""

import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from vtouch_testing import Check, plugin_path  # noqa: E402

from paraview import simple  # noqa: E402

import numpy  # noqa: E402

check = Check("TickOptions")
simple.LoadPlugin(plugin_path(), ns=globals())
import vesseltouch  # noqa: E402

phantom = VesselPhantom(Shape="Helix", Dimensions=[96, 96, 96])  # noqa: F821
s = vesseltouch.HapticSession(phantom)
s.ResetCamera(direction=(0, 1, 0), view_up=(0, 0, 1))  # the helix seen from the side
s.SetDevice("simulated")

# The tick's options (issue 17), as haptic parameters of the table.
OPTIONS = ("TracerRule", "TracerMovementThreshold", "TracerJunctionWindow", "TracerJunctionMargin",
           "ContactDwell", "ContactApproachAtStart", "SlopeForceBudget",
           "ForceInterpolationPerAxis", "MaxForceRate", "ChangeOfHeightZMaxPerResolution",
           "ProxyTangentDrag", "ProxyTangentSnap", "ProxySnapDrag", "ProxyNormalUnilateral",
           "ProxyThresholdFromData", "ProxyFriction", "ProxyTickSpacing", "ProxyTickForce",
           "ProxyTickAtBifurcations", "ProxyFieldForce", "ProxyKappaLow", "ProxyKappaHigh",
           "IdleRadius", "IdleDwell", "IdleRamp")


def applied():
    """The haptic parameters the C++ session holds: GetHapticParameters, which parses the
    proxy's AppliedHapticParametersInfo."""
    return s.GetHapticParameters()


# --- The defaults the pipeline holds are the table's. ---
described = s.DescribeHapticParameters()
defaults = {name: described[name]["default"] for name in OPTIONS}
options = applied()
check.true(all(name in options for name in OPTIONS), "the session holds every option")
for name, value in defaults.items():
    check.near(options[name], value, 1e-12, "default %s" % name)
info = dict(pair.split("=", 1) for pair in str(s._info("AppliedHapticParametersInfo")).split())
check.true(all(name in info for name in OPTIONS), "AppliedHapticParametersInfo names every option")

# --- Each option set through Python reaches the pipeline. ---
s.SetTracerRule("movement", movement_threshold_px=0.05, junction_window_px=12.0,
                junction_margin_px=2.0)
s.SetContact(dwell_s=0.02, approach_at_start=False)
s.SetForceSmoothing(max_rate_N_per_s=50.0, per_axis=True, slope_force_budget=0.5)
s.SetForceLaw("ConstraintProxy", z_max_counts=3.0)
s.SetConstraintProxy(tangent_rule="snap", normal_rule="unilateral", threshold_from_data=True,
                     friction=0.2, tick_spacing_mm=2.0, tick_force_N=0.4,
                     tick_at_bifurcations=True, field_force=True, kappa_low=0.1, kappa_high=0.6)
s.SetIdleGate(radius_mm=0.5, dwell_s=2.0, ramp_s=0.1)
expected = {"TracerRule": 1, "TracerMovementThreshold": 0.05, "TracerJunctionWindow": 12.0,
            "TracerJunctionMargin": 2.0, "ContactDwell": 0.02, "ContactApproachAtStart": 0,
            "SlopeForceBudget": 0.5, "ForceInterpolationPerAxis": 1, "MaxForceRate": 50.0,
            "ChangeOfHeightZMaxPerResolution": 3.0, "ProxyTangentDrag": 0, "ProxyTangentSnap": 1,
            "ProxySnapDrag": 0, "ProxyNormalUnilateral": 1, "ProxyThresholdFromData": 1,
            "ProxyFriction": 0.2, "ProxyTickSpacing": 2.0, "ProxyTickForce": 0.4,
            "ProxyTickAtBifurcations": 1, "ProxyFieldForce": 1, "ProxyKappaLow": 0.1,
            "ProxyKappaHigh": 0.6, "IdleRadius": 0.5, "IdleDwell": 2.0, "IdleRamp": 0.1}
options = applied()
for name, value in expected.items():
    check.near(options[name], value, 1e-12, "set from Python: %s" % name)
s.SetConstraintProxy(tangent_rule="drag", normal_rule="popover")
options = applied()
check.equal((options["ProxyTangentDrag"], options["ProxyTangentSnap"]), (1.0, 0.0),
            "tangent rule drag")
check.equal((options["ProxySnapDrag"], options["ProxyNormalUnilateral"]), (1.0, 0.0),
            "normal rule pop-over")
for bad in (lambda: s.SetConstraintProxy(tangent_rule="sideways"),
            lambda: s.SetConstraintProxy(normal_rule="sticky"),
            lambda: s.SetTracerRule("telepathy"),
            lambda: s.SetTracerRule(junction_window_px=-1.0)):
    try:
        bad()
        check.true(False, "an unknown rule name or a value out of range raises ValueError")
    except ValueError:
        check.true(True, "an unknown rule name or a value out of range raises ValueError")

# Back to the defaults (the table's) for the traces below.
s.SetHapticParameters(**defaults)
options = applied()
for name, value in defaults.items():
    check.near(options[name], value, 1e-12, "back to the default: %s" % name)


def trace(seconds=2.5):
    """A scripted hand sweeping the helix at 50 mm/s; the log's tracing rows, the force along
    the agent's screen travel and its magnitude."""
    s.SetHandSweep(path=0, speed_mm_per_s=50.0)
    log = s.RunOffline(seconds, rate_Hz=1000.0)
    tracing = (log["state"][1:] == 1) & (log["state"][:-1] == 1)
    travel = numpy.diff(log["position"][:, [0, 2]], axis=0)  # the screen: world x, z
    length = numpy.linalg.norm(travel, axis=1)
    moving = tracing & (length > 1e-4)
    along = (log["force"][1:] * travel).sum(axis=1)[moving] / length[moving]
    magnitude = numpy.linalg.norm(log["force"][1:][moving], axis=1)
    check.true(moving.sum() > 1000, "the hand traces the helix (%d ticks)" % moving.sum())
    return along, magnitude


# --- Felt: tick marks along the vessel (Ikits' texture) on the free constraint proxy. ---
s.SetForceLaw("ConstraintProxy", k_c=200.0, b_c=0.0)
along_plain, _ = trace()
s.SetConstraintProxy(tick_spacing_mm=1.0, tick_force_N=0.3)
along_ticks, _ = trace()
rms_plain = float(numpy.sqrt(numpy.mean(along_plain ** 2)))
rms_ticks = float(numpy.sqrt(numpy.mean(along_ticks ** 2)))
check.true(rms_plain < 0.05, "free proxy: no force along the vessel (RMS %.3f N)" % rms_plain)
check.true(rms_ticks > 0.1 and float(numpy.abs(along_ticks).max()) <= 0.3 + 0.05,
           "tick marks every 1 mm: a detent force along the vessel bounded by 0.3 N (RMS %.3f, "
           "max %.3f N)" % (rms_ticks, float(numpy.abs(along_ticks).max())))
# Field force: the depth slope of eq. 2 pushes back on the rising half, pulls on the falling one.
s.SetConstraintProxy(tick_spacing_mm=0.0, field_force=True)
along_field, _ = trace()
rms_field = float(numpy.sqrt(numpy.mean(along_field ** 2)))
check.true(rms_field > 2.0 * rms_plain and rms_field > 0.05,
           "field force: the slope is felt along the vessel (RMS %.3f N)" % rms_field)
s.SetConstraintProxy(field_force=False)

# --- Felt: the slope force budget sizes lambda (Yi & Hayward 4.1). ---
s.SetForceLaw("LDGF", k=1.0, lambda_mm=0.005)
_, sized = trace()
s.SetForceSmoothing(slope_force_budget=0.0)  # lambda as set: 0.005 mm
_, unsized = trace()
s.SetForceSmoothing(slope_force_budget=0.9)
ratio = float(numpy.median(sized)) / float(numpy.median(unsized))
# The rendered slope is cos(b) / (cos(b) + lambda / w) of tan(b): with the sized lambda (0.37 mm
# for k = 1 N, w = 1 mm, 3 N) 0.73 of it at tan(b) = 0.13 down to 0.46 at tan(b) = 3; with
# 0.005 mm 0.99 or more. The phantom helix's slopes lie in between.
check.true(0.46 <= ratio <= 0.74, "budget 0.9 renders the helix weaker than budget 0, as the "
           "sized lambda's bias predicts (median ratio %.3f)" % ratio)

# --- Felt: Fig. 5's per-axis smoothing against the Euclidean bound, on the onset of the force.
s.SetForceSmoothing(max_rate_N_per_s=5.0)
s.SetHandSweep(path=0, speed_mm_per_s=50.0)
euclidean = numpy.linalg.norm(s.RunOffline(1.5)["force"], axis=1)
s.SetForceSmoothing(per_axis=True)
per_axis = numpy.linalg.norm(s.RunOffline(1.5)["force"], axis=1)
s.SetForceSmoothing(max_rate_N_per_s=100.0, per_axis=False)
step_euclidean = float(numpy.abs(numpy.diff(euclidean)).max())
step_per_axis = float(numpy.abs(numpy.diff(per_axis)).max())
# 5 N/s at 1 kHz: Euclidean steps of at most 5 mN; per axis at most 5 mN per axis (sqrt 2 more on
# a diagonal), and the two runs differ.
check.true(step_euclidean <= 0.005 + 1e-9, "Euclidean bound: |dF| <= 5 mN per tick (%.4f)"
           % step_euclidean)
check.true(step_per_axis <= 0.005 * 2 ** 0.5 + 1e-9, "per axis: |dF| <= 5 mN x sqrt 2 (%.4f)"
           % step_per_axis)
check.true(not numpy.array_equal(euclidean, per_axis), "the per-axis option changes the force")

check.finish()

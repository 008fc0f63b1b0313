// The scenes vesseltouch-force-sweep prints besides the force error: the two tracing rules and
// Hayward & Yi's surface stimulus (flat JSON keys, one per line, each preceded by ",\n").
//
// The two tracing rules (HapticParameters::tracerRule; Yi & Hayward §3.2.1), on the pipeline with
// the cursor driven point by point along the projected path plus a seeded dither:
//   tracer.<rule>.<scene>.mean_error_px / max_error_px   agent to the cursor's intended point on
//       the path, on screen (tracking error; the movement rule's drift accumulates here)
//   tracer.<rule>.<scene>.max_force_step_n   largest per-tick change of the LDGF target force
//       (the force steps at the spiral's projection cusps)
//   tracer.<rule>.<scene>.reached_fraction   last point reached / path length
//   tracer.<rule>.branch.angle<deg>.taken    the hand comes along the parent and turns into a
//       branch <deg> degrees off it (10, 20, 30, 45, 60, 90; five dither seeds): fraction of runs
//       that end on the branch
//   tracer.<rule>.branch.angle<deg>.kept     the hand goes on along the parent past the same
//       junction: fraction of runs that end on the parent
//   tracer.<rule>.branch_at_junction.angle<deg>.{taken,kept}  the same with the junction
//       re-decision off (tracerJunctionWindow_px = 0: the choice made at the junction is final)
//   tracer.<rule>.branch.angles_deg          the angles (list, for the chart)
//   tracer.<rule>.branch.correct_fraction    taken and kept over every angle and seed
// with <rule> offset (default) or movement (the paper's rule).
//
// Hayward & Yi's surface stimulus (their eqs. 4-7): z(x, y) = tan(alpha) x + A sin(omega x) y on
// three patches (dz/dx = -tan 0.4, 0, +tan 0.7: a trough), A = 1, ~100 oscillations over the
// line, drawn as 25 parallel centerlines 1 px apart so that the contact map holds the surface;
// the agent traces y = 0 at 20 mm/s, k = 1 N:
//   surface.<law>.patch<i>.mean_fx_n     mean force along the motion on patch i (eq. 5 and eq. 7
//       both give -k dz/dx)
//   surface.<law>.rms_fy_n               RMS force across the motion (eq. 5: k A |sin(omega x)|,
//       the texture that "forces the user to track the grooves"; eq. 7: 0)
//   surface.trace.{x_mm, <law>_fx_n, <law>_fy_n}  the traces (lists) for the chart
// with <law> change_of_height or lateral_gradient.
#pragma once

namespace vtouch
{
namespace bench
{
/// tracer.<rule>.<scene>.* and tracer.<rule>.branch.correct_fraction.
void printTracerComparison();
/// surface.<law>.* and the surface.trace.* lists.
void printSurfaceStimulus();
} // namespace bench
} // namespace vtouch

// Hayward & Yi's "change of height" force, their eq. 3, with the robust estimate of mu of their
// Appendix A (eqs. 8-9), exactly as written.
#pragma once

#include "vtouchForceLaw.h"

namespace vtouch
{

/// Eq. 3: f = -k (dh/dl) mu, with h the height (toward the viewer), l the hand's path and mu the
/// direction of motion. For the tracing agent the hand's projection on the screen tangent eta moves
/// the agent (Yi & Hayward §3.2.1), so per unit hand travel in the direction u = mu / |mu| the
/// depth z (= -h, positive away from the viewer) changes by s (eta . u), with the stencil slope
/// s = dz / (|dl| + lambda) toward increasing index (Yi & Hayward eq. 2). Hence
///   f = k(P) s (eta . u) mu,   u = mu / |mu|.
/// dh/dl is a property of the path alone (it does not depend on |mu|); the force scales with
/// |mu| once, not |mu|^2, and equals LDGF when the hand moves along the vessel (|mu| = 1).
///
/// Appendix A, eqs. 8-9: a point W trails the measured position P by at most z_max:
///   W_k = P_k - z_max (P_k - W_{k-1}) / |P_k - W_{k-1}|   if |P_k - W_{k-1}| > z_max,
///   W_k = W_{k-1}                                         otherwise;
///   mu_k = (P_k - W_k) / z_max.
/// No division or difference of small noisy quantities: mu is defined at rest (it keeps the last
/// direction of motion, so a resting hand keeps feeling the slope it was moving on, as the paper
/// intends), a hand at any speed gets |mu| = 1 once it has moved z_max, sensor noise or
/// quantization whose excursions stay below z_max leaves mu unchanged, and a reversal turns mu
/// continuously through zero over 2 z_max of travel (the force passes through zero: no flip). z_max
/// is "set according to the resolution of a particular device": zMaxPerResolution counts of the
/// device's positionResolution_mm. A zero force at rest is not this law's business: it comes from
/// the force zones (k(P) = 0 for a lifted stylus, or the idle gate of devices without pressure).
///
/// Passivity of the reversal (departure, `boundReversalStiffness`): while |P - W| < z_max the
/// force is |f| = k |s| |P - W| / z_max, a spring of stiffness k |s| / z_max anchored at W. With
/// z_max at two resolution counts (10 um) and k |s| up to 2.7 N that is 270 kN/m, far above what a
/// device renders stably at its rate (a sampled spring needs b > K T / 2, Colgate & Schenkel), and
/// a hand resting on a slope against a soft grip rings in it (0.13 mm, 80 Hz on the simulated
/// stylus). So z_max is at least k |s| / K_max, with K_max the device's largest stable stiffness
/// (DeviceCapabilities::maxStiffness_N_per_m, scaled by rate / 1 kHz as for the proxy coupler):
/// within a reversal the force is then a spring of at most K_max anchored at W, saturating at the
/// slope force. The resolution's z_max stays the floor (noise still never flips mu).
class ChangeOfHeightForceLaw final : public ForceLaw
{
public:
  /// Regularization lambda, mm of screen arc length (as LDGF, Yi & Hayward §4.1). Default 0.005 mm.
  double lambda_mm = 0.005;
  /// Device sizing of lambda (LdgfForceLaw::boundingLambda_mm): |f| <= k |s| <= budget x F_max.
  /// Default 0.9.
  double forceBudget = 0.9;
  /// z_max, mm of hand travel; 0 (default) = zMaxPerResolution x the device's position resolution.
  double zMax_mm = 0.0;
  /// z_max in device resolution counts when zMax_mm is 0. Default 2 (a reading dithering by one
  /// count never moves W).
  double zMaxPerResolution = 2.0;
  /// z_max when the device reports no resolution, mm. Default 0.02 mm.
  double zMaxFallback_mm = 0.02;
  /// z_max >= k |s| / K_max (above): the reversal is never stiffer than the device renders
  /// stably. Default true; false gives z_max from the resolution alone.
  bool boundReversalStiffness = true;

  ForceLawId id() const override { return ForceLawId::ChangeOfHeight; }
  void reset() noexcept override;
  Vec2 compute(const ForceInput& in, ForceRequest& request) noexcept override;

  /// The current mu (eq. 9, |mu| <= 1), device plane.
  Vec2 mu() const;
  /// The z_max in use for `capabilities` (may be null), mm.
  double zMaxFor(const DeviceCapabilities* capabilities) const;

private:
  Vec2 Position; // P: the hand, integrated from its per-tick displacement, device mm
  Vec2 Trail;    // W of eq. 8
  double ZMax_mm = 0.02;
};

} // namespace vtouch

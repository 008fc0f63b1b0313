// Yi & Hayward's lateral depth gradient force (LDGF), their eq. 2.
#pragma once

#include "vtouchForceLaw.h"

namespace vtouch
{

/// F = k(P) * dz / (dl + lambda) * eta, evaluated at the tracing agent.
/// dz is the depth change (positive AWAY from the viewer) over the stencil toward increasing index,
/// dl the stencil's screen arc length in mm and eta the unit projected tangent toward increasing
/// index. Flipping the direction flips both dz and eta, so the force does not depend on the way the
/// agent travels: a vessel rising toward the viewer pushes the hand back, a falling one pulls it
/// on. Zero while exploring.
class LdgfForceLaw final : public ForceLaw
{
public:
  /// Smallest regularization lambda, mm of screen arc length (> 0). Default 0.005 mm. The lambda
  /// in use is the larger of this and the device-sized one (boundingLambda_mm).
  double lambda_mm = 0.005;
  /// Fraction of the device's force limit the law may reach where dl -> 0 (Yi & Hayward §4.1:
  /// "rather than clamping the intensity of F, the force function is regularized"). 0 disables
  /// the device sizing. Default 0.9.
  double forceBudget = 0.9;

  ForceLawId id() const override { return ForceLawId::Ldgf; }
  void reset() noexcept override {}
  Vec2 compute(const ForceInput& in, ForceRequest& request) noexcept override;

  /// The law itself, for tests: k * dz / (dl + lambda) * eta.
  static Vec2 evaluate(double k_N, double dz_mm, double dl_mm, const Vec2& eta, double lambda_mm);
  /// §4.1 sized for the device: over a stencil of 3D arc length w, dz^2 + dl^2 = w^2 (unit
  /// tangent), and k dz / (dl + lambda) is largest where the vessel runs along the view direction
  /// (dl = 0, |dz| = w): k w / lambda. The lambda that keeps it within budget x F_max is
  ///   lambda = k_max w / (budget F_max),
  /// with k_max the saturation gain of the force zones and F_max the device's
  /// maxContinuousForce_N. Returns max(minimum_mm, that) (minimum_mm when the device reports no
  /// force limit or budget <= 0).
  static double boundingLambda_mm(double minimum_mm, const ForceInput& in, double budget);
};

} // namespace vtouch

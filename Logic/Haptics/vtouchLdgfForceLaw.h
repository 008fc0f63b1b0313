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
  /// Regularization lambda, mm of screen arc length (> 0): bounds the force where the vessel runs
  /// along the view direction (dl -> 0) to k * |dz| / lambda <= k * window / lambda (200 k with
  /// the defaults). Default 0.005 mm: a bias of at most 1 % wherever the projected tangent keeps
  /// half its length (dl >= 0.5 mm over the 1 mm stencil window).
  double lambda_mm = 0.005;

  ForceLawId id() const override { return ForceLawId::Ldgf; }
  void reset() noexcept override {}
  Vec2 compute(const ForceInput& in, ForceRequest& request) noexcept override;

  /// The law itself, for tests: k * dz / (dl + lambda) * eta.
  static Vec2 evaluate(double k_N, double dz_mm, double dl_mm, const Vec2& eta, double lambda_mm);
};

} // namespace vtouch

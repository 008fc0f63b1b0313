// Hayward & Yi's "change of height" force, their eq. 3, with the robust motion estimate mu.
#pragma once

#include "vtouchForceLaw.h"

namespace vtouch
{

/// f = -k * (dh/dl) * mu, with h the height toward the viewer and mu the direction of motion.
/// With our depth z (= -h, positive away from the viewer) and the slope s = dz/(dl + lambda) toward
/// increasing index along eta, the height change per unit motion along mu is -s (eta . mu), so
///   f = k(P) * s * (eta . mu) * mu.
/// For a hand moving steadily along the vessel (|mu| = 1) this equals LDGF; for a hand at rest it
/// is zero, which is the point of the law.
///
/// Robust mu (our reading of Appendix A): a motion window W accumulates the hand displacement and
/// forgets it with time constant `forgetTime_s`; its length is saturated at z_max:
///   W_k = exp(-dt/T) W_{k-1} + dx_k;  if |W_k| > z_max: W_k = z_max W_k / |W_k|;  mu = W_k /
///   z_max.
/// A still hand gives mu -> 0 (no spurious force); sensor noise of amplitude sigma moves W by a
/// random walk that stays far below z_max, so a barely moving hand gets a proportionally small
/// force; a deliberate motion saturates |mu| at 1 within z_max of travel.
class ChangeOfHeightForceLaw final : public ForceLaw
{
public:
  /// Regularization lambda, mm of screen arc length (as LDGF). Default 0.005 mm.
  double lambda_mm = 0.005;
  /// Saturation length of the motion window, mm of hand travel. Default 1 mm.
  double zMax_mm = 1.0;
  /// Forgetting time constant of the motion window, s. Default 0.1 s (a hand slower than
  /// z_max / T = 10 mm/s gets a proportionally reduced force).
  double forgetTime_s = 0.1;

  ForceLawId id() const override { return ForceLawId::ChangeOfHeight; }
  void reset() noexcept override { this->Window = {}; }
  Vec2 compute(const ForceInput& in, ForceRequest& request) noexcept override;

  /// The current mu (|mu| <= 1), device plane.
  Vec2 mu() const;

private:
  Vec2 Window;
};

} // namespace vtouch

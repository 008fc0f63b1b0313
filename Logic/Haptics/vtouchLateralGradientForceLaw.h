// The classic baseline both papers compare against: the gradient of a height map, in the plane.
#pragma once

#include "vtouchForceLaw.h"

namespace vtouch
{

/// f = -k(P) grad(h) = k(P) grad(z), where z(x, y) is the depth of the centerline point the contact
/// map assigns to screen pixel (x, y) (a height surface around the vessels; no value away from
/// them). The gradient is a central difference over +-`probe_px` at the cursor, in mm/mm. It works
/// in both states (it needs no agent) and shows the baseline's known faults: discontinuities where
/// vessels overlap and no guidance along the vessel.
class LateralGradientForceLaw final : public ForceLaw
{
public:
  /// Half-width of the central difference, pixels (>= 1). Default 2 px.
  double probe_px = 2.0;

  ForceLawId id() const override { return ForceLawId::LateralGradient; }
  void reset() noexcept override {}
  Vec2 compute(const ForceInput& in, ForceRequest& request) noexcept override;
};

} // namespace vtouch

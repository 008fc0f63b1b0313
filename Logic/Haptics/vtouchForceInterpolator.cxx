#include "vtouchForceInterpolator.h"

#include <cmath>

namespace vtouch
{

Vec2 ForceInterpolator::step(const Vec2& target_N, double dt_s)
{
  if (!target_N.isFinite() || !std::isfinite(dt_s))
  {
    this->Output = {};
    this->Limited = false;
    return this->Output;
  }
  const Vec2 delta = target_N - this->Output;
  const double maxStep = std::fabs(this->maxRate_N_per_s) * std::fmax(0.0, dt_s);
  if (this->perAxis)
  {
    // Yi & Hayward Fig. 5, re-planned every tick (the target moves between ticks).
    const double largest = std::fmax(std::fabs(delta.x), std::fabs(delta.y));
    const double steps = maxStep > 0.0 ? std::ceil(largest / maxStep - 1e-12) : 1.0;
    this->Limited = steps > 1.0;
    this->Output = this->Limited ? this->Output + delta * (1.0 / steps) : target_N;
    return this->Output;
  }
  const double n = delta.norm();
  this->Limited = n > maxStep;
  this->Output = this->Limited ? this->Output + delta * (maxStep / n) : target_N;
  return this->Output;
}

} // namespace vtouch

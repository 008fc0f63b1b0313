#include "vtouchForceOnsetRamp.h"

#include <algorithm>
#include <cmath>

namespace vtouch
{

void ForceOnsetRamp::reset() noexcept
{
  this->HeldTicks = 0;
  this->QuietThroughHold = true;
  this->Scale = 0.0;
}

Vec3 ForceOnsetRamp::apply(const Vec3& commanded_N, double dt_s) noexcept
{
  const ForceOnsetRampParameters& p = this->Parameters;
  if (!commanded_N.isFinite())
  {
    return commanded_N; // let the safety filter downstream see it and fault
  }
  if (this->HeldTicks < p.holdTicks)
  {
    // Hold: send zero, remember whether the command would have needed softening.
    ++this->HeldTicks;
    this->QuietThroughHold =
      this->QuietThroughHold && !(commanded_N.norm() >= std::max(0.0, p.quietThreshold_N));
    this->Scale = 0.0;
    return Vec3{};
  }
  if (this->Scale < 1.0)
  {
    if ((this->QuietThroughHold && p.holdTicks > 0) || !(p.rampTime_s > 0.0))
    {
      this->Scale = 1.0;
    }
    else
    {
      const double dt = std::isfinite(dt_s) ? std::clamp(dt_s, 0.0, p.maxTickInterval_s) : 0.0;
      const double next = this->Scale + dt / p.rampTime_s;
      this->Scale = next > 1.0 - 1e-9 ? 1.0 : next; // no rounding tail below full scale
    }
  }
  return commanded_N * this->Scale;
}

} // namespace vtouch

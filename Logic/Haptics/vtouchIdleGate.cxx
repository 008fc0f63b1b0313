#include "vtouchIdleGate.h"

#include <algorithm>
#include <cmath>

namespace vtouch
{

void IdleGate::reset() noexcept
{
  this->HasAnchor = false;
  this->Rest_s = 0.0;
  this->Idle = false;
  this->Factor = 1.0;
}

double IdleGate::update(const Vec2& p, double dt_s) noexcept
{
  const double dt = (std::isfinite(dt_s) && dt_s > 0.0) ? dt_s : 0.0;
  if (!(std::isfinite(this->dwell_s) && this->dwell_s > 0.0))
  {
    this->reset();
    return this->Factor;
  }
  if (p.isFinite())
  {
    const double radius = std::isfinite(this->radius_mm) ? std::max(0.0, this->radius_mm) : 1.0;
    if (!this->HasAnchor || (p - this->Anchor).norm() > radius)
    {
      this->Anchor = p; // moved: the rest starts again from here
      this->HasAnchor = true;
      this->Rest_s = 0.0;
    }
    else
    {
      this->Rest_s += dt;
    }
  }
  this->Idle = this->Rest_s >= this->dwell_s;
  const double target = this->Idle ? 0.0 : 1.0;
  const double ramp = std::isfinite(this->ramp_s) ? std::max(0.0, this->ramp_s) : 0.05;
  const double step = ramp > 0.0 ? dt / ramp : 1.0;
  this->Factor = this->Factor < target ? std::min(target, this->Factor + step)
                                       : std::max(target, this->Factor - step);
  return this->Factor;
}

} // namespace vtouch

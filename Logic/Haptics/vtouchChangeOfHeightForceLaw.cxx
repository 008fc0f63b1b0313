#include "vtouchChangeOfHeightForceLaw.h"

#include <cmath>

namespace vtouch
{

Vec2 ChangeOfHeightForceLaw::mu() const
{
  return this->zMax_mm > 0.0 ? this->Window * (1.0 / this->zMax_mm) : Vec2{};
}

Vec2 ChangeOfHeightForceLaw::compute(const ForceInput& in, ForceRequest&) noexcept
{
  // The window tracks the hand in every state so mu is ready at contact.
  const double decay = this->forgetTime_s > 0.0 ? std::exp(-in.dt_s / this->forgetTime_s) : 0.0;
  Vec2 w = this->Window * decay;
  if (in.handDelta_Device_mm.isFinite())
  {
    w = w + in.handDelta_Device_mm;
  }
  const double n = w.norm();
  if (n > this->zMax_mm && n > 0.0)
  {
    w = w * (this->zMax_mm / n);
  }
  this->Window = w;
  if (in.state != InteractionState::Tracing)
  {
    return {};
  }
  const double denominator = std::fabs(in.agent.dl_mm) + std::fabs(this->lambda_mm);
  if (!(denominator > 0.0))
  {
    return {};
  }
  const double slope = in.agent.dz_mm / denominator;
  const Vec2 m = this->mu();
  return m * (in.zoneGain_N * slope * in.agent.eta.dot(m));
}

} // namespace vtouch

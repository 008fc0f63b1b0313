#include "vtouchVelocityEstimator.h"

#include <algorithm>
#include <cmath>

namespace vtouch
{

VelocityEstimator::VelocityEstimator(std::size_t windowSamples, double maxWindow_s)
  : Window(std::clamp<std::size_t>(windowSamples, 2, kCapacity))
  , MaxWindow_s(maxWindow_s > 0.0 ? maxWindow_s : 0.02)
{
}

void VelocityEstimator::reset()
{
  this->Head = 0;
  this->Count = 0;
  this->Velocity = Vec3{};
}

bool VelocityEstimator::add(double timestamp_s, const Vec3& position_mm)
{
  if (!std::isfinite(timestamp_s) || !position_mm.isFinite())
  {
    return false;
  }
  if (this->Count > 0)
  {
    const Sample& newest = this->Samples[(this->Head + kCapacity - 1) % kCapacity];
    if (!(timestamp_s > newest.t_s))
    {
      return false;
    }
  }
  this->Samples[this->Head] = Sample{ timestamp_s, position_mm };
  this->Head = (this->Head + 1) % kCapacity;
  this->Count = std::min(this->Count + 1, kCapacity);
  this->update();
  return true;
}

void VelocityEstimator::update()
{
  const std::size_t n = std::min(this->Count, this->Window);
  const double tNewest = this->Samples[(this->Head + kCapacity - 1) % kCapacity].t_s;
  // Times are taken relative to the newest sample so that large absolute clocks keep precision.
  double st = 0.0, stt = 0.0;
  Vec3 sp, stp;
  std::size_t used = 0;
  for (std::size_t i = 0; i < n; ++i)
  {
    const Sample& s = this->Samples[(this->Head + kCapacity - 1 - i) % kCapacity];
    const double t = s.t_s - tNewest;
    if (-t > this->MaxWindow_s)
    {
      break;
    }
    st += t;
    stt += t * t;
    sp = sp + s.p_mm;
    stp = stp + s.p_mm * t;
    ++used;
  }
  if (used < 2)
  {
    this->Velocity = Vec3{};
    return;
  }
  const double m = static_cast<double>(used);
  const double denominator = m * stt - st * st;
  if (!(denominator > 0.0))
  {
    this->Velocity = Vec3{};
    return;
  }
  this->Velocity = (stp * m - sp * st) * (1.0 / denominator);
}

} // namespace vtouch

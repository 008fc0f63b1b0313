#include "vtouchHandTrack.h"

#include <algorithm>
#include <cmath>

namespace vtouch
{

bool HandTrack::add(double time_s, const Vec2& position_Device_mm)
{
  if (!std::isfinite(time_s) || !position_Device_mm.isFinite() ||
      (!this->Time_s.empty() && time_s <= this->Time_s.back()))
  {
    return false;
  }
  this->Time_s.push_back(time_s);
  this->Position_mm.push_back(position_Device_mm);
  return true;
}

void HandTrack::clear()
{
  this->Time_s.clear();
  this->Position_mm.clear();
}

void HandTrack::at(double time_s, Vec2& p, Vec2& v) const
{
  v = {};
  if (this->Time_s.empty())
  {
    p = {};
    return;
  }
  if (time_s <= this->Time_s.front() || this->Time_s.size() == 1)
  {
    p = this->Position_mm.front();
    return;
  }
  if (time_s >= this->Time_s.back())
  {
    p = this->Position_mm.back();
    return;
  }
  const std::size_t i = static_cast<std::size_t>(
    std::upper_bound(this->Time_s.begin(), this->Time_s.end(), time_s) - this->Time_s.begin());
  const double dt = this->Time_s[i] - this->Time_s[i - 1];
  v = (this->Position_mm[i] - this->Position_mm[i - 1]) * (1.0 / dt);
  p = this->Position_mm[i - 1] + v * (time_s - this->Time_s[i - 1]);
}

} // namespace vtouch

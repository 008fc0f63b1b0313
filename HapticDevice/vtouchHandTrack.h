// A recorded or planned hand trajectory: timed positions in the device frame, linearly
// interpolated. It drives a SimulatedDevice's scripted hand (DeviceFactory) for offline runs,
// tests and replays of a user's trace.
#pragma once

#include "vtouchVector.h"

#include <cstddef>
#include <vector>

namespace vtouch
{

class HandTrack
{
public:
  /// Appends a sample (time s, position device mm). Refused (false) when a value is not finite
  /// or the time does not increase.
  bool add(double time_s, const Vec2& position_Device_mm);
  void clear();

  bool empty() const { return this->Time_s.empty(); }
  std::size_t size() const { return this->Time_s.size(); }
  double startTime_s() const { return this->Time_s.empty() ? 0.0 : this->Time_s.front(); }
  double endTime_s() const { return this->Time_s.empty() ? 0.0 : this->Time_s.back(); }
  Vec2 firstPosition_Device_mm() const
  {
    return this->Position_mm.empty() ? Vec2{} : this->Position_mm.front();
  }

  /// Position at `time_s` (held before the first and after the last sample) and the velocity of
  /// the segment it falls in (zero outside), device mm and mm/s. No allocation: safe in a
  /// simulated device's integration step.
  void at(double time_s, Vec2& position_Device_mm, Vec2& velocity_Device_mm_per_s) const;

private:
  std::vector<double> Time_s;
  std::vector<Vec2> Position_mm;
};

} // namespace vtouch

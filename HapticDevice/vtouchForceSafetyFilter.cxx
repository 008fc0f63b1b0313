#include "vtouchForceSafetyFilter.h"

#include <algorithm>
#include <cmath>

namespace vtouch
{

ForceSafetyFilter::ForceSafetyFilter(const ForceSafetyParameters& parameters)
  : Parameters(parameters)
{
}

void ForceSafetyFilter::reset()
{
  this->Engaged = false;
  this->QuietTicks = 0;
  this->Output_N = Vec3{};
}

Vec3 ForceSafetyFilter::apply(const Vec3& commanded_N, double dt_s, SafetyFault* fault)
{
  const ForceSafetyParameters& p = this->Parameters;
  if (!commanded_N.isFinite())
  {
    ++this->NonFinite;
    if (fault)
    {
      *fault = SafetyFault::NonFiniteForce;
    }
    this->reset();
    return this->Output_N;
  }

  const double magnitude = commanded_N.norm();
  if (!this->Engaged)
  {
    this->QuietTicks = magnitude < p.engageThreshold_N ? this->QuietTicks + 1 : 0;
    this->Engaged = this->QuietTicks >= std::max(1, p.engageTicks);
    if (!this->Engaged)
    {
      this->Output_N = Vec3{};
      return this->Output_N;
    }
  }

  Vec3 target = commanded_N;
  const double limit = std::max(0.0, p.maxForce_N);
  if (magnitude > limit)
  {
    ++this->Clamped;
    target = commanded_N * (limit / magnitude);
  }

  const double dt = std::isfinite(dt_s) ? std::clamp(dt_s, 0.0, p.maxTickInterval_s) : 0.0;
  const double maxStep_N = std::max(0.0, p.maxSlewRate_N_per_s) * dt;
  const Vec3 delta = target - this->Output_N;
  const double step = delta.norm();
  if (step > maxStep_N)
  {
    ++this->SlewLimited;
    this->Output_N = this->Output_N + delta * (maxStep_N / step);
  }
  else
  {
    this->Output_N = target;
  }
  return this->Output_N;
}

} // namespace vtouch

#include "vtouchContactGate.h"

#include <cmath>

namespace vtouch
{

void ContactGate::reset() noexcept
{
  this->Armed = !this->approachAtStart;
  this->Dwelt_s = 0.0;
}

void ContactGate::disarm() noexcept
{
  this->Armed = false;
  this->Dwelt_s = 0.0;
}

bool ContactGate::update(bool nearVessel, double dt_s) noexcept
{
  if (!nearVessel)
  {
    this->Armed = true; // the cursor is off every vessel: the next approach may capture
    this->Dwelt_s = 0.0;
    return false;
  }
  if (!this->Armed)
  {
    return false;
  }
  // The first tick within the radius counts as one period: dwell_s = 0 captures at once.
  this->Dwelt_s += (std::isfinite(dt_s) && dt_s > 0.0) ? dt_s : 0.0;
  const double dwell = (std::isfinite(this->dwell_s) && this->dwell_s > 0.0) ? this->dwell_s : 0.0;
  return this->Dwelt_s >= dwell - 1e-12;
}

} // namespace vtouch

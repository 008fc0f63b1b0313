#include "vtouchForceZones.h"

#include <algorithm>
#include <cmath>

namespace vtouch
{

double ForceZones::fraction(double p) const
{
  if (!this->usePressure)
  {
    return 1.0;
  }
  if (!std::isfinite(p) || p < this->zeroBelow)
  {
    return 0.0;
  }
  if (p >= this->saturateAbove || !(this->saturateAbove > this->zeroBelow))
  {
    return 1.0;
  }
  return std::clamp((p - this->zeroBelow) / (this->saturateAbove - this->zeroBelow), 0.0, 1.0);
}

double ForceZones::gain(double p) const
{
  return std::isfinite(this->gain_N) ? this->gain_N * this->fraction(p) : 0.0;
}

} // namespace vtouch

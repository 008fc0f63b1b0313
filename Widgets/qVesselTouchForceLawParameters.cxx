#include "qVesselTouchForceLawParameters.h"

#include <algorithm>
#include <cmath>

namespace
{
// Spin boxes round what they show; values that agree to that precision are the same setting.
bool same(double a, double b)
{
  return std::abs(a - b) <= 1e-9 * std::max(1.0, std::abs(a));
}
} // namespace

bool qVesselTouchForceLawParameters::operator==(const qVesselTouchForceLawParameters& o) const
{
  for (const vtouch::HapticParameterDescriptor& d : vtouch::kHapticParameterDescriptors)
  {
    if (!same(d.get(haptic), d.get(o.haptic)))
    {
      return false;
    }
  }
  return same(ldgfGain_N, o.ldgfGain_N) && same(cohGain_N, o.cohGain_N) &&
         same(lateralGain_N, o.lateralGain_N);
}

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
  return same(ldgfGain_N, o.ldgfGain_N) && same(ldgfLambda_mm, o.ldgfLambda_mm) &&
         same(cohGain_N, o.cohGain_N) && same(cohLambda_mm, o.cohLambda_mm) &&
         same(cohZMax_mm, o.cohZMax_mm) && same(cohForgetTime_s, o.cohForgetTime_s) &&
         same(lateralGain_N, o.lateralGain_N) && same(lateralProbe_px, o.lateralProbe_px) &&
         same(proxyStiffness_N_per_m, o.proxyStiffness_N_per_m) &&
         same(proxyDamping_N_s_per_m, o.proxyDamping_N_s_per_m) &&
         proxyTangentDrag == o.proxyTangentDrag &&
         same(proxyTangentThreshold_N, o.proxyTangentThreshold_N) &&
         proxySnapDrag == o.proxySnapDrag && same(proxySnapThreshold_N, o.proxySnapThreshold_N) &&
         same(proxyKappaLow, o.proxyKappaLow) && same(proxyKappaHigh, o.proxyKappaHigh);
}

#include "vtouchLdgfForceLaw.h"

#include <algorithm>
#include <cmath>

namespace vtouch
{

Vec2 LdgfForceLaw::evaluate(double k_N,
  double dz_mm,
  double dl_mm,
  const Vec2& eta,
  double lambda_mm)
{
  const double denominator = std::fabs(dl_mm) + std::fabs(lambda_mm);
  if (!(denominator > 0.0))
  {
    return {};
  }
  return eta * (k_N * dz_mm / denominator);
}

double LdgfForceLaw::boundingLambda_mm(double minimum_mm, const ForceInput& in, double budget)
{
  const double floor_mm = std::isfinite(minimum_mm) ? std::fabs(minimum_mm) : 0.0;
  const double limit_N = in.capabilities ? in.capabilities->maxContinuousForce_N : 0.0;
  if (!(budget > 0.0) || !(limit_N > 0.0) || !std::isfinite(budget * limit_N) ||
      !(in.maxZoneGain_N > 0.0) || !(in.slopeWindow_mm > 0.0))
  {
    return floor_mm;
  }
  const double sized_mm = in.maxZoneGain_N * in.slopeWindow_mm / (budget * limit_N);
  return std::isfinite(sized_mm) ? std::max(floor_mm, sized_mm) : floor_mm;
}

Vec2 LdgfForceLaw::compute(const ForceInput& in, ForceRequest&) noexcept
{
  if (in.state != InteractionState::Tracing)
  {
    return {};
  }
  const double lambda = boundingLambda_mm(this->lambda_mm, in, this->forceBudget);
  const AgentSample& at = in.slopeSample();
  return evaluate(in.zoneGain_N, at.dz_mm, at.dl_mm, at.eta, lambda);
}

} // namespace vtouch

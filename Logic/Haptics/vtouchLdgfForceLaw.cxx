#include "vtouchLdgfForceLaw.h"

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

Vec2 LdgfForceLaw::compute(const ForceInput& in, ForceRequest&) noexcept
{
  if (in.state != InteractionState::Tracing)
  {
    return {};
  }
  return evaluate(in.zoneGain_N, in.agent.dz_mm, in.agent.dl_mm, in.agent.eta, this->lambda_mm);
}

} // namespace vtouch

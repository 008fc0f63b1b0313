#include "vtouchChangeOfHeightForceLaw.h"
#include "vtouchLdgfForceLaw.h"

#include <algorithm>
#include <cmath>

namespace vtouch
{

void ChangeOfHeightForceLaw::reset() noexcept
{
  // W = P: mu = 0 until the hand has moved z_max (no direction is known yet).
  this->Position = {};
  this->Trail = {};
}

double ChangeOfHeightForceLaw::zMaxFor(const DeviceCapabilities* capabilities) const
{
  if (std::isfinite(this->zMax_mm) && this->zMax_mm > 0.0)
  {
    return this->zMax_mm;
  }
  const double resolution = capabilities ? capabilities->positionResolution_mm : 0.0;
  const double counts = std::isfinite(this->zMaxPerResolution) && this->zMaxPerResolution > 0.0
                          ? this->zMaxPerResolution
                          : 2.0;
  if (std::isfinite(resolution) && resolution > 0.0)
  {
    return counts * resolution;
  }
  return std::isfinite(this->zMaxFallback_mm) && this->zMaxFallback_mm > 0.0 ? this->zMaxFallback_mm
                                                                             : 0.02;
}

Vec2 ChangeOfHeightForceLaw::mu() const
{
  return (this->Position - this->Trail) * (1.0 / this->ZMax_mm);
}

Vec2 ChangeOfHeightForceLaw::compute(const ForceInput& in, ForceRequest&) noexcept
{
  // The slope along the vessel (eq. 2's regularized dz/dl), when tracing.
  const bool tracing = in.state == InteractionState::Tracing;
  const AgentSample& at = in.slopeSample();
  const double denominator = tracing
                               ? std::fabs(at.dl_mm) + LdgfForceLaw::boundingLambda_mm(
                                                         this->lambda_mm, in, this->forceBudget)
                               : 0.0;
  const double slope = denominator > 0.0 ? at.dz_mm / denominator : 0.0;
  // z_max: from the resolution, and at least k |s| / K_max so that the reversal is a spring the
  // device renders stably (see the header).
  const double previousZMax_mm = this->ZMax_mm;
  this->ZMax_mm = this->zMaxFor(in.capabilities);
  const DeviceCapabilities* caps = in.capabilities;
  if (this->boundReversalStiffness && caps && caps->maxStiffness_N_per_m > 0.0 && in.dt_s > 0.0)
  {
    const double stiffness_N_per_mm = caps->maxStiffness_N_per_m * (1e-3 / in.dt_s) * 1e-3;
    const double reversal_mm = std::fabs(in.zoneGain_N * slope) / stiffness_N_per_mm;
    if (std::isfinite(reversal_mm))
    {
      this->ZMax_mm = std::max(this->ZMax_mm, reversal_mm);
    }
  }
  // W trails P in every state, so mu is ready at contact. When z_max changes, W is moved so that
  // mu is unchanged (a hand moving onto a steeper slope keeps |mu| = 1): the recursion is then
  // mu_k = Pi(mu_{k-1} + dP_k / z_max_k), Pi the projection on the unit disc, which for a
  // constant z_max is eqs. 8-9 exactly.
  if (this->ZMax_mm != previousZMax_mm && previousZMax_mm > 0.0)
  {
    this->Trail =
      this->Position - (this->Position - this->Trail) * (this->ZMax_mm / previousZMax_mm);
  }
  if (in.handDelta_Device_mm.isFinite())
  {
    this->Position = this->Position + in.handDelta_Device_mm;
  }
  const Vec2 z = this->Position - this->Trail; // Z_k before the update of W
  const double n = z.norm();
  if (n > this->ZMax_mm) // eq. 8
  {
    this->Trail = this->Position - z * (this->ZMax_mm / n);
  }
  if (!tracing || !(denominator > 0.0))
  {
    return {};
  }
  const Vec2 m = this->mu(); // eq. 9
  const double magnitude = m.norm();
  if (!(magnitude > 0.0))
  {
    return {};
  }
  // eq. 3: -k (dh/dl) mu with dh/dl = -s (eta . u), u = mu / |mu|.
  return m * (in.zoneGain_N * slope * at.eta.dot(m) / magnitude);
}

} // namespace vtouch

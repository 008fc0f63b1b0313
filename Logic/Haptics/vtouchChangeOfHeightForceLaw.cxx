#include "vtouchChangeOfHeightForceLaw.h"
#include "vtouchLdgfForceLaw.h"

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
  // W trails P in every state, so mu is ready at contact.
  this->ZMax_mm = this->zMaxFor(in.capabilities);
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
  if (in.state != InteractionState::Tracing)
  {
    return {};
  }
  const double denominator = std::fabs(in.agent.dl_mm) + LdgfForceLaw::boundingLambda_mm(
                                                           this->lambda_mm, in, this->forceBudget);
  if (!(denominator > 0.0))
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
  const double slope = in.agent.dz_mm / denominator;
  return m * (in.zoneGain_N * slope * in.agent.eta.dot(m) / magnitude);
}

} // namespace vtouch

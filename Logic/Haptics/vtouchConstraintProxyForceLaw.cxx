#include "vtouchConstraintProxyForceLaw.h"

#include <algorithm>
#include <cmath>

namespace vtouch
{

void ConstraintProxyForceLaw::reset() noexcept
{
  this->Tangent = { 1.0, 0.0 };
  this->HasFrame = false;
}

double ConstraintProxyForceLaw::kappa(double s) const
{
  const double lo = std::min(this->kappaLow, this->kappaHigh);
  const double hi = std::max(this->kappaLow, this->kappaHigh);
  if (!(hi > lo))
  {
    return s >= hi ? 1.0 : 0.0;
  }
  const double u = std::clamp((s - lo) / (hi - lo), 0.0, 1.0);
  return u * u * (3.0 - 2.0 * u);
}

double ConstraintProxyForceLaw::effectiveStiffness_N_per_m(const DeviceCapabilities* caps,
  double dt_s) const
{
  double k = std::max(0.0, this->stiffness_N_per_m);
  if (caps && caps->maxStiffness_N_per_m > 0.0 && dt_s > 0.0)
  {
    k = std::min(k, caps->maxStiffness_N_per_m * (1e-3 / dt_s));
  }
  return std::isfinite(k) ? k : 0.0;
}

double ConstraintProxyForceLaw::effectiveDamping_N_s_per_m(const DeviceCapabilities* caps) const
{
  double b = std::max(0.0, this->damping_N_s_per_m);
  if (caps && caps->maxStiffness_N_per_m > 0.0)
  {
    b = std::min(b, caps->maxStiffness_N_per_m * 1e-3);
  }
  return std::isfinite(b) ? b : 0.0;
}

double ConstraintProxyForceLaw::tangentTrail_px(const DeviceCapabilities* caps,
  double pixelsPerHandMm,
  double dt_s) const
{
  const double k = this->effectiveStiffness_N_per_m(caps, dt_s);
  if (this->tangentRule != TangentRule::Drag || !(k > 0.0))
  {
    return 0.0;
  }
  return std::max(0.0, this->tangentThreshold_N) / k * 1000.0 * pixelsPerHandMm;
}

Vec2 ConstraintProxyForceLaw::compute(const ForceInput& in, ForceRequest& request) noexcept
{
  if (in.state != InteractionState::Tracing || !(in.pixelsPerHandMm > 0.0))
  {
    this->HasFrame = false;
    return {};
  }
  const double s = std::clamp(in.agent.frameStrength, 0.0, 1.0);
  const double a = this->kappa(s);
  // Keep the last good frame while the projected tangent is unreliable (hysteresis at the low
  // knee): its weight a is ~0 there anyway, so the force cannot follow the tangent's noise.
  if (a > 0.0 || !this->HasFrame)
  {
    const double n = in.agent.eta.norm();
    if (n > 0.5)
    {
      Vec2 t = in.agent.eta * (1.0 / n);
      if (this->HasFrame && t.dot(this->Tangent) < 0.0)
      {
        t = t * -1.0; // the frame's sign is irrelevant; keep it continuous
      }
      this->Tangent = t;
      this->HasFrame = true;
    }
  }
  const Vec2 t = this->Tangent;
  const Vec2 nrm{ -t.y, t.x };
  // x - p in hand metres.
  const Vec2 d = (in.cursor_px - in.agent.screen_px) * (1e-3 / in.pixelsPerHandMm);
  const double k = this->effectiveStiffness_N_per_m(in.capabilities, in.dt_s) * in.zoneFraction;
  const double b = this->effectiveDamping_N_s_per_m(in.capabilities) * in.zoneFraction;
  const double ct = this->tangentRule == TangentRule::Drag ? 1.0 : 0.0;
  const double dt = d.dot(t);
  const double dn = d.dot(nrm);
  const Vec2 anisotropic = t * (ct * dt) + nrm * dn;
  const Vec2 spring = (d * (1.0 - a) + anisotropic * a) * (-k);
  const Vec2 damping = in.handVelocity_Device_mm_per_s * (-b * 1e-3);

  if (this->normalRule == NormalRule::SnapDrag && std::fabs(k * dn) > this->snapThreshold_N)
  {
    const int target = in.view->contactAt(
      static_cast<int>(std::floor(in.cursor_px.x)), static_cast<int>(std::floor(in.cursor_px.y)));
    if (target >= 0 && target != in.agent.point &&
        (in.view->screen_px(target) - in.cursor_px).norm() <
          (in.agent.screen_px - in.cursor_px).norm())
    {
      request.snapToPoint = target;
    }
  }
  return spring + damping;
}

} // namespace vtouch

#include "vtouchConstraintProxyForceLaw.h"
#include "vtouchLdgfForceLaw.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace vtouch
{

void ConstraintProxyForceLaw::reset() noexcept
{
  this->Tangent = { 1.0, 0.0 };
  this->HasFrame = false;
  this->HasLastAgent = false;
  this->LastNormalForce_N = 0.0;
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
  if (this->tangentRule == TangentRule::SnapDrag)
  {
    return std::numeric_limits<double>::infinity(); // the law steps the proxy itself (eq. 11)
  }
  const double k = this->effectiveStiffness_N_per_m(caps, dt_s);
  const double mu = std::isfinite(this->friction) ? std::max(0.0, this->friction) : 0.0;
  const double friction_N = mu * this->LastNormalForce_N;
  const double base_N =
    this->tangentRule == TangentRule::Drag ? std::max(0.0, this->tangentThreshold_N) : 0.0;
  if (!(k > 0.0) || !(base_N + friction_N > 0.0))
  {
    return 0.0;
  }
  return (base_N + friction_N) / k * 1000.0 * pixelsPerHandMm;
}

double ConstraintProxyForceLaw::tickForce(double arc_mm) const
{
  const double spacing = this->tickSpacing_mm;
  const double w = this->tickWidth_mm;
  if (!(spacing > 0.0) || !(w > 0.0) || !std::isfinite(arc_mm) || !std::isfinite(spacing))
  {
    return 0.0;
  }
  return this->detentForce(arc_mm - spacing * std::round(arc_mm / spacing)); // nearest mark
}

double ConstraintProxyForceLaw::detentForce(double offset_mm) const
{
  const double w = this->tickWidth_mm;
  if (!(w > 0.0) || !std::isfinite(offset_mm))
  {
    return 0.0;
  }
  const double x = offset_mm / w;
  // A detent: a potential well at the mark (draws the hand in from either side, peak A at
  // |u| = w, negligible beyond ~4 w); conservative, so it never adds energy over a round trip.
  return -this->tickForce_N * x * std::exp(0.5 * (1.0 - x * x));
}

Vec2 ConstraintProxyForceLaw::compute(const ForceInput& in, ForceRequest& request) noexcept
{
  if (in.state != InteractionState::Tracing || !(in.pixelsPerHandMm > 0.0))
  {
    this->HasFrame = false;
    this->HasLastAgent = false;
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
  const double mPerPx = 1e-3 / in.pixelsPerHandMm;
  const Vec2 d = (in.cursor_px - in.agent.screen_px) * mPerPx;
  const double k = this->effectiveStiffness_N_per_m(in.capabilities, in.dt_s) * in.zoneFraction;
  const double b = this->effectiveDamping_N_s_per_m(in.capabilities) * in.zoneFraction;
  const double ct = this->tangentRule == TangentRule::Drag ? 1.0 : 0.0;
  const double dt = d.dot(t);
  double dn = d.dot(nrm);
  if (this->normalRule == NormalRule::Unilateral && dn > 0.0)
  {
    dn = 0.0; // eq. 10: the proxy would follow the hand on this side; no force
  }
  const Vec2 anisotropic = t * (ct * dt) + nrm * dn;
  Vec2 spring = (d * (1.0 - a) + anisotropic * a) * (-k);
  if (this->tangentRule == TangentRule::SnapDrag)
  {
    // Eq. 11: the proxy stays until the hand leads it by more than tau = tau_t / k_c along t,
    // then steps by tau; meanwhile the tangent spring holds (-k_c d_t, at most tau_t).
    const double tau_m = k > 0.0 ? std::max(0.0, this->tangentThreshold_N) / k : 0.0;
    spring = spring - t * (a * k * dt);
    if (tau_m > 0.0 && std::fabs(dt) > tau_m)
    {
      request.agentStep_px = t * ((dt > 0.0 ? tau_m : -tau_m) / mPerPx);
    }
  }
  // Eq. 7's damper on the relative velocity: pdot from the proxy's screen motion.
  Vec2 pdot;
  if (this->HasLastAgent && in.dt_s > 0.0)
  {
    pdot = (in.agent.screen_px - this->LastAgent_px) * (1e3 * mPerPx / in.dt_s); // hand mm/s
  }
  this->LastAgent_px = in.agent.screen_px;
  this->HasLastAgent = true;
  const Vec2 relative = in.handVelocity_Device_mm_per_s - pdot;
  const Vec2 damping = relative.isFinite() ? relative * (-b * 1e-3) : Vec2{};
  this->LastNormalForce_N = std::fabs(spring.dot(nrm));

  Vec2 secondary;
  if (this->tickSpacing_mm > 0.0 || this->tickAtBifurcations)
  {
    // Along increasing arc = along eta (toward increasing index).
    const double ne = in.agent.eta.norm();
    if (ne > 0.5)
    {
      double along_N = this->tickForce(in.agentArc_mm);
      if (this->tickAtBifurcations)
      {
        along_N += this->detentForce(in.bifurcationOffset_mm);
      }
      // Scaled by k(P) like the coupler: the zero-force zone (and the idle gate) silence it.
      secondary = secondary + in.agent.eta * (along_N * in.zoneFraction / ne);
    }
  }
  if (this->fieldForce)
  {
    const double lambda = LdgfForceLaw::boundingLambda_mm(this->fieldLambda_mm, in, 0.9);
    const AgentSample& at = in.slopeSample();
    secondary =
      secondary + LdgfForceLaw::evaluate(in.zoneGain_N, at.dz_mm, at.dl_mm, at.eta, lambda);
  }

  if (this->normalRule == NormalRule::PopOver)
  {
    const double threshold =
      this->thresholdFromData ? this->snapThreshold_N * s : this->snapThreshold_N;
    if (std::fabs(k * dn) > threshold)
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
  }
  return spring + damping + secondary;
}

} // namespace vtouch

#include "vtouchHapticPipeline.h"

#include "vtouchHapticParameterTable.h"

#include <algorithm>
#include <cmath>

namespace vtouch
{

HapticPipeline::HapticPipeline()
{
  this->Laws[static_cast<int>(ForceLawId::Ldgf)] = &this->Ldgf;
  this->Laws[static_cast<int>(ForceLawId::ChangeOfHeight)] = &this->ChangeOfHeight;
  this->Laws[static_cast<int>(ForceLawId::LateralGradient)] = &this->Lateral;
  this->Laws[static_cast<int>(ForceLawId::ConstraintProxy)] = &this->Proxy;
  this->Laws[static_cast<int>(ForceLawId::None)] = nullptr;
}

void HapticPipeline::release() noexcept
{
  this->Trace.release();
  this->Contact.disarm();
}

void HapticPipeline::reset() noexcept
{
  this->Trace.release();
  this->Frame.reset();
  this->LastApexSign = 1;
  this->ContactNeedsReset = true;
  for (ForceLaw* law : this->Laws)
  {
    if (law)
    {
      law->reset();
    }
  }
  this->Interpolator.reset();
  this->Idle.reset();
  this->HasCursor = false;
  this->HasHand = false;
  this->LastButtons = 0;
  this->Fade = 1.0;
}

void HapticPipeline::zeroForce() noexcept
{
  this->Interpolator.reset();
}

void HapticPipeline::applyParameters(const HapticParameters& p)
{
  this->Ldgf.lambda_mm = p.ldgfLambda_mm;
  this->ChangeOfHeight.lambda_mm = p.cohLambda_mm;
  this->Ldgf.forceBudget = p.slopeForceBudget;
  this->ChangeOfHeight.forceBudget = p.slopeForceBudget;
  this->ChangeOfHeight.zMax_mm = p.cohZMax_mm;
  this->ChangeOfHeight.zMaxPerResolution = p.cohZMaxPerResolution;
  this->Lateral.probe_px = p.lateralProbe_px;
  this->Proxy.stiffness_N_per_m = p.proxyStiffness_N_per_m;
  this->Proxy.damping_N_s_per_m = p.proxyDamping_N_s_per_m;
  using TangentRule = ConstraintProxyForceLaw::TangentRule;
  using NormalRule = ConstraintProxyForceLaw::NormalRule;
  this->Proxy.tangentRule = p.proxyTangentSnap   ? TangentRule::SnapDrag
                            : p.proxyTangentDrag ? TangentRule::Drag
                                                 : TangentRule::Free;
  this->Proxy.tangentThreshold_N = p.proxyTangentThreshold_N;
  this->Proxy.normalRule = p.proxySnapDrag           ? NormalRule::PopOver
                           : p.proxyNormalUnilateral ? NormalRule::Unilateral
                                                     : NormalRule::Rigid;
  this->Proxy.thresholdFromData = p.proxyThresholdFromData;
  this->Proxy.friction = p.proxyFriction;
  this->Proxy.tickSpacing_mm = p.proxyTickSpacing_mm;
  this->Proxy.tickForce_N = p.proxyTickForce_N;
  this->Proxy.tickAtBifurcations = p.proxyTickAtBifurcations;
  this->Proxy.fieldForce = p.proxyFieldForce;
  this->Proxy.fieldLambda_mm = p.ldgfLambda_mm;
  this->Proxy.snapThreshold_N = p.proxySnapThreshold_N;
  this->Proxy.kappaLow = p.proxyKappaLow;
  this->Proxy.kappaHigh = p.proxyKappaHigh;
  this->Zones.gain_N = p.zoneGain_N;
  this->Zones.zeroBelow = p.zoneZeroBelow;
  this->Zones.saturateAbove = p.zoneSaturateAbove;
  this->Interpolator.maxRate_N_per_s = p.maxForceRate_N_per_s;
  this->Interpolator.perAxis = p.forceInterpolationPerAxis;
  this->Idle.radius_mm = p.idleRadius_mm;
  this->Idle.dwell_s = p.idleDwell_s;
  this->Idle.ramp_s = p.idleRamp_s;
  this->Trace.deadBand_px = std::max(0.0, p.tracerDeadBand_px);
  // A non-finite value (the facade validates against the table, a raw struct may still carry one)
  // falls back to the table's default, not to a second copy of it here.
  static const HapticParameters kDefaults{};
  const auto finiteOr = [](double value, double fallback)
  { return std::isfinite(value) ? value : fallback; };
  this->Contact.dwell_s = std::max(0.0, finiteOr(p.contactDwell_s, kDefaults.contactDwell_s));
  this->Contact.approachAtStart = p.contactApproachAtStart;
  this->Trace.directionHysteresis = std::clamp(
    finiteOr(p.tracerDirectionHysteresis, kDefaults.tracerDirectionHysteresis), 0.0, 1.0);
  this->Trace.movementThreshold_px = std::max(
    0.0, finiteOr(p.tracerMovementThreshold_px, kDefaults.tracerMovementThreshold_px));
  this->Trace.foldLookAhead_px =
    std::max(0.0, finiteOr(p.tracerFoldLookAhead_px, kDefaults.tracerFoldLookAhead_px));
  this->Trace.junctionWindow_px =
    std::max(0.0, finiteOr(p.tracerJunctionWindow_px, kDefaults.tracerJunctionWindow_px));
  this->Trace.junctionMargin_px =
    std::max(0.0, finiteOr(p.tracerJunctionMargin_px, kDefaults.tracerJunctionMargin_px));
}

Vec2 HapticPipeline::renderLaws(const ForceInput& fin,
  const HapticParameters& p,
  ForceRequest& req) noexcept
{
  const int requested = static_cast<int>(p.forceLaw);
  if (requested >= 0 && requested < kForceLawCount && p.forceLaw != this->Active)
  {
    // Start a crossfade from whatever is rendered now (even mid-fade: restart from the new pair).
    this->Previous = this->Active;
    this->Active = p.forceLaw;
    // Nothing was rendered before the first tick: no fade then.
    this->Fade = (p.crossfade_s > 0.0 && this->Ticks > 1) ? 0.0 : 1.0;
    if (ForceLaw* law = this->Laws[static_cast<int>(this->Active)])
    {
      law->reset();
    }
  }
  ForceLaw* active = this->Laws[static_cast<int>(this->Active)];
  const Vec2 fActive = active ? active->compute(fin, req) : Vec2{};
  if (this->Fade >= 1.0)
  {
    return fActive;
  }
  ForceLaw* previous = this->Laws[static_cast<int>(this->Previous)];
  ForceRequest ignored;
  const Vec2 fPrevious = previous ? previous->compute(fin, ignored) : Vec2{};
  this->Fade = std::min(1.0, this->Fade + fin.dt_s / std::max(p.crossfade_s, 1e-9));
  // Smoothstep weights: continuous force and continuous force rate at both ends of the fade.
  const double w = this->Fade * this->Fade * (3.0 - 2.0 * this->Fade);
  return fPrevious * (1.0 - w) + fActive * w;
}

AgentState HapticPipeline::step(const TickInput& in, const HapticParameters& p) noexcept
{
  this->applyParameters(p);
  if (this->ContactNeedsReset)
  {
    this->Contact.reset();
    this->ContactNeedsReset = false;
  }
  AgentState out;
  out.time_s = in.time_s;
  out.tick = ++this->Ticks;
  const ViewModel* vm = in.view;
  const DeviceState& dev = in.device;
  const Vec2 hand{ dev.position_Device_mm.x, dev.position_Device_mm.y };
  out.hand_Device_mm = hand;

  // Cursor: hand motion times (mapping x zoom), unless re-indexing.
  const double zoom = std::clamp(std::isfinite(p.zoom) ? p.zoom : 1.0,
    hapticParameter(HapticParameterId::Zoom).minimum,
    hapticParameter(HapticParameterId::Zoom).maximum);
  const double pxPerMm = std::max(1e-6, p.pixelsPerDeviceMm) * zoom;
  const bool hasPressure = in.capabilities ? in.capabilities->hasPressure : false;
  this->Zones.usePressure = hasPressure;
  const bool reindex =
    (hasPressure && !(dev.pressure >= p.reindexPressure)) || (dev.buttons & p.reindexButtonMask);
  out.reindexing = reindex;
  Vec2 handDelta;
  if (this->HasHand && hand.isFinite())
  {
    handDelta = hand - this->LastHand;
  }
  if (hand.isFinite())
  {
    this->LastHand = hand;
    this->HasHand = true;
  }
  if (vm && !this->HasCursor)
  {
    this->Cursor = { 0.5 * vm->mapWidth(), 0.5 * vm->mapHeight() };
    this->HasCursor = true;
  }
  const Vec2 cursorBefore = this->Cursor; // the movement rule projects this tick's motion
  if (!reindex)
  {
    this->Cursor = this->Cursor + handDelta * pxPerMm;
  }
  if (vm)
  {
    this->Cursor.x = std::clamp(this->Cursor.x, 0.0, std::max(0.0, vm->mapWidth() - 1e-6));
    this->Cursor.y = std::clamp(this->Cursor.y, 0.0, std::max(0.0, vm->mapHeight() - 1e-6));
  }
  out.cursor_px = this->Cursor;

  // State machine.
  const std::uint32_t pressed = dev.buttons & ~this->LastButtons;
  this->LastButtons = dev.buttons;
  if (pressed & p.releaseButtonMask)
  {
    this->release(); // §3.2: a click returns to exploring, and stays there (ContactGate)
  }
  if (!vm || (this->Trace.state() == InteractionState::Tracing &&
               this->Trace.topologyId() != vm->topology().id()))
  {
    this->release();
  }
  if (vm)
  {
    if (this->Trace.state() == InteractionState::Exploring)
    {
      const bool near =
        this->Cursor.isFinite() && vm->contactAt(static_cast<int>(std::floor(this->Cursor.x)),
                                     static_cast<int>(std::floor(this->Cursor.y))) >= 0;
      if (this->Contact.update(near, in.dt_s))
      {
        this->Trace.tryContact(*vm, this->Cursor);
      }
    }
    else
    {
      this->Trace.trail_px = this->Active == ForceLawId::ConstraintProxy
                               ? this->Proxy.tangentTrail_px(in.capabilities, pxPerMm, in.dt_s)
                               : 0.0;
      if (!std::isfinite(this->Trace.trail_px))
      {
        // Ikits eq. 11: the proxy moves only in the law's steps (ForceRequest::agentStep_px).
        this->Trace.trail_px = 0.0;
      }
      else
      {
        if (p.tracerRule == 1)
        {
          this->Trace.followMovement(*vm, this->Cursor - cursorBefore);
        }
        else
        {
          this->Trace.follow(*vm, this->Cursor);
        }
        // The branch choice of the last junction follows the hand (both rules).
        this->Trace.reconsiderJunction(*vm, this->Cursor);
      }
    }
  }

  // Forces.
  Vec2 target;
  ForceInput fin;
  if (vm)
  {
    fin.view = vm;
    fin.state = this->Trace.state();
    // The location the position-dependent forces (the slope laws' dz/dl, tick marks) read: with
    // the offset rule, the cursor's projection within the dead band of the agent, so that the
    // force is a function of the hand's position, not of the dead band's history (a backlash in
    // a steep field does net work on the hand each cycle: Tracer::locationToward).
    AgentLocation forceAt = this->Trace.location();
    double forceArc_mm = this->Trace.arcLength_mm();
    if (fin.state == InteractionState::Tracing)
    {
      fin.agent = this->Trace.sample(*vm);
      if (p.tracerRule != 1 && this->Trace.deadBand_px > 0.0)
      {
        double lead_mm = 0.0;
        forceAt = this->Trace.locationToward(*vm, this->Cursor, this->Trace.deadBand_px, &lead_mm);
        forceArc_mm += lead_mm;
        fin.slope = Tracer::sampleAt(*vm, forceAt);
        fin.hasSlope = true;
      }
    }
    fin.cursor_px = this->Cursor;
    fin.handDelta_Device_mm = handDelta;
    fin.handVelocity_Device_mm_per_s = { dev.velocity_Device_mm_per_s.x,
      dev.velocity_Device_mm_per_s.y };
    fin.pixelsPerHandMm = pxPerMm;
    fin.zoneGain_N = this->Zones.gain(dev.pressure);
    fin.zoneFraction = this->Zones.fraction(dev.pressure);
    if (!hasPressure)
    {
      // §5.2's zero-force zone for devices that cannot sense the hand's push: a dwell gate.
      const double idle = this->Idle.update(hand, in.dt_s);
      fin.zoneGain_N *= idle;
      fin.zoneFraction *= idle;
      out.idle = this->Idle.idle();
    }
    fin.maxZoneGain_N = std::max(0.0, this->Zones.gain_N);
    fin.slopeWindow_mm = vm->topology().slopeWindow_mm();
    fin.agentArc_mm = forceArc_mm;
    fin.bifurcationOffset_mm =
      vm->topology().bifurcationOffset_mm(forceAt.from, forceAt.to, forceAt.t);
    fin.dt_s = in.dt_s;
    fin.capabilities = in.capabilities;
    ForceRequest req;
    target = this->renderLaws(fin, p, req);
    if (req.agentStep_px.norm() > 0.0 && this->Trace.state() == InteractionState::Tracing)
    {
      this->Trace.followMovement(*vm, req.agentStep_px);
    }
    if (req.snapToPoint >= 0)
    {
      this->Trace.placeAt(*vm, req.snapToPoint);
    }
    out.zoneGain_N = fin.zoneGain_N;
  }
  if (!target.isFinite())
  {
    target = {};
  }
  out.targetForce_N = target;
  out.force_N = this->Interpolator.step(target, in.dt_s);

  out.state = this->Trace.state();
  out.forceLaw = this->Active;
  out.directionOfTravel = this->Trace.directionOfTravel();
  out.torsionAngle_rad = this->Trace.torsionAngle_rad();
  if (vm && out.state == InteractionState::Tracing)
  {
    const AgentSample s = this->Trace.sample(*vm);
    out.path = vm->topology().pathOf(s.point);
    out.point = vm->topology().pointOf(s.point);
    out.agentScreen_px = s.screen_px;
    out.position_World_mm = s.position_World_mm;
    out.tangent_World = s.tangent_World;
    if (out.directionOfTravel != 0)
    {
      this->LastApexSign = out.directionOfTravel > 0 ? 1 : -1;
    }
    this->Frame.update(
      s.position_World_mm, s.tangent_World, out.torsionAngle_rad, this->LastApexSign);
    out.coneRoll_rad = this->Frame.coneRoll_rad();
    out.coneNormal_World = this->Frame.coneNormal_World();
  }
  else
  {
    this->Frame.reset();
  }
  return out;
}

} // namespace vtouch

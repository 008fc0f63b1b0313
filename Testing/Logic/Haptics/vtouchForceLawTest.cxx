#include "vtouchChangeOfHeightForceLaw.h"
#include "vtouchConstraintProxyForceLaw.h"
#include "vtouchForceInterpolator.h"
#include "vtouchForceZones.h"
#include "vtouchHapticsTestUtilities.h"
#include "vtouchLateralGradientForceLaw.h"
#include "vtouchLdgfForceLaw.h"
#include "vtouchTracer.h"

#include <gtest/gtest.h>

#include <random>

namespace vtouch
{
namespace
{
using namespace vtouch::testing;

Vec2 px(double x_mm, double y_mm)
{
  return { 400.0 + 4.0 * x_mm, 300.0 + 4.0 * y_mm };
}

/// A ForceInput with the agent placed at the point nearest to `at` (tracing).
ForceInput tracingInput(const ViewModel& vm, const Vec2& at, Tracer& tracer)
{
  EXPECT_TRUE(tracer.tryContact(vm, at));
  ForceInput in;
  in.view = &vm;
  in.state = InteractionState::Tracing;
  in.agent = tracer.sample(vm);
  in.cursor_px = in.agent.screen_px;
  in.pixelsPerHandMm = 4.0;
  in.zoneGain_N = 1.0;
  in.zoneFraction = 1.0;
  in.dt_s = 0.001;
  return in;
}

TEST(LdgfForceLaw, BoundedByLambdaWhenVesselRunsAlongViewDirection)
{
  const double lambda = 0.01;
  double previous = 0.0;
  // Lines tilted ever closer to the view direction (z): the force grows but stays bounded.
  for (double angle_deg : { 60.0, 80.0, 89.0, 89.9, 89.99, 89.999 })
  {
    const double a = angle_deg * kPi / 180.0;
    const QSkeleton s = straightLine({ 0, 0, 0 }, { 10 * std::cos(a), 0, 10 * std::sin(a) }, 0.25);
    auto vm = buildView(s, topCamera({ 0, 0, 5 }));
    const int mid = vm->pointCount() / 2;
    const double dz = vm->dz_mm(mid);
    const Vec2 eta = vm->eta(mid);
    const Vec2 f = LdgfForceLaw::evaluate(1.0, dz, vm->dl_mm(mid), eta, lambda);
    ASSERT_TRUE(f.isFinite()) << angle_deg;
    EXPECT_LE(f.norm(), std::fabs(dz) / lambda + 1e-9) << angle_deg;
    EXPECT_GE(f.norm(), previous - 1e-9) << angle_deg;
    previous = f.norm();
  }
  // dz -> -1 mm over the 1 mm stencil as dl -> 0: the force tends to |dz| / lambda = 100 N.
  EXPECT_GT(previous, 95.0);
  // Exactly along the view direction the projected tangent is undefined: finite (zero) force.
  const QSkeleton s = straightLine({ 0, 0, 0 }, { 0, 0, 10 }, 0.25);
  auto vm = buildView(s, topCamera({ 0, 0, 5 }));
  const int mid = vm->pointCount() / 2;
  EXPECT_EQ(vm->dl_mm(mid), 0.0);
  const Vec2 f = LdgfForceLaw::evaluate(1.0, vm->dz_mm(mid), vm->dl_mm(mid), vm->eta(mid), lambda);
  EXPECT_TRUE(f.isFinite());
  EXPECT_LE(f.norm(), 1.0 / lambda);
}

TEST(LdgfForceLaw, PushesBackWhereVesselRisesTowardViewer)
{
  // Rising toward the viewer (+z) along +x with tan(beta) = 0.5.
  const QSkeleton s = straightLine({ -20, 0, 0 }, { 20, 0, 20 }, 0.25);
  auto vm = buildView(s, topCamera({ 0, 0, 10 }));
  Tracer tracer;
  ForceInput in = tracingInput(*vm, px(0, 0), tracer);
  LdgfForceLaw law;
  ForceRequest req;
  const Vec2 f = law.compute(in, req);
  const double dl = in.agent.dl_mm;
  EXPECT_NEAR(f.x, -0.5 * dl / (dl + law.lambda_mm), 1e-5); // against travel toward +x
  EXPECT_NEAR(f.y, 0.0, 1e-6);
  // Reversing the path direction flips dz and eta together: the same force.
  const Vec2 g =
    LdgfForceLaw::evaluate(1.0, -in.agent.dz_mm, dl, in.agent.eta * -1.0, law.lambda_mm);
  EXPECT_NEAR(g.x, f.x, 1e-12);
  // No force while exploring.
  in.state = InteractionState::Exploring;
  EXPECT_EQ(law.compute(in, req).norm(), 0.0);
}

/// Hayward & Yi, Appendix A, eqs. 8-9, written out independently of the law.
struct AppendixA
{
  double zMax = 0.01;
  Vec2 P;
  Vec2 W;
  Vec2 step(const Vec2& delta)
  {
    P = P + delta;
    const Vec2 d = P - W;
    if (d.norm() > zMax)
    {
      W = P - d * (zMax / d.norm());
    }
    return (P - W) * (1.0 / zMax);
  }
};

/// A rising line (dz/dl = 0.5 along +x), the agent on it, a device of 5 um resolution.
struct CohRig
{
  std::shared_ptr<ViewModel> vm =
    buildView(straightLine({ -20, 0, 0 }, { 20, 0, 20 }, 0.25), topCamera({ 0, 0, 10 }));
  Tracer tracer;
  DeviceCapabilities caps;
  ForceInput in;
  ChangeOfHeightForceLaw law;
  ForceRequest req;
  CohRig()
  {
    caps.positionResolution_mm = 0.005;
    in = tracingInput(*vm, px(0, 0), tracer);
    in.capabilities = &caps;
  }
  Vec2 ldgf() const
  {
    return LdgfForceLaw::evaluate(1.0, in.agent.dz_mm, in.agent.dl_mm, in.agent.eta, law.lambda_mm);
  }
  Vec2 move(const Vec2& delta_mm)
  {
    in.handDelta_Device_mm = delta_mm;
    return law.compute(in, req);
  }
};

TEST(ChangeOfHeightForceLaw, MuIsAppendixAEquations8And9)
{
  CohRig rig;
  EXPECT_DOUBLE_EQ(rig.law.zMaxFor(&rig.caps), 0.01); // two counts of the 5 um resolution
  EXPECT_DOUBLE_EQ(rig.law.zMaxFor(nullptr), rig.law.zMaxFallback_mm);
  AppendixA reference;
  std::mt19937 rng(7);
  std::normal_distribution<double> step(0.0, 0.004);
  for (int k = 0; k < 5000; ++k)
  {
    const Vec2 delta{ step(rng) + 0.001, step(rng) };
    rig.move(delta);
    const Vec2 mu = reference.step(delta);
    ASSERT_NEAR((rig.law.mu() - mu).norm(), 0.0, 1e-9) << k;
    ASSERT_LE(rig.law.mu().norm(), 1.0 + 1e-12) << k;
  }
}

TEST(ChangeOfHeightForceLaw, NoForceBeforeTheHandHasMoved)
{
  CohRig rig;
  for (int k = 0; k < 1000; ++k)
  {
    ASSERT_EQ(rig.move({}).norm(), 0.0); // mu = 0: no direction of motion is known yet
  }
}

TEST(ChangeOfHeightForceLaw, EqualsLdgfAtAnyHandSpeedOnceMoved)
{
  // Eq. 3 has no speed in it: 1 mm/s and 100 mm/s along the vessel feel the same slope (the old
  // forgetting factor gave 10 % of it at 1 mm/s).
  for (double speed_mm_per_s : { 1.0, 10.0, 100.0 })
  {
    CohRig rig;
    Vec2 f;
    for (int k = 0; k < 100; ++k) // 0.1 s
    {
      f = rig.move({ speed_mm_per_s * 0.001, 0.0 });
    }
    EXPECT_NEAR(rig.law.mu().x, 1.0, 1e-12) << speed_mm_per_s;
    EXPECT_NEAR((f - rig.ldgf()).norm(), 0.0, 1e-12) << speed_mm_per_s;
    // Moving back (-x) over the same slope: the same (gravity-like) force, as LDGF.
    for (int k = 0; k < 100; ++k)
    {
      f = rig.move({ -speed_mm_per_s * 0.001, 0.0 });
    }
    EXPECT_NEAR((f - rig.ldgf()).norm(), 0.0, 1e-12) << speed_mm_per_s;
    // Across the vessel (+y) the slope along the motion is zero: no force. W pursues P like a
    // tractrix: the angle of mu to +y shrinks as 2 tan^-1(e^(-travel / z_max)), 10 z_max here.
    for (int k = 0; k < 100; ++k)
    {
      f = rig.move({ 0.0, speed_mm_per_s * 0.001 });
    }
    EXPECT_LT(f.norm(), 4.0 * std::exp(-10.0) * rig.ldgf().norm()) << speed_mm_per_s;
  }
}

TEST(ChangeOfHeightForceLaw, RestingHandKeepsMuAndForce)
{
  // Appendix A: "mu is defined when P is stationary". The hand stops after moving: W stays, mu
  // and the force keep their last values exactly (no decay, no division by a vanishing dl).
  CohRig rig;
  Vec2 f;
  for (int k = 0; k < 50; ++k)
  {
    f = rig.move({ 0.001, 0.0 });
  }
  const Vec2 mu = rig.law.mu();
  for (int k = 0; k < 5000; ++k)
  {
    ASSERT_EQ(rig.move({}).x, f.x) << k;
    ASSERT_EQ(rig.law.mu().x, mu.x) << k;
  }
  EXPECT_NEAR((f - rig.ldgf()).norm(), 0.0, 1e-12);
}

TEST(ChangeOfHeightForceLaw, ReversingHandPassesThroughZeroWithoutFlip)
{
  // The hand goes +x at 1 mm/s, then reverses. mu turns through zero over 2 z_max of travel; the
  // force along the vessel keeps the LDGF sign throughout (the slope felt does not depend on the
  // direction of travel) and its magnitude is |mu| times LDGF's: continuous, no flip.
  CohRig rig;
  const Vec2 ldgf = rig.ldgf();
  ASSERT_LT(ldgf.x, -0.4);
  for (int k = 0; k < 50; ++k)
  {
    rig.move({ 0.001, 0.0 });
  }
  Vec2 previous = rig.move({ 0.0, 0.0 });
  double worstStep = 0.0;
  for (int k = 0; k < 100; ++k)
  {
    const Vec2 f = rig.move({ -0.001, 0.0 });
    ASSERT_LE(f.x, 1e-15) << k;
    ASSERT_NEAR(f.norm(), std::fabs(rig.law.mu().x) * ldgf.norm(), 1e-12) << k;
    worstStep = std::max(worstStep, (f - previous).norm());
    previous = f;
  }
  EXPECT_NEAR((previous - ldgf).norm(), 0.0, 1e-12);
  // 1 um per tick over 2 z_max = 20 um: at most |ldgf| / 10 per tick (through zero).
  EXPECT_LE(worstStep, ldgf.norm() * 0.001 / 0.01 + 1e-12);
}

TEST(ChangeOfHeightForceLaw, ReversalIsNoStifferThanTheDeviceRendersStably)
{
  // Within a reversal |f| = k |s| |P - W| / z_max: a spring anchored at W. With the device's
  // largest stable stiffness K_max (1000 N/m at 1 kHz, as the simulated stylus) z_max is at least
  // k |s| / K_max, so the force never changes faster than K_max per unit of hand travel; with the
  // paper's z_max alone (two 5 um counts) the same reversal is k |s| / 10 um = 50 kN/m here. A hand
  // moving on while the slope steepens keeps |mu| = 1 (z_max grows, mu does not collapse).
  for (bool bounded : { true, false })
  {
    CohRig rig;
    rig.caps.maxStiffness_N_per_m = 1000.0;
    rig.law.boundReversalStiffness = bounded;
    const double f0 = rig.ldgf().norm();
    for (int k = 0; k < 2000; ++k) // 2 mm along +x, 1 um per tick
    {
      rig.move({ 0.001, 0.0 });
    }
    EXPECT_NEAR(rig.law.mu().x, 1.0, 1e-12);
    Vec2 previous = rig.move({});
    double stiffest_N_per_mm = 0.0;
    for (int k = 0; k < 2000; ++k) // and back
    {
      const Vec2 f = rig.move({ -0.001, 0.0 });
      stiffest_N_per_mm = std::max(stiffest_N_per_mm, (f - previous).norm() / 0.001);
      ASSERT_LE(f.x, 1e-15) << k; // no flip
      previous = f;
    }
    EXPECT_NEAR((previous - rig.ldgf()).norm(), 0.0, 1e-12);
    if (bounded)
    {
      EXPECT_LE(stiffest_N_per_mm, 1.0 + 1e-9); // K_max = 1 N/mm
      EXPECT_NEAR(
        rig.law.zMaxFor(&rig.caps), 0.01, 1e-15); // the resolution's z_max stays the floor
    }
    else
    {
      EXPECT_NEAR(stiffest_N_per_mm, f0 / 0.01, 1e-6 * f0 / 0.01); // k |s| / z_max
    }
  }
  // The slope doubles under a moving hand: mu stays at 1, the force doubles.
  CohRig rig;
  rig.caps.maxStiffness_N_per_m = 1000.0;
  for (int k = 0; k < 2000; ++k)
  {
    rig.move({ 0.001, 0.0 });
  }
  rig.in.agent.dz_mm *= 2.0;
  const Vec2 f = rig.move({ 0.001, 0.0 });
  EXPECT_NEAR(rig.law.mu().x, 1.0, 1e-12);
  EXPECT_NEAR((f - rig.ldgf()).norm(), 0.0, 1e-12);
}

TEST(ChangeOfHeightForceLaw, SensorNoiseBelowZMaxNeverFlipsMu)
{
  // A hand that moved along +x rests on a sensor with white noise, sigma = z_max / 10 (the
  // simulated device reports 5 sigma as its resolution, z_max is two of those). Over 20 s the
  // excursions drag W by at most their peak, which stays below z_max / 2: mu stays defined
  // (|mu| > 0.1) and points the way the hand last moved.
  for (unsigned seed : { 1u, 2u, 3u })
  {
    CohRig rig;
    for (int k = 0; k < 50; ++k)
    {
      rig.move({ 0.001, 0.0 });
    }
    std::mt19937 rng(seed);
    std::normal_distribution<double> noise(0.0, 0.001);
    Vec2 previous;
    double worstCos = 1.0;
    double smallest = 1.0;
    for (int k = 0; k < 20000; ++k)
    {
      const Vec2 p{ noise(rng), noise(rng) };
      const Vec2 f = rig.move(p - previous);
      previous = p;
      const Vec2 mu = rig.law.mu();
      smallest = std::min(smallest, mu.norm());
      worstCos = std::min(worstCos, mu.x / std::max(mu.norm(), 1e-300));
      ASSERT_LE(f.x, 1e-15) << k; // the slope force never reverses
    }
    EXPECT_GT(worstCos, 0.0) << seed;
    EXPECT_GT(smallest, 0.1) << seed;
  }
}

TEST(LateralGradientForceLaw, PointsTowardIncreasingDepth)
{
  const QSkeleton s = straightLine({ -20, 0, 0 }, { 20, 0, 20 }, 0.25);
  auto vm = buildView(s, topCamera({ 0, 0, 10 }), 12.0);
  LateralGradientForceLaw law;
  ForceInput in;
  in.view = vm.get();
  in.zoneGain_N = 1.0;
  in.cursor_px = px(0, 1); // beside the vessel, in exploring: the baseline needs no agent
  ForceRequest req;
  const Vec2 f = law.compute(in, req);
  EXPECT_LT(f.x, 0.0);         // the vessel rises toward the viewer along +x: pushed back toward -x
  EXPECT_NEAR(f.x, -0.5, 0.1); // the Voronoi height surface is a staircase of 1/4-mm steps
  in.cursor_px = px(0, 30);    // far from every vessel
  EXPECT_EQ(law.compute(in, req).norm(), 0.0);
}

TEST(ConstraintProxyForceLaw, KappaIsASmoothStepOfFrameStrength)
{
  ConstraintProxyForceLaw law;
  EXPECT_EQ(law.kappa(0.0), 0.0);
  EXPECT_EQ(law.kappa(law.kappaLow), 0.0);
  EXPECT_NEAR(law.kappa(0.5 * (law.kappaLow + law.kappaHigh)), 0.5, 1e-12);
  EXPECT_EQ(law.kappa(law.kappaHigh), 1.0);
  EXPECT_EQ(law.kappa(1.0), 1.0);
}

TEST(ConstraintProxyForceLaw, SpringAlongNormalOnlyWithFreeTangentAndDeviceBounds)
{
  const QSkeleton s = straightLine({ -20, 0, 0 }, { 20, 0, 0 }, 0.25);
  auto vm = buildView(s, topCamera({ 0, 0, 0 }));
  Tracer tracer;
  ForceInput in = tracingInput(*vm, px(0, 0), tracer);
  in.cursor_px = in.agent.screen_px + Vec2{ 8.0, 4.0 }; // 2 mm along, 1 mm across (4 px/mm)
  ConstraintProxyForceLaw law;
  ForceRequest req;
  Vec2 f = law.compute(in, req);
  EXPECT_NEAR(f.x, 0.0, 1e-9);
  EXPECT_NEAR(f.y, -200.0 * 1e-3, 1e-9); // default k_c 200 N/m, 1 mm
  // Drag tangent: the tangent spring is active too.
  law.tangentRule = ConstraintProxyForceLaw::TangentRule::Drag;
  f = law.compute(in, req);
  EXPECT_NEAR(f.x, -0.4, 1e-9);
  EXPECT_NEAR(law.tangentTrail_px(nullptr, 4.0), 0.3 / 200.0 * 1000.0 * 4.0, 1e-12);
  // Bounded by the device: k_c <= maxStiffness, b_c <= maxStiffness * 1 ms.
  DeviceCapabilities caps;
  caps.maxStiffness_N_per_m = 150.0;
  law.damping_N_s_per_m = 5.0;
  EXPECT_EQ(law.effectiveStiffness_N_per_m(&caps), 150.0);
  EXPECT_EQ(law.effectiveStiffness_N_per_m(&caps, 0.004), 37.5); // the capability is at 1 kHz
  EXPECT_EQ(law.effectiveDamping_N_s_per_m(&caps), 0.15);
  in.capabilities = &caps;
  law.tangentRule = ConstraintProxyForceLaw::TangentRule::Free;
  EXPECT_NEAR(law.compute(in, req).y, -0.15, 1e-9);
}

TEST(ConstraintProxyForceLaw, DegenerateFrameDoesNotJitter)
{
  // The agent sits where the vessel runs along the view direction; the projected tangent there is
  // noise. The force must not follow it.
  const QSkeleton s = straightLine({ 0, 0, -5 }, { 0, 0, 5 }, 0.25);
  auto vm = buildView(s, topCamera({ 0, 0, 0 }));
  Tracer tracer;
  ForceInput in = tracingInput(*vm, px(0, 0), tracer);
  in.cursor_px = in.agent.screen_px + Vec2{ 3.0, 2.0 };
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> angle(0.0, 2 * kPi);
  std::uniform_real_distribution<double> strength(0.0, 0.1);
  auto spread = [&](ConstraintProxyForceLaw& law)
  {
    ForceRequest req;
    double lo = 1e300;
    double hi = -1e300;
    for (int k = 0; k < 2000; ++k)
    {
      const double a = angle(rng);
      in.agent.eta = { std::cos(a), std::sin(a) };
      in.agent.frameStrength = strength(rng);
      const Vec2 f = law.compute(in, req);
      lo = std::min(lo, f.x);
      hi = std::max(hi, f.x);
    }
    return hi - lo;
  };
  ConstraintProxyForceLaw law;
  EXPECT_LT(spread(law), 1e-12);
  ForceRequest req;
  EXPECT_NEAR(law.compute(in, req).x, -0.2 * 0.75, 1e-9); // isotropic spring to the proxy
  // Without the transfer function (always anisotropic) the same input makes the force jitter.
  ConstraintProxyForceLaw raw;
  raw.kappaLow = -2.0;
  raw.kappaHigh = -1.0;
  EXPECT_GT(spread(raw), 0.1);
}

TEST(ConstraintProxyForceLaw, PopOverJumpsToNeighbourVesselWhenPushedHard)
{
  QSkeleton s = straightLine({ -20, 0, 0 }, { 20, 0, 0 }, 0.25);
  QSkeleton other = straightLine({ -20, 3, 0 }, { 20, 3, 0 }, 0.25); // 12 px above
  other.paths[0].id = 1;
  s.paths.push_back(other.paths[0]);
  auto vm = buildView(s, topCamera({ 0, 0, 0 }), 5.0);
  Tracer tracer;
  ForceInput in = tracingInput(*vm, px(0, 0), tracer);
  in.cursor_px = px(0, 2.6); // 2.6 mm across: 0.52 N at 200 N/m, within 5 px of the other line
  ConstraintProxyForceLaw law;
  law.normalRule = ConstraintProxyForceLaw::NormalRule::PopOver;
  law.snapThreshold_N = 1.0;
  ForceRequest req;
  law.compute(in, req);
  EXPECT_EQ(req.snapToPoint, -1); // below the threshold: the proxy holds
  law.snapThreshold_N = 0.5;
  law.compute(in, req);
  ASSERT_GE(req.snapToPoint, 0);
  EXPECT_EQ(vm->topology().pathOf(req.snapToPoint), 1);
}

TEST(ConstraintProxyForceLaw, DampingActsOnRelativeVelocitySoFreeMotionFeelsNoDrag)
{
  // Ikits eq. 7: b_c (xdot - pdot). The hand and the proxy slide together along a free vessel at
  // 50 mm/s: no drag at all (b_c xdot was 5 mN against the motion). Across the vessel the proxy
  // stays: the damper acts on the whole hand velocity there.
  const QSkeleton s = straightLine({ -20, 0, 0 }, { 20, 0, 0 }, 0.25);
  auto vm = buildView(s, topCamera({ 0, 0, 0 }));
  Tracer tracer;
  ForceInput in = tracingInput(*vm, px(0, 0), tracer);
  ConstraintProxyForceLaw law;
  ForceRequest req;
  in.handVelocity_Device_mm_per_s = { 50.0, 0.0 };
  Vec2 f;
  for (int k = 0; k < 10; ++k)
  {
    in.agent.screen_px.x += 0.2; // 50 mm/s x 4 px/mm x 1 ms
    in.cursor_px = in.agent.screen_px;
    f = law.compute(in, req);
  }
  EXPECT_NEAR(f.norm(), 0.0, 1e-12);
  in.handVelocity_Device_mm_per_s = { 0.0, 50.0 };
  f = law.compute(in, req); // the proxy did not move this tick
  EXPECT_NEAR(f.y, -0.1 * 0.05, 1e-12);
  law.damping_N_s_per_m = 0.0; // dropped, as Ikits do
  EXPECT_NEAR(law.compute(in, req).norm(), 0.0, 1e-12);
}

TEST(ConstraintProxyForceLaw, SnapDragStepsTheProxyByTau)
{
  // Eq. 11: the proxy holds until the hand leads it by tau = tau_t / k_c = 1.5 mm along t, then
  // steps by tau (6 px at 4 px/mm); meanwhile the tangent spring pulls back.
  const QSkeleton s = straightLine({ -20, 0, 0 }, { 20, 0, 0 }, 0.25);
  auto vm = buildView(s, topCamera({ 0, 0, 0 }));
  Tracer tracer;
  ForceInput in = tracingInput(*vm, px(0, 0), tracer);
  ConstraintProxyForceLaw law;
  law.tangentRule = ConstraintProxyForceLaw::TangentRule::SnapDrag;
  law.damping_N_s_per_m = 0.0;
  EXPECT_TRUE(std::isinf(law.tangentTrail_px(nullptr, 4.0))); // the tracer must not follow
  ForceRequest req;
  in.cursor_px = in.agent.screen_px + Vec2{ 4.0, 0.0 }; // 1 mm ahead
  Vec2 f = law.compute(in, req);
  EXPECT_NEAR(f.x, -0.2, 1e-12);
  EXPECT_EQ(req.agentStep_px.norm(), 0.0);
  in.cursor_px = in.agent.screen_px + Vec2{ 8.0, 0.0 }; // 2 mm ahead
  f = law.compute(in, req);
  EXPECT_NEAR(req.agentStep_px.x, 6.0, 1e-9);
  EXPECT_NEAR(req.agentStep_px.y, 0.0, 1e-12);
}

TEST(ConstraintProxyForceLaw, UnilateralConstraintPushesFromOneSideOnly)
{
  // Eq. 10: on the +n side the proxy would follow the hand (no force); on the -n side, a spring.
  const QSkeleton s = straightLine({ -20, 0, 0 }, { 20, 0, 0 }, 0.25);
  auto vm = buildView(s, topCamera({ 0, 0, 0 }));
  Tracer tracer;
  ForceInput in = tracingInput(*vm, px(0, 0), tracer);
  ConstraintProxyForceLaw law;
  law.normalRule = ConstraintProxyForceLaw::NormalRule::Unilateral;
  law.damping_N_s_per_m = 0.0;
  ForceRequest req;
  in.cursor_px = in.agent.screen_px + Vec2{ 0.0, 4.0 }; // +n (left of +x): free
  EXPECT_NEAR(law.compute(in, req).norm(), 0.0, 1e-12);
  in.cursor_px = in.agent.screen_px + Vec2{ 0.0, -4.0 }; // -n: pushed back
  EXPECT_NEAR(law.compute(in, req).y, 0.2, 1e-12);
}

TEST(ConstraintProxyForceLaw, SecondaryEffectsFrictionTicksAndFieldForce)
{
  const QSkeleton s = straightLine({ -20, 0, 0 }, { 20, 0, 20 }, 0.25);
  auto vm = buildView(s, topCamera({ 0, 0, 10 }));
  Tracer tracer;
  ForceInput in = tracingInput(*vm, px(0, 0), tracer);
  ConstraintProxyForceLaw law;
  law.damping_N_s_per_m = 0.0;
  ForceRequest req;
  // Friction in the constraint subspace: a 1 mm push across the vessel (0.2 N normal force) with
  // mu = 0.5 holds the proxy until the tangent force exceeds 0.1 N (a 2 px trail at 4 px/mm).
  law.friction = 0.5;
  in.cursor_px = in.agent.screen_px + Vec2{ 0.0, 4.0 };
  law.compute(in, req);
  EXPECT_NEAR(law.tangentTrail_px(nullptr, 4.0), 0.1 / 200.0 * 1000.0 * 4.0, 1e-9);
  law.friction = 0.0;
  // Tick marks: detents every 5 mm of arc, peak A at +-w around each mark, nothing between.
  law.tickSpacing_mm = 5.0;
  EXPECT_EQ(law.tickForce(0.0), 0.0);
  EXPECT_NEAR(law.tickForce(law.tickWidth_mm), -law.tickForce_N, 1e-12);
  EXPECT_NEAR(law.tickForce(-law.tickWidth_mm), law.tickForce_N, 1e-12);
  EXPECT_NEAR(law.tickForce(10.0 + law.tickWidth_mm), -law.tickForce_N, 1e-9);
  EXPECT_LT(std::fabs(law.tickForce(2.5)), 1e-6);
  in.cursor_px = in.agent.screen_px;
  in.agentArc_mm = law.tickWidth_mm;
  const Vec2 tick = law.compute(in, req);
  EXPECT_NEAR(tick.dot(in.agent.eta), -law.tickForce_N, 1e-9);
  // Field force: the depth slope along the vessel, as LDGF.
  law.tickSpacing_mm = 0.0;
  law.fieldForce = true;
  const Vec2 field = law.compute(in, req);
  const Vec2 ldgf =
    LdgfForceLaw::evaluate(1.0, in.agent.dz_mm, in.agent.dl_mm, in.agent.eta, law.fieldLambda_mm);
  EXPECT_NEAR((field - ldgf).norm(), 0.0, 1e-12);
  EXPECT_GT(ldgf.norm(), 0.4);
}

TEST(ConstraintProxyForceLaw, PopOverThresholdFollowsFrameStrengthWhenDataDriven)
{
  // Eq. 16 with a linear ramp: tau_snap x s. On a weak frame (s = 0.4) a push of 0.52 N pops over
  // with a 1 N threshold (0.4 N effective); at full strength it does not.
  QSkeleton s = straightLine({ -20, 0, 0 }, { 20, 0, 0 }, 0.25);
  QSkeleton other = straightLine({ -20, 3, 0 }, { 20, 3, 0 }, 0.25);
  other.paths[0].id = 1;
  s.paths.push_back(other.paths[0]);
  auto vm = buildView(s, topCamera({ 0, 0, 0 }), 5.0);
  Tracer tracer;
  ForceInput in = tracingInput(*vm, px(0, 0), tracer);
  in.cursor_px = px(0, 2.6);
  ConstraintProxyForceLaw law;
  law.normalRule = ConstraintProxyForceLaw::NormalRule::PopOver;
  law.snapThreshold_N = 1.0;
  law.thresholdFromData = true;
  law.kappaLow = 0.0; // keep the normal spring whole on the weak frame
  law.kappaHigh = 0.01;
  ForceRequest req;
  law.compute(in, req);
  EXPECT_EQ(req.snapToPoint, -1);
  in.agent.frameStrength = 0.4;
  law.compute(in, req);
  EXPECT_GE(req.snapToPoint, 0);
}

TEST(ForceZones, ZeroProportionalAndSaturationZones)
{
  ForceZones z;
  z.gain_N = 2.0;
  z.zeroBelow = 0.1;
  z.saturateAbove = 0.5;
  EXPECT_EQ(z.gain(0.0), 0.0);
  EXPECT_EQ(z.gain(0.09), 0.0);
  EXPECT_NEAR(z.gain(0.3), 1.0, 1e-12);
  EXPECT_EQ(z.gain(0.5), 2.0);
  EXPECT_EQ(z.gain(1.0), 2.0);
  EXPECT_EQ(z.gain(std::nan("")), 0.0);
  z.usePressure = false;
  EXPECT_EQ(z.gain(0.0), 2.0);
}

TEST(ForceInterpolator, SpreadsLargeStepOverTicksWithBoundedIncrement)
{
  ForceInterpolator interp;
  interp.maxRate_N_per_s = 100.0;
  const double dt = 0.001;
  Vec2 previous;
  int ticks = 0;
  while ((interp.output() - Vec2{ 1.5, -2.0 }).norm() > 1e-12 && ticks < 1000)
  {
    const Vec2 f = interp.step({ 1.5, -2.0 }, dt);
    EXPECT_LE((f - previous).norm(), 0.1 + 1e-12);
    previous = f;
    ++ticks;
  }
  EXPECT_EQ(ticks, 25); // |step| = 2.5 N at 0.1 N per tick
  // Small changes pass through at once.
  EXPECT_NEAR(interp.step({ 1.55, -2.0 }, dt).x, 1.55, 1e-12);
  EXPECT_FALSE(interp.limited());
  // A NaN target gives zero, not NaN.
  EXPECT_EQ(interp.step({ std::nan(""), 0 }, dt).norm(), 0.0);
}

TEST(ForceInterpolator, PerAxisFigure5SplitsAStepIntoNEqualIncrementsButDependsOnDirection)
{
  // Fig. 5: n = max(|dfx| / threshold, |dfy| / threshold, 1), increments df / n. The same step of
  // 1 N takes 10 ticks along an axis and 8 along the diagonal (0.707 N per axis); the Euclidean
  // bound takes 10 in both directions. Both keep the increment's direction.
  auto ticksTo = [](const Vec2& target, bool perAxis)
  {
    ForceInterpolator interp;
    interp.maxRate_N_per_s = 100.0; // 0.1 N per 1 ms tick
    interp.perAxis = perAxis;
    int ticks = 0;
    Vec2 previous;
    while ((interp.output() - target).norm() > 1e-12 && ticks < 1000)
    {
      const Vec2 f = interp.step(target, 0.001);
      const Vec2 d = f - previous;
      EXPECT_NEAR(d.x * target.y - d.y * target.x, 0.0, 1e-12); // along the step
      previous = f;
      ++ticks;
    }
    return ticks;
  };
  const double r = std::sqrt(0.5);
  EXPECT_EQ(ticksTo({ 1.0, 0.0 }, true), 10);
  EXPECT_EQ(ticksTo({ r, r }, true), 8);
  EXPECT_EQ(ticksTo({ 1.0, 0.0 }, false), 10);
  EXPECT_EQ(ticksTo({ r, r }, false), 10);
  // Fig. 5's increments are equal: 0.07071 N per axis on the diagonal, 8 of them.
  ForceInterpolator interp;
  interp.perAxis = true;
  const Vec2 f = interp.step({ r, r }, 0.001);
  EXPECT_NEAR(f.x, r / 8.0, 1e-12);
}

} // namespace
} // namespace vtouch

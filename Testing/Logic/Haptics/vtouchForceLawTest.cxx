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

TEST(ChangeOfHeightForceLaw, NoForceWhenHandAtRest)
{
  const QSkeleton s = straightLine({ -20, 0, 0 }, { 20, 0, 20 }, 0.25);
  auto vm = buildView(s, topCamera({ 0, 0, 10 }));
  Tracer tracer;
  ForceInput in = tracingInput(*vm, px(0, 0), tracer);
  ChangeOfHeightForceLaw law;
  ForceRequest req;
  for (int k = 0; k < 1000; ++k)
  {
    ASSERT_EQ(law.compute(in, req).norm(), 0.0);
  }
  // A resting hand with sensor noise (sigma 5 um, seeded): a small fraction of the slope force.
  std::mt19937 rng(3);
  std::normal_distribution<double> noise(0.0, 0.005);
  Vec2 previous{ noise(rng), noise(rng) };
  double worst = 0.0;
  for (int k = 0; k < 5000; ++k)
  {
    const Vec2 p{ noise(rng), noise(rng) };
    in.handDelta_Device_mm = p - previous;
    previous = p;
    worst = std::max(worst, law.compute(in, req).norm());
  }
  const double ldgf = 0.5;
  EXPECT_LT(worst, 0.05 * ldgf);
}

TEST(ChangeOfHeightForceLaw, EqualsLdgfForSteadyMotionAndFadesWhenHandStops)
{
  const QSkeleton s = straightLine({ -20, 0, 0 }, { 20, 0, 20 }, 0.25);
  auto vm = buildView(s, topCamera({ 0, 0, 10 }));
  Tracer tracer;
  ForceInput in = tracingInput(*vm, px(0, 0), tracer);
  ChangeOfHeightForceLaw law;
  ForceRequest req;
  Vec2 f;
  for (int k = 0; k < 300; ++k) // 40 mm/s toward +x for 0.3 s
  {
    in.handDelta_Device_mm = { 0.04, 0.0 };
    f = law.compute(in, req);
  }
  const Vec2 ldgf =
    LdgfForceLaw::evaluate(1.0, in.agent.dz_mm, in.agent.dl_mm, in.agent.eta, law.lambda_mm);
  EXPECT_NEAR(f.x, ldgf.x, 1e-9);
  EXPECT_NEAR(law.mu().norm(), 1.0, 1e-12);
  // Moving back (-x) over the same slope: the same (gravity-like) force.
  for (int k = 0; k < 300; ++k)
  {
    in.handDelta_Device_mm = { -0.04, 0.0 };
    f = law.compute(in, req);
  }
  EXPECT_NEAR(f.x, ldgf.x, 1e-9);
  // The hand stops: the force fades with the window's forgetting time.
  in.handDelta_Device_mm = {};
  for (int k = 0; k < 500; ++k)
  {
    f = law.compute(in, req);
  }
  EXPECT_LT(f.norm(), 0.001 * ldgf.norm());
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

TEST(ConstraintProxyForceLaw, SnapDragPopsOverToNeighbourVesselWhenPushedHard)
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
  law.normalRule = ConstraintProxyForceLaw::NormalRule::SnapDrag;
  law.snapThreshold_N = 1.0;
  ForceRequest req;
  law.compute(in, req);
  EXPECT_EQ(req.snapToPoint, -1); // below the threshold: the proxy holds
  law.snapThreshold_N = 0.5;
  law.compute(in, req);
  ASSERT_GE(req.snapToPoint, 0);
  EXPECT_EQ(vm->topology().pathOf(req.snapToPoint), 1);
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

} // namespace
} // namespace vtouch

#include "vtouchHapticPipeline.h"
#include "vtouchHapticsTestUtilities.h"
#include "vtouchPointerDevice.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

namespace vtouch
{
namespace
{
using namespace vtouch::testing;

struct PipelineRig
{
  std::shared_ptr<ViewModel> view;
  HapticPipeline pipeline;
  HapticParameters params = immediateContact(); // most tests start on the vessel
  DeviceCapabilities caps;
  DeviceState device;
  double time = 0.0;

  AgentState step(double dt = 0.001)
  {
    TickInput in;
    in.device = this->device;
    in.capabilities = &this->caps;
    in.view = this->view.get();
    in.dt_s = dt;
    in.time_s = (this->time += dt);
    return this->pipeline.step(in, this->params);
  }
};

TEST(HapticPipeline, CrossfadeSwitchesLawsWithoutForceJump)
{
  PipelineRig rig;
  rig.view = buildView(straightLine({ -20, 0, 0 }, { 20, 0, 20 }, 0.25), topCamera({ 0, 0, 10 }));
  rig.params.maxForceRate_N_per_s = 1e9; // isolate the crossfade from the interpolation
  rig.params.crossfade_s = 0.005;
  AgentState s = rig.step(); // the cursor starts at the viewport centre, on the vessel
  ASSERT_EQ(s.state, InteractionState::Tracing);
  s = rig.step();
  const double f0 = s.force_N.norm();
  ASSERT_GT(f0, 0.4);
  rig.params.forceLaw = ForceLawId::None;
  Vec2 previous = s.force_N;
  int ticks = 0;
  while (rig.step().force_N.norm() > 0.0 && ticks < 100)
  {
    ++ticks;
  }
  EXPECT_EQ(ticks, 4); // 5 ms at 1 kHz (the fifth tick is at zero)
  // Replay with per-tick increments: smoothstep's steepest slope is 1.5 / T.
  rig.params.forceLaw = ForceLawId::Ldgf;
  double worst = 0.0;
  previous = rig.step().force_N;
  for (int k = 0; k < 20; ++k)
  {
    const Vec2 f = rig.step().force_N;
    worst = std::max(worst, (f - previous).norm());
    previous = f;
  }
  EXPECT_NEAR(previous.norm(), f0, 1e-9);
  EXPECT_LE(worst, 1.5 * f0 * 0.001 / 0.005 + 1e-9);
  EXPECT_GT(worst, 0.0);
}

TEST(HapticPipeline, SpiralSeenEdgeOnGivesBoundedPerTickIncrements)
{
  // A planar spiral seen almost edge-on (its plane tilted 3 deg from the view direction): the
  // projection folds back on itself, with cusps where dl -> 0 and the LDGF slope flips sign.
  const double tilt = 3.0 * kPi / 180.0;
  const QSkeleton s = singlePath(
    [tilt](double u)
    {
      const double t = 4 * kPi * u;
      const double r = 8 + 3 * t;
      const double a = r * std::cos(t);
      const double b = r * std::sin(t);
      return Vec3{ a, b * std::sin(tilt), b * std::cos(tilt) };
    },
    2400);
  PipelineRig rig;
  rig.view = buildView(s, topCamera({ 0, 0, 0 }, 0.1), 12.0);
  rig.params.maxForceRate_N_per_s = 100.0;
  rig.pipeline.setCursor_px(rig.view->screen_px(0));
  rig.step();
  ASSERT_EQ(rig.pipeline.tracer().state(), InteractionState::Tracing);
  // Drive the hand so that the cursor follows the projected spiral point by point.
  double worstTargetJump = 0.0;
  double worstIncrement = 0.0;
  Vec2 previousTarget;
  Vec2 previousForce;
  int lastPoint = 0;
  for (int k = 1; k < 2400; ++k)
  {
    const Vec2 d = rig.view->screen_px(k) - rig.view->screen_px(k - 1);
    rig.device.position_Device_mm.x += d.x / 4.0;
    rig.device.position_Device_mm.y += d.y / 4.0;
    const AgentState st = rig.step();
    if (k > 1)
    {
      worstTargetJump = std::max(worstTargetJump, (st.targetForce_N - previousTarget).norm());
      worstIncrement = std::max(worstIncrement, (st.force_N - previousForce).norm());
    }
    previousTarget = st.targetForce_N;
    previousForce = st.force_N;
    lastPoint = st.point;
  }
  EXPECT_GT(lastPoint, 2000);             // the agent followed through the cusps
  EXPECT_GT(worstTargetJump, 1.0);        // the raw law jumps at the cusps ...
  EXPECT_LE(worstIncrement, 0.1 + 1e-12); // ... the rendered force moves <= 100 N/s * 1 ms
}

TEST(HapticPipeline, EdgeOnSpiralWithDitheringHandIsTracedMonotonicallyWithBoundedIncrements)
{
  // A planar spiral seen exactly edge-on (the cusp of Yi & Hayward's Figure 4): on screen it runs
  // back and forth along one line. A scripted hand follows it with a seeded dither; at each cusp
  // the projections on "back" and "on" coincide and the tracer's hysteresis must keep going.
  const QSkeleton s = singlePath(
    [](double u)
    {
      const double t = 4 * kPi * u;
      const double r = 8 + 3 * t;
      return Vec3{ r * std::cos(t), 0.0, r * std::sin(t) };
    },
    1200);
  PipelineRig rig;
  rig.view = buildView(s, topCamera({ 0, 0, 0 }, 0.25), 12.0);
  rig.params.maxForceRate_N_per_s = 100.0;
  rig.pipeline.setCursor_px(rig.view->screen_px(0));
  rig.step();
  ASSERT_EQ(rig.pipeline.tracer().state(), InteractionState::Tracing);
  // Edge-on, the contact map picks the nearest in depth among many overlapping points: start
  // the agent at the path's head instead (the cursor is there).
  rig.pipeline.tracer().placeAt(*rig.view, 0);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> dither_mm(-0.03, 0.03); // +-0.12 px at 4 px/mm
  const Vec3 base = rig.device.position_Device_mm;
  double worstIncrement = 0.0;
  double worstTargetJump = 0.0;
  int backward = 0;
  int previousPoint = 0;
  Vec2 previousForce;
  Vec2 previousTarget;
  const Vec2 start = rig.view->screen_px(0);
  for (int k = 1; k < 1200; ++k)
  {
    const Vec2 goal = (rig.view->screen_px(k) - start) * 0.25; // hand mm
    rig.device.position_Device_mm.x = base.x + goal.x + dither_mm(rng);
    rig.device.position_Device_mm.y = base.y + goal.y + dither_mm(rng);
    const AgentState st = rig.step();
    ASSERT_EQ(st.state, InteractionState::Tracing) << k;
    backward += st.point < previousPoint ? 1 : 0;
    previousPoint = std::max(previousPoint, st.point);
    if (k > 1)
    {
      worstIncrement = std::max(worstIncrement, (st.force_N - previousForce).norm());
      worstTargetJump = std::max(worstTargetJump, (st.targetForce_N - previousTarget).norm());
    }
    previousForce = st.force_N;
    previousTarget = st.targetForce_N;
  }
  EXPECT_EQ(backward, 0);                 // monotone along the path: no back-and-forth at the cusps
  EXPECT_GE(previousPoint, 1190);         // followed to the end
  EXPECT_GT(worstTargetJump, 0.1);        // the raw law does jump at the cusps ...
  EXPECT_LE(worstIncrement, 0.1 + 1e-12); // ... the rendered force moves <= 100 N/s * 1 ms
}

TEST(HapticPipeline, ProxyDragHoldsTangentForceAtThresholdWhileDragging)
{
  // Ikits et al. eq. 8: along a Drag axis the proxy stays put while |F_t| <= tau_t and, once
  // dragged, trails the hand so that the coupler force stays tau_t. Hand moving steadily along a
  // straight vessel: the tangential force settles at -(tau_t + b_c v), the normal force at 0.
  PipelineRig rig;
  rig.view = buildView(straightLine({ -40, 0, 0 }, { 40, 0, 0 }, 0.25), topCamera({ 0, 0, 0 }));
  rig.params.forceLaw = ForceLawId::ConstraintProxy;
  rig.params.proxyTangentDrag = true;
  rig.params.maxForceRate_N_per_s = 1e9;
  AgentState st = rig.step(); // contact at the viewport centre
  ASSERT_EQ(st.state, InteractionState::Tracing);
  const double v_mm_per_tick = 0.02; // 20 mm/s
  for (int k = 0; k < 800; ++k)
  {
    rig.device.position_Device_mm.x += v_mm_per_tick;
    rig.device.velocity_Device_mm_per_s.x = v_mm_per_tick * 1000.0;
    st = rig.step();
  }
  const double tau = rig.params.proxyTangentThreshold_N;
  const double damping = rig.params.proxyDamping_N_s_per_m * 0.02;
  EXPECT_NEAR(st.force_N.x, -(tau + damping), 0.01);
  EXPECT_NEAR(st.force_N.y, 0.0, 1e-9);
  // Stopping: the proxy stays, the spring force stays at tau (not above) and never reverses.
  rig.device.velocity_Device_mm_per_s.x = 0.0;
  for (int k = 0; k < 50; ++k)
  {
    st = rig.step();
  }
  EXPECT_NEAR(st.force_N.x, -tau, 0.01);
  // Pulling back by less than 2 tau / k_c keeps the proxy still (the stick band of eq. 8).
  rig.device.position_Device_mm.x -= 2.0; // 2 mm < 2 * 0.3 / 200 m = 3 mm
  st = rig.step();
  st = rig.step();
  const double kc = rig.params.proxyStiffness_N_per_m;
  EXPECT_NEAR(st.force_N.x, -tau + kc * 2e-3, 0.01);
}

TEST(HapticPipeline, ProxySnapDragMovesTheAgentInStepsOfTau)
{
  // Ikits eq. 11 in the loop: the hand slides along the vessel at 20 mm/s; the agent stands still,
  // then jumps by tau = tau_t / k_c = 1.5 mm (6 px), and the tangent force is a sawtooth that
  // never exceeds tau_t.
  PipelineRig rig;
  rig.view = buildView(straightLine({ -40, 0, 0 }, { 40, 0, 0 }, 0.25), topCamera({ 0, 0, 0 }));
  rig.params.forceLaw = ForceLawId::ConstraintProxy;
  rig.params.proxyTangentSnap = true;
  rig.params.proxyDamping_N_s_per_m = 0.0;
  rig.params.maxForceRate_N_per_s = 1e9;
  ASSERT_EQ(rig.step().state, InteractionState::Tracing);
  double x0 = rig.step().agentScreen_px.x;
  int jumps = 0;
  double worst = 0.0;
  for (int k = 1; k <= 1000; ++k)
  {
    rig.device.position_Device_mm.x = 0.02 * k;
    const AgentState s = rig.step();
    const double dx = s.agentScreen_px.x - x0;
    x0 = s.agentScreen_px.x;
    if (dx != 0.0)
    {
      EXPECT_NEAR(dx, 6.0, 1e-6) << k;
      ++jumps;
    }
    worst = std::max(worst, std::fabs(s.force_N.x));
  }
  EXPECT_GE(jumps, 12); // 20 mm of hand travel in 1.5 mm steps
  EXPECT_LE(jumps, 14);
  EXPECT_LE(worst, 0.3 + 0.005);
  EXPECT_GT(worst, 0.28);
}

TEST(HapticPipeline, ProxyTickMarksABifurcationWhereTheBranchJoins)
{
  // Ikits' tick-mark texture at a bifurcation: a branch joins the traced vessel at x = 0 (point
  // 160). Sliding the hand along the vessel from x = -5 to +5 mm, the free proxy's tangent force is
  // the detent centred on the junction, a function of the hand's position (drawn in from both
  // sides, peak A at +-w, nothing 2 mm away), and with the option off there is no tangent force at
  // all.
  for (const bool marks : { true, false })
  {
    QSkeleton s = straightLine({ -40, 0, 0 }, { 40, 0, 0 }, 0.25);
    QSkeleton branch = straightLine({ 0, 0.25, 0 }, { 0, 30, 0 }, 0.25);
    branch.paths[0].id = 1;
    s.paths.push_back(branch.paths[0]);
    join(s, 1, Junction::End::Head, 0, 160);
    ASSERT_EQ(s.validate(), "");
    PipelineRig rig;
    rig.view = buildView(s, topCamera({ 0, 0, 0 }));
    rig.params.forceLaw = ForceLawId::ConstraintProxy;
    rig.params.proxyDamping_N_s_per_m = 0.0;
    rig.params.proxyTickAtBifurcations = marks;
    rig.params.maxForceRate_N_per_s = 1e9;
    ASSERT_EQ(rig.step().state, InteractionState::Tracing); // the cursor starts at x = 0
    for (int k = 1; k <= 500; ++k)
    {
      rig.device.position_Device_mm.x = -0.01 * k; // back to x = -5 mm
      rig.step();
    }
    const double A = rig.params.proxyTickForce_N;
    const double w = 0.25; // ConstraintProxyForceLaw::tickWidth_mm
    double peakBefore = 0.0, peakAfter = 0.0, far = 0.0, wrongSign = 0.0;
    for (int k = 0; k <= 1000; ++k)
    {
      rig.device.position_Device_mm.x = -5.0 + 0.01 * k;
      const AgentState a = rig.step();
      ASSERT_EQ(a.path, 0) << k;
      // Arc from the junction along increasing index where the detent is read: the cursor's
      // projection on the vessel (the hand, 1:1 here), not the agent, which the dead band makes
      // lag the hand (Tracer::locationToward).
      const double u = rig.device.position_Device_mm.x;
      const double f = a.force_N.x;
      if (std::fabs(u) > 2.0)
        far = std::max(far, std::fabs(f));
      else if (u < -0.05)
        peakBefore = std::max(peakBefore, f), wrongSign = std::max(wrongSign, -f);
      else if (u > 0.05)
        peakAfter = std::max(peakAfter, -f), wrongSign = std::max(wrongSign, f);
      if (marks && std::fabs(std::fabs(u) - w) < 0.01)
      {
        EXPECT_NEAR(std::fabs(f), A, 0.01 * A) << u;
      }
    }
    if (marks)
    {
      EXPECT_NEAR(peakBefore, A, 0.01 * A); // pulls on toward the mark before it
      EXPECT_NEAR(peakAfter, A, 0.01 * A);  // pulls back toward it after
      EXPECT_LE(wrongSign, 1e-9);
      EXPECT_LE(far, 0.02 * A);
    }
    else
    {
      EXPECT_LE(std::max({ peakBefore, peakAfter, far, wrongSign }), 1e-9);
    }
  }
}

TEST(HapticPipeline, ReindexingFreezesCursorWhileHandMoves)
{
  PipelineRig rig;
  rig.view = buildView(straightLine({ -20, 30, 0 }, { 20, 30, 0 }, 0.25), topCamera({ 0, 0, 0 }));
  rig.step();
  const Vec2 c0 = rig.pipeline.cursor_px();
  rig.device.buttons = rig.params.reindexButtonMask;
  rig.device.position_Device_mm = { 10, 5, 0 };
  rig.step();
  EXPECT_EQ(rig.pipeline.cursor_px().x, c0.x);
  EXPECT_TRUE(rig.step().reindexing);
  rig.device.buttons = 0;
  rig.device.position_Device_mm = { 11, 5, 0 };
  rig.step();
  EXPECT_NEAR(rig.pipeline.cursor_px().x, c0.x + 4.0, 1e-9);
  // With a pressure input, lifting the stylus re-indexes and zeroes the force zone.
  rig.caps.hasPressure = true;
  rig.device.pressure = 0.0;
  rig.device.position_Device_mm = { 20, 5, 0 };
  const AgentState s = rig.step();
  EXPECT_TRUE(s.reindexing);
  EXPECT_EQ(s.zoneGain_N, 0.0);
  EXPECT_NEAR(rig.pipeline.cursor_px().x, c0.x + 4.0, 1e-9);
}

TEST(HapticPipeline, ZoomScalesCursorMotionButKeepsFeltSlope)
{
  const QSkeleton line = straightLine({ -60, 0, 0 }, { 60, 0, 60 }, 0.25);
  Vec2 ldgf[3];
  int i = 0;
  for (double zoom : { 0.1, 1.0, 10.0 })
  {
    PipelineRig rig;
    rig.view = buildView(line, topCamera({ 0, 0, 30 }));
    rig.params.zoom = zoom;
    rig.params.maxForceRate_N_per_s = 1e9;
    rig.step();
    rig.device.position_Device_mm = { 1.0, 0, 0 };
    rig.step();
    EXPECT_NEAR(rig.pipeline.cursor_px().x, 400.0 + 4.0 * zoom, 1e-9);
    ldgf[i++] = rig.step().force_N;
  }
  EXPECT_NEAR(ldgf[0].x, ldgf[1].x, 1e-6);
  EXPECT_NEAR(ldgf[2].x, ldgf[1].x, 1e-6);
  EXPECT_LT(ldgf[1].x, -0.4);
  // The coupler is stiff in hand millimetres whatever the zoom: 1 mm of hand across the vessel
  // gives k_c * 1 mm.
  for (double zoom : { 0.5, 2.0 })
  {
    PipelineRig rig;
    rig.view = buildView(line, topCamera({ 0, 0, 30 }));
    rig.params.zoom = zoom;
    rig.params.forceLaw = ForceLawId::ConstraintProxy;
    rig.params.proxyDamping_N_s_per_m = 0.0;
    rig.params.maxForceRate_N_per_s = 1e9;
    rig.step();
    rig.device.position_Device_mm = { 0, 1.0, 0 };
    const AgentState s = rig.step();
    EXPECT_NEAR(s.force_N.y, -0.2, 1e-6) << zoom;
  }
}

TEST(HapticPipeline, ButtonClickReturnsToExploringWithStillHand)
{
  // Yi & Hayward §3.2: "a button click returns the user to the exploration state". The hand does
  // not move: the cursor stays within the capture radius, and the agent must not be recaptured.
  PipelineRig rig;
  rig.params = HapticParameters{}; // the product's contact rule (approach + dwell)
  rig.view = buildView(straightLine({ -20, 0, 0 }, { 20, 0, 0 }, 0.25), topCamera({ 0, 0, 0 }));
  // The cursor starts at the centre, on the vessel: no capture before any input.
  for (int k = 0; k < 200; ++k)
  {
    ASSERT_EQ(rig.step().state, InteractionState::Exploring) << k;
  }
  // Approach from 10 mm (40 px) below, then rest on the vessel: captured after the dwell.
  rig.device.position_Device_mm = { 0, -10, 0 };
  EXPECT_EQ(rig.step().state, InteractionState::Exploring);
  rig.device.position_Device_mm = { 0, 0, 0 };
  int ticks = 0;
  while (rig.step().state == InteractionState::Exploring && ticks < 1000)
  {
    ++ticks;
  }
  EXPECT_EQ(ticks + 1, static_cast<int>(std::lround(rig.params.contactDwell_s / 0.001)));
  // Click (one tick down, then up) with the hand still: exploring, and it stays so.
  rig.device.buttons = rig.params.releaseButtonMask;
  EXPECT_EQ(rig.step().state, InteractionState::Exploring);
  rig.device.buttons = 0;
  for (int k = 0; k < 1000; ++k)
  {
    const AgentState s = rig.step();
    ASSERT_EQ(s.state, InteractionState::Exploring) << k;
    ASSERT_EQ(s.force_N.norm(), 0.0) << k;
  }
  // Holding the button does not click again; leaving and coming back captures again.
  rig.device.position_Device_mm = { 0, 10, 0 };
  EXPECT_EQ(rig.step().state, InteractionState::Exploring);
  rig.device.position_Device_mm = { 0, 0, 0 };
  AgentState s;
  for (int k = 0; k < 60; ++k)
  {
    s = rig.step();
  }
  EXPECT_EQ(s.state, InteractionState::Tracing);
  // Without any view model the pipeline explores with zero force.
  rig.view.reset();
  EXPECT_EQ(rig.step().state, InteractionState::Exploring);
}

TEST(HapticPipeline, QuickPointerClickReleasesTracing)
{
  // Issue 20: a press and a release between two ticks (an instant click) must still release.
  PipelineRig rig;
  rig.view = buildView(straightLine({ -20, 0, 0 }, { 20, 0, 0 }, 0.25), topCamera({ 0, 0, 0 }));
  PointerDevice pointer;
  ASSERT_EQ(pointer.open(), DeviceStatus::Ok);
  auto tick = [&]()
  {
    EXPECT_EQ(pointer.read(rig.device), DeviceStatus::Ok);
    return rig.step();
  };
  ASSERT_EQ(tick().state, InteractionState::Tracing);
  for (int click = 0; click < 4; ++click)
  {
    pointer.setButtons(0x1);
    pointer.setButtons(0x0);
    EXPECT_EQ(tick().state, InteractionState::Exploring) << click;
    EXPECT_EQ(tick().state, InteractionState::Exploring) << click;
    // Back onto the vessel from 40 px away (immediate contact in this rig).
    pointer.setPointerPosition({ 0.0, 10.0 });
    EXPECT_EQ(tick().state, InteractionState::Exploring) << click;
    pointer.setPointerPosition({ 0.0, 0.0 });
    EXPECT_EQ(tick().state, InteractionState::Tracing) << click;
  }
  EXPECT_EQ(pointer.deliveredPressCount(0), 4u);
}

TEST(HapticPipeline, CrossedVesselDoesNotCaptureOnTheWayToAnother)
{
  // Issue 20: the agent was captured by the first vessel crossed on the way to another. Two
  // parallel vessels 60 px apart; the cursor sweeps across the first at 1 px/tick (1000 px/s,
  // 24 px of capture zone crossed in 24 ms < the 50 ms dwell) and stops on the second.
  PipelineRig rig;
  rig.params = HapticParameters{};
  QSkeleton two = straightLine({ -20, 0, 0 }, { 20, 0, 0 }, 0.25);
  const QSkeleton second = straightLine({ -20, 15, 0 }, { 20, 15, 0 }, 0.25);
  two.paths.push_back(second.paths[0]);
  rig.view = buildView(two, topCamera({ 0, 0, 0 }));
  rig.step();                                    // the cursor starts at the centre, on the first
  rig.device.position_Device_mm = { 0, -10, 0 }; // then 40 px below it
  rig.step();
  AgentState s;
  for (int k = 1; k <= 100; ++k) // 100 px up, 0.25 mm per tick
  {
    rig.device.position_Device_mm = { 0, -10 + 0.25 * k, 0 };
    s = rig.step();
    ASSERT_EQ(s.state, InteractionState::Exploring) << k;
  }
  for (int k = 0; k < 60; ++k) // rests on the second vessel
  {
    s = rig.step();
  }
  EXPECT_EQ(s.state, InteractionState::Tracing);
  EXPECT_EQ(s.path, 1);
  // The same sweep at 0.1 px/tick (100 px/s) is an approach to the first vessel: it captures.
  PipelineRig slow;
  slow.params = HapticParameters{};
  slow.view = rig.view;
  slow.step();
  slow.device.position_Device_mm = { 0, -10, 0 };
  slow.step();
  int k = 0;
  for (; k < 1000 && s.path != 0; ++k)
  {
    slow.device.position_Device_mm = { 0, -10 + 0.025 * k, 0 };
    s = slow.step();
  }
  EXPECT_EQ(s.state, InteractionState::Tracing);
  EXPECT_EQ(s.path, 0);
}

TEST(HapticPipeline, UnattendedHandleWithoutPressureIsSilencedAfterDwell)
{
  // Yi & Hayward §5.2: "a zero-force zone prevents any activity when the device is left
  // unattended". A device without pressure/z (caps.hasPressure false) gets it from a dwell gate:
  // resting within 1 mm for 1.5 s fades the force out over 50 ms; moving out brings it back.
  PipelineRig rig;
  rig.caps.hasPressure = false;
  rig.view = buildView(straightLine({ -20, 0, 0 }, { 20, 0, 20 }, 0.25), topCamera({ 0, 0, 10 }));
  rig.params.maxForceRate_N_per_s = 1e9; // see the gate, not the interpolation
  AgentState s = rig.step();
  ASSERT_EQ(s.state, InteractionState::Tracing);
  double full = 0.0;
  int silencedAt = -1;
  for (int k = 1; k < 2000; ++k)
  {
    // A resting hand with 0.2 mm of tremor: within the 1 mm radius.
    rig.device.position_Device_mm.x = 0.2 * std::sin(0.05 * k);
    s = rig.step();
    if (k == 100)
    {
      full = s.force_N.norm();
    }
    if (silencedAt < 0 && s.force_N.norm() == 0.0)
    {
      silencedAt = k;
    }
  }
  ASSERT_GT(full, 0.3);
  EXPECT_TRUE(s.idle);
  EXPECT_EQ(s.force_N.norm(), 0.0);
  EXPECT_GE(silencedAt, 1500 + 45); // the dwell, then the fade
  EXPECT_LE(silencedAt, 1500 + 55);
  // Moving 2 mm wakes it: the force fades back in (no step).
  rig.device.position_Device_mm.x = 0.0;
  rig.device.position_Device_mm.y = 0.5; // 2 px across the vessel: the agent stays put
  s = rig.step();
  rig.device.position_Device_mm.y = -1.5;
  double previous = s.force_N.norm();
  double worst = 0.0;
  for (int k = 0; k < 100; ++k)
  {
    s = rig.step();
    worst = std::max(worst, s.force_N.norm() - previous);
    previous = s.force_N.norm();
  }
  EXPECT_FALSE(s.idle);
  EXPECT_NEAR(s.force_N.norm(), full, 0.05 * full);
  EXPECT_LE(worst, full * 0.001 / 0.05 + 0.02 * full);
  // A device with pressure keeps its own zero-force zone: no dwell gate.
  PipelineRig pressure;
  pressure.caps.hasPressure = true;
  pressure.device.pressure = 1.0;
  pressure.view = rig.view;
  for (int k = 0; k < 2000; ++k)
  {
    s = pressure.step();
  }
  EXPECT_FALSE(s.idle);
  EXPECT_GT(s.force_N.norm(), 0.3);
}

TEST(HapticPipeline, ViewChangeWhileTracingKeepsAgentAndBoundsForceStep)
{
  // The camera turns by 60 degrees in one frame: the slope under the agent jumps, the rendered
  // force does not (time-domain interpolation), and the agent stays on the same point.
  const QSkeleton s = straightLine({ -20, 0, 0 }, { 20, 0, 20 }, 0.25);
  auto topo = SceneTopology::build(s, 1.0);
  ViewModelBuilder builder;
  PipelineRig rig;
  rig.view = builder.build(topo, topCamera({ 0, 0, 10 }));
  rig.params.maxForceRate_N_per_s = 100.0;
  AgentState st;
  for (int k = 0; k < 50; ++k)
  {
    st = rig.step();
  }
  ASSERT_EQ(st.state, InteractionState::Tracing);
  const int point = st.point;
  const Vec2 before = st.force_N;
  rig.view = builder.build(topo,
    makeOrthographicCamera(
      { 0, 0, 10 }, { std::sin(kPi / 3), 0, -std::cos(kPi / 3) }, { 0, 1, 0 }, 75.0, 800, 600));
  double worst = 0.0;
  Vec2 previous = before;
  for (int k = 0; k < 50; ++k)
  {
    st = rig.step();
    worst = std::max(worst, (st.force_N - previous).norm());
    previous = st.force_N;
  }
  EXPECT_EQ(st.state, InteractionState::Tracing);
  EXPECT_NEAR(st.point, point, 1);
  EXPECT_GT((st.force_N - before).norm(), 0.3); // the slope did change a lot ...
  EXPECT_LE(worst, 0.1 + 1e-12);                // ... but by at most 0.1 N per 1 ms tick
}

TEST(HapticPipeline, NonFiniteTracerSettingsFallBackToTheParameterTablesDefaults)
{
  // A raw HapticParameters may carry NaN or infinity (the facade validates; scripts built on the
  // struct do not): each tracer setting then takes the table's default, never a stale or made-up
  // value, and the tick stays finite.
  PipelineRig rig;
  rig.view = buildView(straightLine({ -20, 0, 0 }, { 20, 0, 20 }, 0.25), topCamera({ 0, 0, 10 }));
  const HapticParameters defaults{};
  rig.params.tracerDirectionHysteresis = std::numeric_limits<double>::quiet_NaN();
  rig.params.tracerMovementThreshold_px = std::numeric_limits<double>::infinity();
  rig.params.tracerFoldLookAhead_px = -std::numeric_limits<double>::infinity();
  rig.params.tracerJunctionWindow_px = std::numeric_limits<double>::quiet_NaN();
  rig.params.tracerJunctionMargin_px = std::numeric_limits<double>::quiet_NaN();
  rig.params.contactDwell_s = std::numeric_limits<double>::quiet_NaN();
  // Start from values that differ from the defaults, so a setting left untouched shows.
  rig.pipeline.tracer().directionHysteresis = 0.9;
  rig.pipeline.tracer().movementThreshold_px = 7.0;
  rig.pipeline.tracer().foldLookAhead_px = 50.0;
  rig.pipeline.tracer().junctionWindow_px = 400.0;
  rig.pipeline.tracer().junctionMargin_px = 15.0;
  const AgentState s = rig.step();
  const Tracer& t = rig.pipeline.tracer();
  EXPECT_EQ(t.directionHysteresis, defaults.tracerDirectionHysteresis);
  EXPECT_EQ(t.movementThreshold_px, defaults.tracerMovementThreshold_px);
  EXPECT_EQ(t.foldLookAhead_px, defaults.tracerFoldLookAhead_px);
  EXPECT_EQ(t.junctionWindow_px, defaults.tracerJunctionWindow_px);
  EXPECT_EQ(t.junctionMargin_px, defaults.tracerJunctionMargin_px);
  EXPECT_EQ(rig.pipeline.contactGate().dwell_s, defaults.contactDwell_s);
  EXPECT_TRUE(std::isfinite(s.force_N.x) && std::isfinite(s.force_N.y));
}

} // namespace
} // namespace vtouch

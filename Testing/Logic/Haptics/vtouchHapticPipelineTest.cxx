#include "vtouchHapticPipeline.h"
#include "vtouchHapticsTestUtilities.h"

#include <gtest/gtest.h>

namespace vtouch
{
namespace
{
using namespace vtouch::testing;

struct PipelineRig
{
  std::shared_ptr<ViewModel> view;
  HapticPipeline pipeline;
  HapticParameters params;
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

TEST(HapticPipeline, ButtonClickReturnsToExploring)
{
  PipelineRig rig;
  rig.view = buildView(straightLine({ -20, 0, 0 }, { 20, 0, 0 }, 0.25), topCamera({ 0, 0, 0 }));
  ASSERT_EQ(rig.step().state, InteractionState::Tracing);
  rig.device.buttons = rig.params.releaseButtonMask;
  rig.device.position_Device_mm = { 0, 10, 0 }; // and move away while clicking
  EXPECT_EQ(rig.step().state, InteractionState::Exploring);
  // Holding the button does not click again; away from the vessel it stays exploring.
  EXPECT_EQ(rig.step().state, InteractionState::Exploring);
  EXPECT_EQ(rig.step().force_N.norm(), 0.0);
  // Without any view model the pipeline explores with zero force.
  rig.view.reset();
  EXPECT_EQ(rig.step().state, InteractionState::Exploring);
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

} // namespace
} // namespace vtouch

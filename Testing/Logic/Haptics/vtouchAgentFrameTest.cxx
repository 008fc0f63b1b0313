// The cone's roll (Yi & Hayward §7): a rotation-minimising frame plus the integrated torsion.
#include "vtouchAgentFrame.h"
#include "vtouchAgentPose.h"
#include "vtouchHapticPipeline.h"
#include "vtouchHapticsTestUtilities.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace vtouch
{
namespace
{
using namespace vtouch::testing;

constexpr double kA = 10.0; // helix radius, mm
constexpr double kC = 3.0;  // pitch / (2 pi), mm
constexpr double kTurns = 3.0;

Vec3 helix(double u)
{
  return { kA * std::cos(u), kA * std::sin(u), kC * u };
}

/// The helix with its exact torsion tau = c / (a^2 + c^2) on every point.
QSkeleton helixSkeleton(int count)
{
  QSkeleton s = singlePath([](double v) { return helix(2.0 * kPi * kTurns * v); }, count);
  for (SkeletonPoint& p : s.paths[0].points)
  {
    p.torsion_per_mm = kC / (kA * kA + kC * kC);
  }
  return s;
}

TEST(AgentFrame, ConeRollReproducesConeNormalThroughAgentConeMatrix)
{
  // The roll handed to agentConeMatrix() must put the cone's first axis on the frame's normal,
  // for either apex sign and for tangents near the world Z axis (the reference switches to X).
  for (const Vec3& t0 : { Vec3{ 1, 0, 0 }, Vec3{ 0.3, 0.2, 0.93 }, Vec3{ 0, 0.6, -0.8 } })
  {
    for (int sign : { 1, -1 })
    {
      AgentFrame frame;
      const Vec3 t = t0 * (1.0 / t0.norm());
      frame.update({ 0, 0, 0 }, t, 0.0, sign);
      frame.update(t * 0.5, t, 0.7, sign); // rolled by 0.7 rad
      Matrix4x4 m{};
      ASSERT_TRUE(agentConeMatrix({}, t * static_cast<double>(sign), frame.coneRoll_rad(), 1.0, m));
      const Vec3 u{ m[0], m[4], m[8] };
      EXPECT_NEAR((u - frame.coneNormal_World()).norm(), 0.0, 1e-12);
      EXPECT_NEAR(frame.coneNormal_World().dot(frame.rmfNormal_World()), std::cos(0.7), 1e-12);
    }
  }
}

TEST(AgentFrame, RmfHasNoTwistOnAPlanarCurve)
{
  // On a plane curve the RMF normal stays in the plane's normal direction (no twist): a circle in
  // z = 0 with the normal starting along +z keeps it.
  AgentFrame frame;
  for (int k = 0; k <= 400; ++k)
  {
    const double u = 2.0 * kPi * k / 400.0;
    frame.update({ std::cos(u), std::sin(u), 0.0 }, { -std::sin(u), std::cos(u), 0.0 }, 0.0, 1);
    ASSERT_NEAR(frame.rmfNormal_World().z, 1.0, 1e-12) << k;
  }
}

TEST(AgentFrame, ConeRollRateEqualsTorsionOnHelix)
{
  // A helix seen from the side; the hand drives the cursor along its projection, the agent
  // follows the centerline. The cone's normal (through agentConeMatrix, as the view draws it)
  // must turn about the tangent, relative to an independent rotation-minimising frame, at the
  // rate tau = c / (a^2 + c^2) per mm of arc. Measuring the roll from a world axis instead adds
  // the world frame's own turn about the tangent.
  const int count = 3000;
  const QSkeleton s = helixSkeleton(count);
  HapticPipeline pipeline;
  HapticParameters params = immediateContact();
  const auto view = buildView(s,
    makeOrthographicCamera({ 0, 0, kC * kPi * kTurns }, { 0, 1, 0 }, { 0, 0, 1 }, 75.0, 800, 600));
  pipeline.setCursor_px(view->screen_px(0));
  DeviceCapabilities caps;
  TickInput in;
  in.capabilities = &caps;
  in.view = view.get();
  in.device.pressure = 1.0;
  // The independent RMF along the samples, by double reflection on a 10x finer sampling.
  const int fine = 10 * (count - 1);
  std::vector<Vec3> rmf(fine + 1);
  std::vector<Vec3> tan(fine + 1);
  const double du = 2.0 * kPi * kTurns / fine;
  for (int i = 0; i <= fine; ++i)
  {
    const double u = i * du;
    tan[i] = Vec3{ -kA * std::sin(u), kA * std::cos(u), kC } * (1.0 / std::hypot(kA, kC));
  }
  rmf[0] = Vec3{ 0, 0, 1 } - tan[0] * tan[0].z;
  rmf[0] = rmf[0] * (1.0 / rmf[0].norm());
  for (int i = 0; i < fine; ++i)
  {
    const Vec3 v1 = helix((i + 1) * du) - helix(i * du);
    const double c1 = v1.dot(v1);
    const Vec3 rl = rmf[i] - v1 * (2.0 / c1 * v1.dot(rmf[i]));
    const Vec3 tl = tan[i] - v1 * (2.0 / c1 * v1.dot(tan[i]));
    const Vec3 v2 = tan[i + 1] - tl;
    const double c2 = v2.dot(v2);
    rmf[i + 1] = c2 > 0 ? rl - v2 * (2.0 / c2 * v2.dot(rl)) : rl;
  }
  int lastDirection = 1;
  std::vector<double> arc;
  std::vector<double> angle;
  double unwrapped = 0.0;
  double previous = 0.0;
  for (int k = 1; k < count; ++k)
  {
    const Vec2 d = view->screen_px(k) - view->screen_px(k - 1);
    in.device.position_Device_mm.x += d.x / 4.0;
    in.device.position_Device_mm.y += d.y / 4.0;
    const AgentState st = pipeline.step(in, params);
    ASSERT_EQ(st.state, InteractionState::Tracing) << k;
    Matrix4x4 m{};
    const Vec3 apex = agentApexDirection(st.tangent_World, st.directionOfTravel, lastDirection);
    ASSERT_TRUE(agentConeMatrix(st.position_World_mm, apex, st.coneRoll_rad, 1.0, m));
    const Vec3 coneNormal{ m[0], m[4], m[8] };
    // The agent's parameter on the helix, and the reference frame there.
    const double u = st.position_World_mm.z / kC;
    const int i = std::clamp(static_cast<int>(std::lround(u / du)), 0, fine);
    const Vec3 b = tan[i].cross(rmf[i]);
    const double a = std::atan2(coneNormal.dot(b), coneNormal.dot(rmf[i]));
    if (!arc.empty())
    {
      double step = a - previous;
      step -= 2.0 * kPi * std::round(step / (2.0 * kPi));
      unwrapped += step;
    }
    previous = a;
    arc.push_back(u * std::hypot(kA, kC));
    angle.push_back(unwrapped);
  }
  // Least-squares slope of the roll against the arc length.
  const double n = static_cast<double>(arc.size());
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::size_t k = 0; k < arc.size(); ++k)
  {
    sx += arc[k];
    sy += angle[k];
    sxx += arc[k] * arc[k];
    sxy += arc[k] * angle[k];
  }
  const double slope = (n * sxy - sx * sy) / (n * sxx - sx * sx);
  const double tau = kC / (kA * kA + kC * kC);
  std::printf("[ roll     ] helix tau %.5f /mm, cone roll rate %.5f /mm over %.0f mm of arc\n",
    tau,
    slope,
    arc.back() - arc.front());
  EXPECT_GT(arc.back() - arc.front(), 150.0); // the agent ran (nearly) the whole helix
  EXPECT_NEAR(slope, tau, 0.02 * tau);
}

} // namespace
} // namespace vtouch

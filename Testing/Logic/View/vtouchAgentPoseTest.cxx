// The agent's pose, on-screen size and force arrow (Logic/View/vtouchAgentPose).
#include "vtouchAgentPose.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace
{
constexpr double kPi = 3.14159265358979323846;

vtouch::Vec3 apply(const vtouch::Matrix4x4& m, const vtouch::Vec3& p)
{
  return { m[0] * p.x + m[1] * p.y + m[2] * p.z + m[3],
    m[4] * p.x + m[5] * p.y + m[6] * p.z + m[7],
    m[8] * p.x + m[9] * p.y + m[10] * p.z + m[11] };
}

void expectNear(const vtouch::Vec3& a, const vtouch::Vec3& b, double tolerance = 1e-9)
{
  EXPECT_NEAR(a.x, b.x, tolerance);
  EXPECT_NEAR(a.y, b.y, tolerance);
  EXPECT_NEAR(a.z, b.z, tolerance);
}
} // namespace

TEST(AgentPose, ApexPointsAlongDirectionAndCentreStays)
{
  vtouch::Matrix4x4 m{};
  ASSERT_TRUE(vtouch::agentConeMatrix({ 10.0, 20.0, 30.0 }, { 0.0, 3.0, 0.0 }, 0.0, 8.0, m));
  expectNear(apply(m, { 0.0, 0.0, 0.0 }), { 10.0, 20.0, 30.0 });
  // The unit cone's apex (z = +0.5) lands half the height along the direction.
  expectNear(apply(m, { 0.0, 0.0, 0.5 }), { 10.0, 24.0, 30.0 });
  EXPECT_DOUBLE_EQ(m[15], 1.0);
}

TEST(AgentPose, ZeroRollStripeFacesWorldZ)
{
  vtouch::Matrix4x4 m{};
  ASSERT_TRUE(vtouch::agentConeMatrix({}, { 1.0, 0.0, 0.0 }, 0.0, 1.0, m));
  // The stripe sits at local +X of the cone: world +Z made perpendicular to the axis.
  expectNear(apply(m, { 1.0, 0.0, 0.0 }), { 0.0, 0.0, 1.0 });
}

TEST(AgentPose, RollRotatesAboutTheAxis)
{
  vtouch::Matrix4x4 m{};
  ASSERT_TRUE(vtouch::agentConeMatrix({}, { 1.0, 0.0, 0.0 }, 0.5 * kPi, 1.0, m));
  // +Z rolled a quarter turn about +X (right-handed) is -Y.
  expectNear(apply(m, { 1.0, 0.0, 0.0 }), { 0.0, -1.0, 0.0 });
  expectNear(apply(m, { 0.0, 0.0, 1.0 }), { 1.0, 0.0, 0.0 }); // the axis does not move
}

TEST(AgentPose, AxisNearZUsesXReference)
{
  vtouch::Matrix4x4 m{};
  ASSERT_TRUE(vtouch::agentConeMatrix({}, { 0.0, 0.0, -1.0 }, 0.0, 2.0, m));
  expectNear(apply(m, { 0.5, 0.0, 0.0 }), { 1.0, 0.0, 0.0 });
  expectNear(apply(m, { 0.0, 0.0, 0.5 }), { 0.0, 0.0, -1.0 });
}

TEST(AgentPose, RejectsUnusableInput)
{
  vtouch::Matrix4x4 m{};
  m[0] = 42.0;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(vtouch::agentConeMatrix({}, { 0.0, 0.0, 0.0 }, 0.0, 1.0, m));
  EXPECT_FALSE(vtouch::agentConeMatrix({}, { nan, 0.0, 1.0 }, 0.0, 1.0, m));
  EXPECT_FALSE(vtouch::agentConeMatrix({ nan, 0.0, 0.0 }, { 0.0, 0.0, 1.0 }, 0.0, 1.0, m));
  EXPECT_FALSE(vtouch::agentConeMatrix({}, { 0.0, 0.0, 1.0 }, nan, 1.0, m));
  EXPECT_FALSE(vtouch::agentConeMatrix({}, { 0.0, 0.0, 1.0 }, 0.0, 0.0, m));
  EXPECT_DOUBLE_EQ(m[0], 42.0);
}

TEST(AgentPose, ApexDirectionFollowsTravelAndKeepsItAtRest)
{
  int last = 1;
  expectNear(vtouch::agentApexDirection({ 0.0, 1.0, 0.0 }, -1, last), { 0.0, -1.0, 0.0 });
  EXPECT_EQ(last, -1);
  expectNear(vtouch::agentApexDirection({ 0.0, 1.0, 0.0 }, 0, last), { 0.0, -1.0, 0.0 });
  expectNear(vtouch::agentApexDirection({ 0.0, 1.0, 0.0 }, 1, last), { 0.0, 1.0, 0.0 });
  EXPECT_EQ(last, 1);
}

TEST(AgentPose, MillimetresPerPixelParallelAndPerspective)
{
  vtouch::ScreenScale scale;
  scale.parallelScale_mm = 30.0;
  scale.viewportHeight_px = 600.0;
  EXPECT_DOUBLE_EQ(vtouch::millimetresPerPixel(scale, 1000.0), 0.1);
  scale.parallelProjection = false;
  scale.viewAngle_deg = 90.0;
  EXPECT_NEAR(vtouch::millimetresPerPixel(scale, 300.0), 1.0, 1e-12);
  scale.viewportHeight_px = 0.0;
  EXPECT_EQ(vtouch::millimetresPerPixel(scale, 300.0), 0.0);
}

TEST(AgentPose, ForceArrowScalesAndClamps)
{
  const vtouch::Vec2 tip = vtouch::forceArrowTip_px({ 100.0, 50.0 }, { 0.5, -0.25 }, 40.0, 200.0);
  EXPECT_DOUBLE_EQ(tip.x, 120.0);
  EXPECT_DOUBLE_EQ(tip.y, 40.0);
  const vtouch::Vec2 clamped = vtouch::forceArrowTip_px({ 0.0, 0.0 }, { 10.0, 0.0 }, 40.0, 80.0);
  EXPECT_DOUBLE_EQ(clamped.x, 80.0);
  EXPECT_DOUBLE_EQ(clamped.y, 0.0);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const vtouch::Vec2 same = vtouch::forceArrowTip_px({ 3.0, 4.0 }, { nan, 0.0 }, 40.0, 80.0);
  EXPECT_DOUBLE_EQ(same.x, 3.0);
  EXPECT_DOUBLE_EQ(same.y, 4.0);
}

// Smoothing and differential geometry of sampled curves.
#include "vtouchCurveGeometry.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

namespace vtouch
{
namespace
{
constexpr double kPi = 3.14159265358979323846;

std::vector<Vec3> helix(double a, double c, double step, double noise, std::uint32_t seed)
{
  std::mt19937 rng(seed);
  std::normal_distribution<double> n(0.0, noise);
  std::vector<Vec3> p;
  const double speed = std::sqrt(a * a + c * c);
  for (double s = 0.0; s < 3 * 2 * kPi * speed; s += step)
  {
    const double t = s / speed;
    p.push_back({ a * std::cos(t) + n(rng), a * std::sin(t) + n(rng), c * t + n(rng) });
  }
  return p;
}

TEST(CurveGeometry, HelixCurvatureAndTorsionMatchAnalyticValues)
{
  const double a = 20.0, c = 4.0;
  const std::vector<CurveSample> g = computeCurveGeometry(helix(a, c, 1.0, 0.0, 1), {});
  const double kappa = a / (a * a + c * c), tau = c / (a * a + c * c);
  for (std::size_t i = 20; i + 20 < g.size(); ++i)
  {
    EXPECT_NEAR(g[i].curvature, kappa, 0.01 * kappa);
    EXPECT_NEAR(g[i].torsion, tau, 0.02 * tau);
    EXPECT_NEAR(g[i].tangent.norm(), 1.0, 1e-9);
  }
}

TEST(CurveGeometry, NoisyHelixStaysWithinFivePercentAtTheMedian)
{
  const double a = 20.0, c = 4.0;
  CurveGeometryWindows w;
  w.position_mm = 4.0;
  w.curvature_mm = 24.0;
  w.torsion_mm = 28.0;
  const std::vector<CurveSample> g = computeCurveGeometry(helix(a, c, 1.0, 0.15, 7), w);
  std::vector<double> k, t;
  for (std::size_t i = g.size() / 10; i + g.size() / 10 < g.size(); ++i)
  {
    k.push_back(g[i].curvature);
    t.push_back(g[i].torsion);
  }
  std::sort(k.begin(), k.end());
  std::sort(t.begin(), t.end());
  const double kappa = a / (a * a + c * c), tau = c / (a * a + c * c);
  EXPECT_NEAR(k[k.size() / 2], kappa, 0.05 * kappa);
  EXPECT_NEAR(t[t.size() / 2], tau, 0.05 * tau);
}

TEST(CurveGeometry, StraightLineHasZeroCurvatureAndTorsion)
{
  std::vector<Vec3> p;
  for (int i = 0; i < 40; ++i)
  {
    p.push_back({ 1.0 * i, 0.5 * i, -0.25 * i });
  }
  const std::vector<CurveSample> g = computeCurveGeometry(p, {});
  for (const CurveSample& s : g)
  {
    EXPECT_NEAR(s.curvature, 0.0, 1e-9);
    EXPECT_NEAR(s.torsion, 0.0, 1e-9);
    EXPECT_NEAR(s.tangent.dot(Vec3{ 1.0, 0.5, -0.25 } * (1.0 / std::sqrt(1.3125))), 1.0, 1e-9);
  }
}

TEST(CurveGeometry, ShortCurvesKeepTheirPoints)
{
  const std::vector<Vec3> p{ { 0, 0, 0 }, { 1, 0, 0 } };
  const std::vector<CurveSample> g = computeCurveGeometry(p, {});
  ASSERT_EQ(g.size(), 2U);
  EXPECT_NEAR(g[1].position.x, 1.0, 1e-12);
  EXPECT_NEAR(g[0].tangent.x, 1.0, 1e-12);
  EXPECT_TRUE(computeCurveGeometry({}, {}).empty());
}

/// An L: 30 points along x, then 30 along y, turning at index 30 (the corner, at the origin).
std::vector<Vec3> lShape()
{
  std::vector<Vec3> p;
  for (int i = -30; i <= 0; ++i)
  {
    p.push_back({ 1.0 * i, 0.0, 0.0 });
  }
  for (int j = 1; j <= 30; ++j)
  {
    p.push_back({ 0.0, 1.0 * j, 0.0 });
  }
  return p;
}

/// Distance from p to the L's two legs.
double distanceToL(const Vec3& p)
{
  const double toX = std::hypot(p.y, p.z) + std::max(0.0, p.x);
  const double toY = std::hypot(p.x, p.z) + std::max(0.0, -p.y);
  return std::min(toX, toY);
}

TEST(CurveGeometry, CornersAreKeptWhenNoFitSpansThem)
{
  CurveGeometryWindows w;
  w.position_mm = 8.0;
  w.curvature_mm = 12.0;
  w.torsion_mm = 14.0;
  const std::vector<Vec3> p = lShape();
  const std::vector<CurveSample> cut = computeCurveGeometry(p, w);
  const std::vector<CurveSample> kept = computeCurveGeometry(p, w, { 30 });
  double worstCut = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i)
  {
    worstCut = std::max(worstCut, distanceToL(cut[i].position));
    EXPECT_NEAR(distanceToL(kept[i].position), 0.0, 1e-9) << i;
    EXPECT_NEAR(kept[i].tangent.norm(), 1.0, 1e-9);
    if (i != 30)
    {
      // Straight legs on either side: zero curvature, and the leg's own direction.
      EXPECT_NEAR(kept[i].curvature, 0.0, 1e-9) << i;
      EXPECT_NEAR(i < 30 ? kept[i].tangent.x : kept[i].tangent.y, 1.0, 1e-9) << i;
    }
  }
  // Without the corner the fits round it off (by about half a unit here).
  EXPECT_GT(worstCut, 0.4);
  // The corner itself: the mean of the two one-sided fits, the bisecting tangent.
  EXPECT_NEAR(kept[30].position.norm(), 0.0, 1e-9);
  EXPECT_NEAR(kept[30].tangent.x, std::sqrt(0.5), 1e-9);
  EXPECT_NEAR(kept[30].tangent.y, std::sqrt(0.5), 1e-9);
}

TEST(CurveGeometry, CornersAtTheEndsOrOutOfRangeAreIgnored)
{
  CurveGeometryWindows w;
  w.position_mm = 8.0;
  const std::vector<Vec3> p = lShape();
  const std::vector<CurveSample> plain = computeCurveGeometry(p, w);
  const std::vector<CurveSample> ignored =
    computeCurveGeometry(p, w, { 0, p.size() - 1, p.size(), 1000 });
  ASSERT_EQ(ignored.size(), plain.size());
  for (std::size_t i = 0; i < p.size(); ++i)
  {
    EXPECT_EQ(ignored[i].position.x, plain[i].position.x);
    EXPECT_EQ(ignored[i].position.y, plain[i].position.y);
    EXPECT_EQ(ignored[i].curvature, plain[i].curvature);
  }
  // Repeated corners are one corner; two pieces of one point each still give finite output.
  const std::vector<CurveSample> twice = computeCurveGeometry(p, w, { 30, 30, 31, 29 });
  for (const CurveSample& s : twice)
  {
    EXPECT_TRUE(std::isfinite(s.position.x) && std::isfinite(s.curvature));
    EXPECT_NEAR(s.tangent.norm(), 1.0, 1e-9);
  }
}

} // namespace
} // namespace vtouch

namespace vtouch
{
namespace
{
/// RMS distance of smoothed positions from the circle of radius `rho` around the z axis (a
/// straight line along x when rho is 0), over the middle 80 % of the points.
double rmsOffCurve(const std::vector<CurveSample>& g, double rho)
{
  double sum = 0.0;
  std::size_t n = 0;
  for (std::size_t i = g.size() / 10; i + g.size() / 10 < g.size(); ++i, ++n)
  {
    const Vec3& p = g[i].position;
    const double off = rho > 0.0 ? std::hypot(p.x, p.y) - rho : std::hypot(p.y, p.z);
    sum += off * off + (rho > 0.0 ? p.z * p.z : 0.0);
  }
  return std::sqrt(sum / static_cast<double>(n));
}

std::vector<Vec3> noisyArc(double rho, double length, double noise, std::uint32_t seed)
{
  std::mt19937 rng(seed);
  std::normal_distribution<double> n(0.0, noise);
  std::vector<Vec3> p;
  for (double s = 0.0; s <= length; s += 1.0)
  {
    if (rho > 0.0)
    {
      p.push_back({ rho * std::cos(s / rho) + n(rng), rho * std::sin(s / rho) + n(rng), n(rng) });
    }
    else
    {
      p.push_back({ s, n(rng), n(rng) });
    }
  }
  return p;
}

// Where the curve is straight, the position window widens toward widestPosition_mm and averages
// more of the noise away; on a tight bend it stays at position_mm, so the fit adds no bias there.
TEST(CurveGeometry, PositionWindowWidensOnStraightStretchesOnly)
{
  CurveGeometryWindows fixed;
  fixed.position_mm = 8.0;
  fixed.curvature_mm = 24.0;
  fixed.torsion_mm = 28.0;
  CurveGeometryWindows adaptive = fixed;
  adaptive.widestPosition_mm = 12.0;
  double fixedLine = 0.0, adaptiveLine = 0.0;
  for (std::uint32_t seed = 1; seed <= 5; ++seed)
  {
    const std::vector<Vec3> line = noisyArc(0.0, 200.0, 0.3, seed);
    fixedLine += rmsOffCurve(computeCurveGeometry(line, fixed), 0.0);
    adaptiveLine += rmsOffCurve(computeCurveGeometry(line, adaptive), 0.0);
  }
  EXPECT_LT(adaptiveLine, 0.85 * fixedLine);
  // A bend of radius 6 (window / 1.2 = 10 > 6 everywhere): no widening, the same positions.
  const std::vector<Vec3> arc = noisyArc(6.0, 0.9 * 2.0 * kPi * 6.0, 0.0, 1);
  const std::vector<CurveSample> a = computeCurveGeometry(arc, adaptive);
  const std::vector<CurveSample> f = computeCurveGeometry(arc, fixed);
  for (std::size_t i = 0; i < a.size(); ++i)
  {
    EXPECT_NEAR((a[i].position - f[i].position).norm(), 0.0, 1e-12);
  }
}
} // namespace
} // namespace vtouch

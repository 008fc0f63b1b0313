#include "vtouchPhantomGenerator.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

using vtouch::PhantomGenerator;
using vtouch::PhantomShape;
using vtouch::PhantomSpec;
using vtouch::Vec3;

namespace
{
constexpr double kPi = 3.14159265358979323846;

PhantomSpec smallSpec(PhantomShape shape)
{
  PhantomSpec spec;
  spec.shape = shape;
  spec.dimensions = { 64, 64, 64 };
  spec.radiusFraction = 0.05;
  return spec;
}

std::vector<float> render(const PhantomGenerator& g)
{
  const auto& d = g.spec().dimensions;
  std::vector<float> v(static_cast<std::size_t>(d[0]) * d[1] * d[2]);
  EXPECT_TRUE(g.fill(v.data()));
  return v;
}

/// Value of the voxel nearest to a world point.
float sampleNearest(const PhantomGenerator& g, const std::vector<float>& v, const Vec3& p)
{
  const PhantomSpec& s = g.spec();
  int idx[3];
  const double* pp = &p.x;
  for (int a = 0; a < 3; ++a)
  {
    idx[a] = std::clamp(static_cast<int>(std::lround((pp[a] - s.origin_mm[a]) / s.spacing_mm[a])),
      0,
      s.dimensions[a] - 1);
  }
  return v[(static_cast<std::size_t>(idx[2]) * s.dimensions[1] + idx[1]) * s.dimensions[0] +
           idx[0]];
}
} // namespace

TEST(PhantomGenerator, InvalidSpecGivesErrorAndNoOutput)
{
  PhantomSpec spec;
  spec.dimensions = { 10, 10, 1 };
  PhantomGenerator g(spec);
  EXPECT_FALSE(g.ok());
  EXPECT_FALSE(g.error().empty());
  EXPECT_TRUE(g.centerline().empty());
  std::vector<float> v(100, -1.0f);
  EXPECT_FALSE(g.fill(v.data()));
  EXPECT_EQ(v[0], -1.0f);
}

TEST(PhantomGenerator, HelixLengthMatchesItsFormula)
{
  PhantomSpec spec = smallSpec(PhantomShape::Helix);
  PhantomGenerator g(spec);
  ASSERT_TRUE(g.ok()) << g.error();
  const double n = spec.referenceLength_mm();
  const double a = spec.helixRadiusFraction * n;
  const double pitch = spec.helixPitchFraction * n;
  const double expected = spec.helixTurns * std::sqrt(std::pow(2 * kPi * a, 2) + pitch * pitch);
  EXPECT_NEAR(g.totalLength_mm(), expected, 1e-3 * expected);
}

TEST(PhantomGenerator, HelixCarriesAnalyticCurvatureAndTorsion)
{
  PhantomSpec spec = smallSpec(PhantomShape::Helix);
  PhantomGenerator g(spec);
  ASSERT_TRUE(g.ok());
  const double n = spec.referenceLength_mm();
  const double a = spec.helixRadiusFraction * n;
  const double c = spec.helixPitchFraction * n / (2 * kPi);
  const auto& pts = g.centerline().paths.at(0).points;
  ASSERT_GT(pts.size(), 100u);
  for (std::size_t i = 10; i + 10 < pts.size(); i += 37)
  {
    EXPECT_NEAR(pts[i].curvature_per_mm, a / (a * a + c * c), 1e-4);
    EXPECT_NEAR(pts[i].torsion_per_mm, c / (a * a + c * c), 1e-4);
    EXPECT_NEAR(pts[i].tangent_World.norm(), 1.0, 1e-9);
  }
}

// The winding line's crests bend with radius 0.64 N / (A (2 pi k)^2) (amplitude A N, k periods
// over 0.8 N): the defaults fold the default vessel at every crest, amplitude 0.1 and one period
// make a sinuous vessel; absurd values are rejected.
TEST(PhantomGenerator, WindingLineCrestsBendAsSpecified)
{
  for (const auto& [amplitude, periods] : { std::pair{ 0.2, 2.0 }, std::pair{ 0.1, 1.0 } })
  {
    PhantomSpec spec = smallSpec(PhantomShape::WindingLine);
    spec.windingAmplitudeFraction = amplitude;
    spec.windingPeriods = periods;
    PhantomGenerator g(spec);
    ASSERT_TRUE(g.ok()) << g.error();
    const double n = spec.referenceLength_mm();
    const double crestRadius = 0.64 * n / (amplitude * std::pow(2 * kPi * periods, 2));
    double largestCurvature = 0.0;
    for (const auto& q : g.centerline().paths.at(0).points)
    {
      largestCurvature = std::max(largestCurvature, q.curvature_per_mm);
    }
    EXPECT_NEAR(1.0 / largestCurvature, crestRadius, 0.01 * crestRadius);
  }
  PhantomSpec bad = smallSpec(PhantomShape::WindingLine);
  bad.windingAmplitudeFraction = 0.0;
  EXPECT_NE(bad.validate().find("winding line"), std::string::npos);
  bad.windingAmplitudeFraction = 0.1;
  bad.windingPeriods = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(bad.validate().find("winding line"), std::string::npos);
}

TEST(PhantomGenerator, CenterlineVoxelIsBrightAndThreeRadiiAwayIsBackground)
{
  for (PhantomShape shape : { PhantomShape::Helix,
         PhantomShape::Circle,
         PhantomShape::Tree,
         PhantomShape::YBifurcation,
         PhantomShape::WindingLine,
         PhantomShape::LoopNetwork,
         PhantomShape::StraightTube })
  {
    PhantomSpec spec = smallSpec(shape);
    spec.radiusFraction = 0.06;
    PhantomGenerator g(spec);
    ASSERT_TRUE(g.ok()) << vtouch::toString(shape) << ": " << g.error();
    const std::vector<float> v = render(g);
    const double contrast = spec.peakIntensity - spec.backgroundIntensity;
    int checked = 0;
    for (const auto& path : g.centerline().paths)
    {
      for (std::size_t i = path.points.size() / 4; i < path.points.size();
           i += path.points.size() / 3)
      {
        const auto& p = path.points[i];
        EXPECT_GT(
          sampleNearest(g, v, p.position_World_mm), spec.backgroundIntensity + 0.6 * contrast)
          << vtouch::toString(shape);
        // A point 3 radii away along the normal, if it is 3 radii from every vessel.
        Vec3 normal = p.tangent_World.cross(Vec3{ 0, 0, 1 });
        if (normal.norm() < 0.1)
        {
          normal = p.tangent_World.cross(Vec3{ 1, 0, 0 });
        }
        const Vec3 away = p.position_World_mm + normal * (4.5 * p.radius_mm / normal.norm());
        double r = 0.0;
        if (g.distanceToCenterline_mm(away, &r) > 3.5 * std::max(r, p.radius_mm) + 0.5)
        {
          EXPECT_LT(sampleNearest(g, v, away), spec.backgroundIntensity + 0.01 * contrast)
            << vtouch::toString(shape);
          ++checked;
        }
      }
    }
    EXPECT_GT(checked, 0) << vtouch::toString(shape);
  }
}

TEST(PhantomGenerator, RasterMatchesAnalyticProfileEverywhere)
{
  // Every voxel against the brute-force analytic intensity: the fast rasterizer may not miss or
  // misplace any part of a vessel (bends, junctions, loop closure).
  for (PhantomShape shape : { PhantomShape::Tree, PhantomShape::LoopNetwork, PhantomShape::Circle })
  {
    PhantomSpec spec = smallSpec(shape);
    spec.dimensions = { 40, 40, 40 };
    spec.radiusFraction = 0.07;
    PhantomGenerator g(spec);
    ASSERT_TRUE(g.ok());
    const std::vector<float> v = render(g);
    double worst = 0.0;
    for (int k = 0; k < 40; k += 3)
      for (int j = 0; j < 40; j += 2)
        for (int i = 0; i < 40; i += 2)
        {
          const double expected = g.intensityAt({ double(i), double(j), double(k) });
          const double got = v[(static_cast<std::size_t>(k) * 40 + j) * 40 + i];
          worst = std::max(worst, std::abs(expected - got));
        }
    // 2 % of the contrast covers the chord approximation and the cutoff at 3.5 radii.
    EXPECT_LT(worst, 0.02 * (spec.peakIntensity - spec.backgroundIntensity))
      << vtouch::toString(shape);
  }
}

TEST(PhantomGenerator, TopologyOfEachShape)
{
  struct Expect
  {
    PhantomShape shape;
    std::size_t paths;
    std::size_t junctions;
  };
  for (const Expect& e : { Expect{ PhantomShape::Helix, 1, 0 },
         Expect{ PhantomShape::Circle, 1, 1 },
         Expect{ PhantomShape::YBifurcation, 3, 2 },
         Expect{ PhantomShape::Tree, 7, 6 },
         Expect{ PhantomShape::LoopNetwork, 5, 5 },
         Expect{ PhantomShape::Column, 1, 0 } })
  {
    PhantomGenerator g(smallSpec(e.shape));
    ASSERT_TRUE(g.ok());
    EXPECT_EQ(g.centerline().paths.size(), e.paths) << vtouch::toString(e.shape);
    EXPECT_EQ(g.centerline().junctions.size(), e.junctions) << vtouch::toString(e.shape);
    EXPECT_EQ(g.centerline().validate(), "") << vtouch::toString(e.shape);
  }
}

TEST(PhantomGenerator, TreeRadiiFollowGenerations)
{
  PhantomSpec spec = smallSpec(PhantomShape::Tree);
  spec.treeRadiusFractions = { 0.055, 0.045, 0.035 };
  PhantomGenerator g(spec);
  ASSERT_TRUE(g.ok());
  const double n = spec.referenceLength_mm();
  const auto& paths = g.centerline().paths;
  EXPECT_NEAR(paths[0].points[0].radius_mm, 0.055 * n, 1e-9);
  EXPECT_NEAR(paths[1].points[0].radius_mm, 0.045 * n, 1e-9);
  EXPECT_NEAR(paths[2].points[0].radius_mm, 0.035 * n, 1e-9);
}

TEST(PhantomGenerator, SameSeedSameVolumeOtherSeedOtherNoise)
{
  PhantomSpec spec = smallSpec(PhantomShape::Helix);
  spec.dimensions = { 32, 32, 32 };
  spec.noiseStdDev = 20.0;
  const std::vector<float> a = render(PhantomGenerator(spec));
  const std::vector<float> b = render(PhantomGenerator(spec));
  EXPECT_EQ(a, b);
  spec.seed = 2;
  const std::vector<float> c = render(PhantomGenerator(spec));
  EXPECT_NE(a, c);
  // The noise has the requested standard deviation (background voxels far from the helix).
  double sum = 0.0, sum2 = 0.0;
  int count = 0;
  for (std::size_t n = 0; n < 32 * 32; ++n) // slice k = 0 corner region
  {
    const int i = n % 32, j = static_cast<int>(n / 32);
    if (i < 6 && j < 6)
    {
      const double x = a[n] - spec.backgroundIntensity;
      sum += x;
      sum2 += x * x;
      ++count;
    }
  }
  const double mean = sum / count;
  EXPECT_NEAR(std::sqrt(sum2 / count - mean * mean), 20.0, 5.0);
}

TEST(PhantomGenerator, UnsignedShortMatchesFloat)
{
  PhantomSpec spec = smallSpec(PhantomShape::YBifurcation);
  spec.dimensions = { 32, 32, 32 };
  PhantomGenerator g(spec);
  const std::vector<float> f = render(g);
  std::vector<std::uint16_t> u(f.size());
  ASSERT_TRUE(g.fill(u.data()));
  for (std::size_t n = 0; n < f.size(); n += 7)
  {
    EXPECT_NEAR(u[n], f[n], 0.5);
  }
}

TEST(PhantomGenerator, AnisotropicSpacingKeepsVesselsInMillimetres)
{
  PhantomSpec spec = smallSpec(PhantomShape::Helix);
  spec.dimensions = { 64, 64, 32 };
  spec.spacing_mm = { 0.5, 0.5, 1.0 };
  PhantomGenerator g(spec);
  ASSERT_TRUE(g.ok());
  const std::vector<float> v = render(g);
  const auto& pts = g.centerline().paths[0].points;
  for (std::size_t i = 20; i < pts.size() - 20; i += 50)
  {
    EXPECT_GT(sampleNearest(g, v, pts[i].position_World_mm), 600.0);
  }
}

TEST(PhantomGenerator, ColumnIsFourByFourVoxels)
{
  PhantomSpec spec = smallSpec(PhantomShape::Column);
  spec.dimensions = { 20, 20, 100 };
  PhantomGenerator g(spec);
  ASSERT_TRUE(g.ok());
  const std::vector<float> v = render(g);
  for (int k : { 0, 50, 99 })
  {
    int bright = 0;
    for (int n = 0; n < 400; ++n)
    {
      bright += v[static_cast<std::size_t>(k) * 400 + n] > 500.0f;
    }
    EXPECT_EQ(bright, 16);
  }
}

TEST(PhantomGenerator, AbortFromProgressStopsFilling)
{
  PhantomGenerator g(smallSpec(PhantomShape::Helix));
  std::vector<float> v(64 * 64 * 64, -1.0f);
  int calls = 0;
  EXPECT_FALSE(g.fill(v.data(), [&](double) { return ++calls > 1; }));
  EXPECT_EQ(calls, 1);
  EXPECT_EQ(v[0], -1.0f); // aborted before any worker started
}

TEST(PhantomGenerator, ProgressRunsFromZeroToOne)
{
  PhantomGenerator g(smallSpec(PhantomShape::Tree));
  std::vector<float> v(64 * 64 * 64);
  std::vector<double> seen;
  EXPECT_TRUE(g.fill(v.data(),
    [&](double f)
    {
      seen.push_back(f);
      return true;
    }));
  ASSERT_GE(seen.size(), 2u);
  EXPECT_EQ(seen.front(), 0.0);
  EXPECT_EQ(seen.back(), 1.0);
  EXPECT_TRUE(std::is_sorted(seen.begin(), seen.end()));
}

// The RawAngiogram phantom: its random tree (VascularTreeGenerator), clutter (PhantomClutter),
// partial-volume rasterizer and noise (AngiogramRasterizer through PhantomGenerator).
#include "vtouchAngiogramRasterizer.h"
#include "vtouchPhantomClutter.h"
#include "vtouchPhantomGenerator.h"
#include "vtouchVascularTreeGenerator.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <vector>

using vtouch::AngiogramRasterizer;
using vtouch::PhantomClutter;
using vtouch::PhantomGenerator;
using vtouch::PhantomShape;
using vtouch::PhantomSpec;
using vtouch::QSkeleton;
using vtouch::Vec3;

namespace
{
constexpr double kPi = 3.14159265358979323846;

PhantomSpec angiogramSpec(int n, std::uint32_t seed)
{
  PhantomSpec spec;
  spec.shape = PhantomShape::RawAngiogram;
  spec.dimensions = { n, n, n };
  spec.seed = seed;
  spec.noiseStdDev = 0.0;
  return spec;
}

QSkeleton tree(const PhantomSpec& spec)
{
  return vtouch::VascularTreeGenerator(spec, 0.25).build();
}

std::vector<float> render(const PhantomGenerator& g)
{
  const auto& d = g.spec().dimensions;
  std::vector<float> v(static_cast<std::size_t>(d[0]) * d[1] * d[2]);
  EXPECT_TRUE(g.fill(v.data()));
  return v;
}

/// Children of each path (paths whose head joins the path's last point).
std::map<int, std::vector<int>> children(const QSkeleton& s)
{
  std::map<int, std::vector<int>> c;
  for (const vtouch::Junction& j : s.junctions)
  {
    c[j.parentPath].push_back(j.childPath);
  }
  return c;
}

double pathLength(const vtouch::SkeletonPath& p)
{
  double length = 0.0;
  for (std::size_t i = 0; i + 1 < p.points.size(); ++i)
  {
    length += (p.points[i + 1].position_World_mm - p.points[i].position_World_mm).norm();
  }
  return length;
}
} // namespace

TEST(VascularTreeGenerator, SameSeedGivesSameTreeAndAnotherSeedAnother)
{
  const QSkeleton a = tree(angiogramSpec(128, 5));
  const QSkeleton b = tree(angiogramSpec(128, 5));
  const QSkeleton c = tree(angiogramSpec(128, 6));
  ASSERT_EQ(a.paths.size(), b.paths.size());
  for (std::size_t i = 0; i < a.paths.size(); ++i)
  {
    ASSERT_EQ(a.paths[i].points.size(), b.paths[i].points.size());
    EXPECT_EQ(
      a.paths[i].points.back().position_World_mm.x, b.paths[i].points.back().position_World_mm.x);
  }
  const Vec3 endA = a.paths.back().points.back().position_World_mm;
  const Vec3 endC = c.paths.back().points.back().position_World_mm;
  EXPECT_GT((endA - endC).norm(), 1.0);
  EXPECT_TRUE(a.validate().empty()) << a.validate();
}

TEST(VascularTreeGenerator, MurrayLawHoldsAtEveryBifurcation)
{
  for (std::uint32_t seed : { 1u, 2u, 3u })
  {
    const QSkeleton s = tree(angiogramSpec(192, seed));
    int bifurcations = 0;
    for (const auto& [parent, kids] : children(s))
    {
      ASSERT_EQ(kids.size(), 2u) << "a bifurcation has two children";
      const double r0 = s.paths[parent].points.back().radius_mm;
      const double r1 = s.paths[kids[0]].points.front().radius_mm;
      const double r2 = s.paths[kids[1]].points.front().radius_mm;
      EXPECT_NEAR(r1 * r1 * r1 + r2 * r2 * r2, r0 * r0 * r0, 1e-9 * r0 * r0 * r0);
      // The children start where the parent ends.
      EXPECT_LT((s.paths[kids[0]].points.front().position_World_mm -
                  s.paths[parent].points.back().position_World_mm)
                  .norm(),
        1e-9);
      ++bifurcations;
    }
    EXPECT_EQ(bifurcations, static_cast<int>(s.paths.size() - 1) / 2);
  }
}

TEST(VascularTreeGenerator, RadiiRunFromLargestDownToSmallestAndCountMeetsTarget)
{
  PhantomSpec spec = angiogramSpec(192, 4);
  spec.angiogramSegments = 250;
  const QSkeleton s = tree(spec);
  EXPECT_GE(s.paths.size(), 200u);
  EXPECT_LE(s.paths.size(), 250u);
  double rMin = 1e9;
  double rMax = 0.0;
  std::map<int, double> lengthPerClass; // the benchmark's radius classes
  const double edges[] = { 0.5, 0.6, 0.75, 1.0, 2.0 };
  for (const auto& p : s.paths)
  {
    for (const auto& q : p.points)
    {
      rMin = std::min(rMin, q.radius_mm);
      rMax = std::max(rMax, q.radius_mm);
    }
    const double r = p.points.front().radius_mm;
    const int cls = static_cast<int>(
                      std::upper_bound(std::begin(edges), std::end(edges), r) - std::begin(edges)) -
                    1;
    lengthPerClass[cls] += pathLength(p);
  }
  EXPECT_DOUBLE_EQ(s.paths.front().points.front().radius_mm, 4.0) << "the root is the largest";
  EXPECT_GE(rMin, 0.5 - 1e-12);
  EXPECT_LT(rMin, 0.6) << "some vessels are in the thinnest class";
  EXPECT_LE(rMax, 4.0 + 1e-12);
  for (int cls = 0; cls < 5; ++cls)
  {
    EXPECT_GT(lengthPerClass[cls], 100.0) << "radius class " << cls << " holds vessels";
  }
}

TEST(VascularTreeGenerator, SegmentsRunInAllOrientationsCurveAndStayInsideAndApart)
{
  const PhantomSpec spec = angiogramSpec(160, 7);
  const QSkeleton s = tree(spec);
  double along[3] = { 0, 0, 0 };
  double maxCurvature = 0.0;
  for (const auto& p : s.paths)
  {
    for (const auto& q : p.points)
    {
      const Vec3& t = q.tangent_World;
      const double m[3] = { std::abs(t.x), std::abs(t.y), std::abs(t.z) };
      along[std::max_element(m, m + 3) - m] += 1.0;
      maxCurvature = std::max(maxCurvature, q.curvature_per_mm);
      for (int a = 0; a < 3; ++a)
      {
        const double x = (&q.position_World_mm.x)[a];
        EXPECT_GE(x - q.radius_mm, 0.0);
        EXPECT_LE(x + q.radius_mm, spec.dimensions[a] - 1.0);
      }
    }
  }
  const double total = along[0] + along[1] + along[2];
  for (double f : along)
  {
    EXPECT_GT(f / total, 0.15) << "every axis dominates some of the vessels";
  }
  EXPECT_GT(maxCurvature, 0.02) << "segments are curved";
  EXPECT_LT(maxCurvature, 1.0);

  // Vessels that are not parent, child or sibling of each other never touch (walls two voxels
  // apart less the sampling error).
  const auto kids = children(s);
  std::vector<int> parentOf(s.paths.size(), -1);
  for (const auto& [parent, c] : kids)
  {
    for (int k : c)
    {
      parentOf[k] = parent;
    }
  }
  for (std::size_t i = 0; i < s.paths.size(); ++i)
    for (std::size_t j = i + 1; j < s.paths.size(); ++j)
    {
      const int pi = parentOf[i];
      const int pj = parentOf[j];
      if (pi == static_cast<int>(j) || pj == static_cast<int>(i) || (pi >= 0 && pi == pj) ||
          (pi >= 0 && parentOf[pi] == static_cast<int>(j)) ||
          (pj >= 0 && parentOf[pj] == static_cast<int>(i)) || (pi >= 0 && pj == parentOf[pi]) ||
          (pj >= 0 && pi == parentOf[pj]))
      {
        continue; // family: they meet at a bifurcation
      }
      for (std::size_t a = 0; a < s.paths[i].points.size(); a += 4)
        for (std::size_t b = 0; b < s.paths[j].points.size(); b += 4)
        {
          const auto& p = s.paths[i].points[a];
          const auto& q = s.paths[j].points[b];
          ASSERT_GT(
            (p.position_World_mm - q.position_World_mm).norm(), p.radius_mm + q.radius_mm + 1.0)
            << "paths " << i << " and " << j;
        }
    }
}

TEST(PhantomClutter, TouchesVesselsButIsNotInTheTree)
{
  for (std::uint32_t seed : { 1u, 2u, 3u })
  {
    PhantomSpec spec = angiogramSpec(160, seed);
    spec.clutterCount = 10;
    const PhantomGenerator g(spec);
    ASSERT_TRUE(g.ok()) << g.error();
    const QSkeleton& s = g.centerline();
    const PhantomClutter clutter(spec, s);
    EXPECT_GE(clutter.objects().size(), 8u);
    int plates = 0;
    for (const PhantomClutter::Object& o : clutter.objects())
    {
      plates += o.plate ? 1 : 0;
      // It touches its vessel: the wall lies inside it by half a voxel at the contact.
      const double radius = s.paths[o.touchedPath].points.front().radius_mm;
      EXPECT_NEAR(o.signedDistanceBound_mm(o.contact_World_mm), radius - 0.5, 1e-9);
      const Vec3 wall = o.contact_World_mm - o.axes[0] * (radius - 0.25);
      EXPECT_TRUE(o.contains(wall));
      // No vessel axis is inside it: the tree (port 1) does not run through the clutter.
      for (const auto& p : s.paths)
        for (const auto& q : p.points)
        {
          ASSERT_FALSE(o.contains(q.position_World_mm)) << "path " << p.id;
        }
    }
    EXPECT_GT(plates, 0);
    EXPECT_LT(plates, static_cast<int>(clutter.objects().size()));

    // The clutter is at vessel intensity in the volume; the tree in port 1 is the same with and
    // without clutter.
    const std::vector<float> v = render(g);
    PhantomSpec bare = spec;
    bare.clutterCount = 0;
    const PhantomGenerator without(bare);
    EXPECT_EQ(without.centerline().pointCount(), s.pointCount());
    for (const PhantomClutter::Object& o : clutter.objects())
    {
      const Vec3 c = o.centre_World_mm;
      const int i = static_cast<int>(std::lround(c.x));
      const int j = static_cast<int>(std::lround(c.y));
      const int k = static_cast<int>(std::lround(c.z));
      if (i < 0 || j < 0 || k < 0 || i >= 160 || j >= 160 || k >= 160)
      {
        continue;
      }
      EXPECT_GT(v[(static_cast<std::size_t>(k) * 160 + j) * 160 + i], 0.85 * spec.peakIntensity);
    }
  }
}

TEST(AngiogramRasterizer, PartialVolumeIsAFractionInUnitIntervalThatAddsUpToTheVessels)
{
  PhantomSpec spec = angiogramSpec(96, 3);
  spec.clutterCount = 0;
  spec.angiogramSegments = 60;
  const PhantomGenerator g(spec);
  ASSERT_TRUE(g.ok());
  const AngiogramRasterizer rasterizer(spec, g.centerline());
  std::vector<float> f(96u * 96u * 96u, -1.0f);
  rasterizer.fractions(f.data(), 0, 96);
  double sum = 0.0;
  int partial = 0;
  for (float x : f)
  {
    ASSERT_GE(x, 0.0f);
    ASSERT_LE(x, 1.0f);
    sum += x;
    partial += x > 0.0f && x < 1.0f ? 1 : 0;
  }
  EXPECT_GT(partial, 1000);
  // The vessels' volume: sum of pi r^2 L less the overlaps at the bifurcations (at most the
  // parent's end ball per bifurcation, counted from the sum's side).
  double tubes = 0.0;
  double overlapBound = 0.0;
  for (const auto& p : g.centerline().paths)
  {
    const double r = p.points.front().radius_mm;
    tubes += kPi * r * r * pathLength(p);
    if (p.head.junction >= 0)
    {
      const double rp = g.centerline()
                          .paths[g.centerline().junctions[p.head.junction].parentPath]
                          .points.back()
                          .radius_mm;
      overlapBound += kPi * r * r * rp;
    }
  }
  EXPECT_LE(sum, tubes * 1.01 + 0.67 * kPi * 64); // + the end caps at most
  EXPECT_GE(sum, (tubes - overlapBound) * 0.99);
  // Inside a thick vessel the fraction is 1; two voxels beyond any wall it is 0.
  const auto& root = g.centerline().paths.front().points;
  const Vec3 mid = root[root.size() / 2].position_World_mm;
  const auto at = [&](int i, int j, int k) { return f[(k * 96u + j) * 96u + i]; };
  EXPECT_EQ(at(static_cast<int>(std::lround(mid.x)),
              static_cast<int>(std::lround(mid.y)),
              static_cast<int>(std::lround(mid.z))),
    1.0f);
  int checked = 0;
  for (int k = 0; k < 96; k += 5)
    for (int j = 0; j < 96; j += 5)
      for (int i = 0; i < 96; i += 5)
      {
        double radius = 0.0;
        const double d = g.distanceToCenterline_mm({ double(i), double(j), double(k) }, &radius);
        if (d > radius + 2.0 + 4.0) // 4: the largest radius of another vessel nearby
        {
          EXPECT_EQ(at(i, j, k), 0.0f);
          ++checked;
        }
      }
  EXPECT_GT(checked, 1000);
}

TEST(PhantomGenerator, RawAngiogramSameSeedSameVolume)
{
  PhantomSpec spec = angiogramSpec(64, 9);
  spec.angiogramLargestRadius_vox = 3.0;
  spec.noiseStdDev = 20.0;
  const std::vector<float> a = render(PhantomGenerator(spec));
  const std::vector<float> b = render(PhantomGenerator(spec));
  spec.seed = 10;
  const std::vector<float> c = render(PhantomGenerator(spec));
  EXPECT_EQ(a, b);
  EXPECT_NE(a, c);
}

TEST(PhantomGenerator, RawAngiogramGaussianNoiseHasTheRequestedStatistics)
{
  PhantomSpec spec = angiogramSpec(64, 2);
  spec.angiogramLargestRadius_vox = 3.0;
  const std::vector<float> clean = render(PhantomGenerator(spec));
  spec.noiseStdDev = 25.0;
  const std::vector<float> noisy = render(PhantomGenerator(spec));
  double sum = 0.0;
  double sum2 = 0.0;
  for (std::size_t n = 0; n < clean.size(); ++n)
  {
    const double e = static_cast<double>(noisy[n]) - clean[n];
    sum += e;
    sum2 += e * e;
  }
  const double count = static_cast<double>(clean.size());
  const double mean = sum / count;
  const double sd = std::sqrt(sum2 / count - mean * mean);
  EXPECT_LT(std::abs(mean), 4.0 * 25.0 / std::sqrt(count));
  EXPECT_NEAR(sd, 25.0, 0.01 * 25.0);
}

TEST(PhantomGenerator, RawAngiogramRicianNoiseIsRayleighWhereThereIsNoSignal)
{
  PhantomSpec spec = angiogramSpec(64, 2);
  spec.angiogramLargestRadius_vox = 3.0;
  spec.tissueIntensity = 0.0; // MR background: no signal outside the vessels
  spec.clutterCount = 0;
  spec.noiseModel = PhantomSpec::NoiseModel::Rician;
  spec.noiseStdDev = 20.0;
  const PhantomGenerator g(spec);
  const std::vector<float> v = render(g);
  const AngiogramRasterizer rasterizer(spec, g.centerline());
  std::vector<float> f(v.size());
  rasterizer.fractions(f.data(), 0, 64);
  double sum = 0.0;
  double sum2 = 0.0;
  double count = 0.0;
  for (std::size_t n = 0; n < v.size(); ++n)
  {
    if (f[n] == 0.0f)
    {
      ASSERT_GE(v[n], 0.0f) << "a magnitude is never negative";
      sum += v[n];
      sum2 += static_cast<double>(v[n]) * v[n];
      count += 1.0;
    }
  }
  ASSERT_GT(count, 100000.0);
  const double mean = sum / count;
  const double sd = std::sqrt(sum2 / count - mean * mean);
  EXPECT_NEAR(mean, 20.0 * std::sqrt(kPi / 2.0), 0.01 * 20.0 * std::sqrt(kPi / 2.0));
  EXPECT_NEAR(sd, 20.0 * std::sqrt((4.0 - kPi) / 2.0), 0.02 * 20.0 * std::sqrt((4.0 - kPi) / 2.0));
}

TEST(PhantomGenerator, RawAngiogramBiasFieldScalesTheTissueSmoothly)
{
  PhantomSpec spec = angiogramSpec(64, 4);
  spec.angiogramLargestRadius_vox = 3.0;
  spec.clutterCount = 0;
  spec.biasAmplitude = 0.0;
  const std::vector<float> flat = render(PhantomGenerator(spec));
  spec.biasAmplitude = 0.3;
  const std::vector<float> biased = render(PhantomGenerator(spec));
  double lo = 1e9;
  double hi = 0.0;
  double maxStep = 0.0;
  for (std::size_t n = 0; n + 1 < flat.size(); ++n)
  {
    const double ratio = biased[n] / flat[n];
    lo = std::min(lo, ratio);
    hi = std::max(hi, ratio);
    if ((n + 1) % 64 != 0)
    {
      maxStep = std::max(maxStep, std::abs(biased[n + 1] / flat[n + 1] - ratio));
    }
  }
  EXPECT_GE(lo, 0.7 - 1e-4);
  EXPECT_LE(hi, 1.3 + 1e-4);
  EXPECT_GT(hi - lo, 0.1) << "the bias varies across the volume";
  EXPECT_LT(maxStep, 0.02) << "and smoothly";
}

TEST(PhantomSpec, RawAngiogramRejectsBadParametersWithAMessage)
{
  const auto error = [](auto change)
  {
    PhantomSpec spec = angiogramSpec(64, 1);
    change(spec);
    return spec.validate();
  };
  EXPECT_TRUE(error([](PhantomSpec&) {}).empty());
  EXPECT_NE(
    error([](PhantomSpec& s) { s.angiogramSegments = 0; }).find("segment"), std::string::npos);
  EXPECT_NE(error([](PhantomSpec& s) { s.angiogramSmallestRadius_vox = 5.0; }).find("radii"),
    std::string::npos);
  EXPECT_NE(error([](PhantomSpec& s) { s.noiseModel = static_cast<PhantomSpec::NoiseModel>(7); })
              .find("noise model"),
    std::string::npos);
  EXPECT_NE(error([](PhantomSpec& s) { s.biasAmplitude = 1.5; }).find("bias"), std::string::npos);
  EXPECT_NE(error([](PhantomSpec& s) { s.clutterCount = -1; }).find("clutter"), std::string::npos);
  EXPECT_NE(error(
              [](PhantomSpec& s) {
                s.dimensions = { 20, 64, 64 };
              })
              .find("needs at least"),
    std::string::npos);
  EXPECT_NE(
    error([](PhantomSpec& s) { s.tissueIntensity = NAN; }).find("tissue"), std::string::npos);
}

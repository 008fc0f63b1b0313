// Junction re-centring on hand-made raw skeletons: a branch leaving a curved vessel, where the
// traces bulge toward the branch near the junction, and a bifurcation, which is left alone.
#include "vtouchJunctionRecentring.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace vtouch
{
namespace
{
using P3 = std::array<double, 3>;
constexpr double kPi = 3.14159265358979323846;

double dist(const P3& a, const P3& b)
{
  return std::sqrt(
    (a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

void addPoint(RawSkeletonPath& path, const P3& c, double radius)
{
  path.voxels.push_back(
    { std::llround(c[0]), std::llround(c[1]), std::llround(c[2]) }); // left alone by the stage
  path.center_mm.push_back(c);
  path.radius_mm.push_back(radius);
}

/// Distance from p to the segment a-b.
double segmentDistance(const P3& p, const P3& a, const P3& b)
{
  const P3 ab{ b[0] - a[0], b[1] - a[1], b[2] - a[2] };
  const P3 ap{ p[0] - a[0], p[1] - a[1], p[2] - a[2] };
  const double len2 = ab[0] * ab[0] + ab[1] * ab[1] + ab[2] * ab[2];
  const double t = std::clamp((ap[0] * ab[0] + ap[1] * ab[1] + ap[2] * ab[2]) / len2, 0.0, 1.0);
  return dist(p, { a[0] + t * ab[0], a[1] + t * ab[1], a[2] + t * ab[2] });
}

constexpr double kRing = 20.0;  // radius of curvature of the through vessel, mm
constexpr double kRadius = 4.0; // its lumen radius
constexpr double kBulge = 1.5;  // how far the traces near the junction lean toward the branch
constexpr double kBranch = 3.2; // the branch's lumen radius

/// A vessel along an arc of radius kRing in the x-y plane (angles -1.2..1.2 rad, 0.05 rad apart,
/// the junction at angle 0, the point (kRing, 0, 0)), and a branch leaving it radially (+x) to
/// x = kRing + 24. Points within one lumen radius of the junction lean toward the branch (the
/// arc's) or toward the arc's head (the branch's), as back-traces through a merged lumen do.
RawSkeleton branchOffACurvedVessel()
{
  RawSkeleton s;
  s.paths.resize(2);
  const P3 junction{ kRing, 0.0, 0.0 };
  for (int i = -24; i <= 24; ++i)
  {
    const double a = 0.05 * i;
    P3 c{ kRing * std::cos(a), kRing * std::sin(a), 0.0 };
    const double lean = std::max(0.0, 1.0 - dist(c, junction) / kRadius);
    c[0] += kBulge * lean;
    addPoint(s.paths[0], c, kRadius);
  }
  const P3 start = s.paths[0].center_mm[24];
  addPoint(s.paths[1], start, kRadius);
  for (int k = 1; k <= 24; ++k)
  {
    P3 c{ kRing + k, 0.0, 0.0 };
    const double lean = std::max(0.0, 1.0 - k / kRadius);
    c[1] -= kBulge * lean;
    addPoint(s.paths[1], c, kBranch);
  }
  s.junctions.push_back({ 1, false, 0, 24 });
  s.paths[1].headJunction = 0;
  return s;
}

TEST(JunctionRecentring, BranchOffACurvedVesselMovesTheJunctionOntoBothAxes)
{
  RawSkeleton s = branchOffACurvedVessel();
  const RawSkeleton before = s;
  const std::vector<bool> moved = recentreJunctions(s, 0, 1.0);
  ASSERT_EQ(moved.size(), 1U);
  EXPECT_TRUE(moved[0]);
  const P3 junction{ kRing, 0.0, 0.0 };
  // The junction point of both paths, on the arc and on the branch axis.
  EXPECT_LT(dist(s.paths[0].center_mm[24], junction), 0.15);
  EXPECT_EQ(s.paths[1].center_mm[0], s.paths[0].center_mm[24]);
  EXPECT_GT(dist(before.paths[0].center_mm[24], junction), 1.0);
  // The arc stays round through the junction: every point within 0.1 mm of the circle.
  for (const P3& c : s.paths[0].center_mm)
  {
    EXPECT_NEAR(std::hypot(c[0], c[1]), kRing, 0.1);
    EXPECT_NEAR(c[2], 0.0, 1e-9);
  }
  // The branch runs along its axis from the junction.
  for (const P3& c : s.paths[1].center_mm)
  {
    EXPECT_LT(segmentDistance(c, junction, { kRing + 24.0, 0.0, 0.0 }), 0.15);
  }
  // Only centres move: voxels, radii and links stay.
  for (std::size_t p = 0; p < s.paths.size(); ++p)
  {
    EXPECT_EQ(s.paths[p].voxels, before.paths[p].voxels);
    EXPECT_EQ(s.paths[p].radius_mm, before.paths[p].radius_mm);
  }
  EXPECT_EQ(s.junctions[0].parentPoint, 24);
}

TEST(JunctionRecentring, BifurcationIntoThinnerChildrenIsLeftToTheTracer)
{
  // A trunk along +y into (0, 0, 0) and two children at +-40 deg, each 0.8 of its calibre: no
  // vessel runs through a bifurcation.
  RawSkeleton s;
  s.paths.resize(2);
  for (int k = -20; k <= 20; ++k)
  {
    const double t = std::abs(k);
    addPoint(s.paths[0],
      k <= 0 ? P3{ 0.0, static_cast<double>(k), 0.0 }
             : P3{ -t * std::sin(40.0 * kPi / 180.0), t * std::cos(40.0 * kPi / 180.0), 0.0 },
      k <= 0 ? 4.0 : 3.2);
  }
  addPoint(s.paths[1], s.paths[0].center_mm[20], 4.0);
  for (int k = 1; k <= 20; ++k)
  {
    addPoint(
      s.paths[1], { k * std::sin(40.0 * kPi / 180.0), k * std::cos(40.0 * kPi / 180.0), 0.0 }, 3.2);
  }
  s.junctions.push_back({ 1, false, 0, 20 });
  const RawSkeleton before = s;
  const std::vector<bool> moved = recentreJunctions(s, 0, 1.0);
  ASSERT_EQ(moved.size(), 1U);
  EXPECT_FALSE(moved[0]);
  EXPECT_EQ(s.paths[0].center_mm, before.paths[0].center_mm);
  EXPECT_EQ(s.paths[1].center_mm, before.paths[1].center_mm);
}

TEST(JunctionRecentring, JunctionsTooCloseToEachOtherOrShortArmsAreLeftAlone)
{
  // A second branch two points from the first: neither junction's arms are their own axes.
  RawSkeleton s = branchOffACurvedVessel();
  RawSkeletonPath second;
  addPoint(second, s.paths[0].center_mm[26], kRadius);
  for (int k = 1; k <= 20; ++k)
  {
    const P3& c = s.paths[0].center_mm[26];
    addPoint(second, { c[0] + k, c[1], c[2] + 0.5 * k }, kBranch);
  }
  s.paths.push_back(second);
  s.junctions.push_back({ 2, false, 0, 26 });
  const RawSkeleton before = s;
  std::vector<bool> moved = recentreJunctions(s, 0, 1.0);
  EXPECT_FALSE(moved[0]);
  EXPECT_FALSE(moved[1]);
  EXPECT_EQ(s.paths[0].center_mm, before.paths[0].center_mm);

  // A branch shorter than the zone plus half the reach.
  RawSkeleton shortArm = branchOffACurvedVessel();
  shortArm.paths[1].voxels.resize(6);
  shortArm.paths[1].center_mm.resize(6);
  shortArm.paths[1].radius_mm.resize(6);
  moved = recentreJunctions(shortArm, 0, 1.0);
  EXPECT_FALSE(moved[0]);

  // Paths before `firstPath` belong to another component: untouched.
  RawSkeleton other = branchOffACurvedVessel();
  moved = recentreJunctions(other, 1, 1.0);
  EXPECT_FALSE(moved[0]);
}

} // namespace
} // namespace vtouch

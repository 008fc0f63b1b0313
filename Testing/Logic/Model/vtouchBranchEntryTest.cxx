// A branch's entry into its parent on the branch's own axis (placeBranchEntries, issue 16: the
// raw CTA's iliac bifurcation). Networks in 1 mm voxels: a straight parent along y (radius 6 mm,
// the aorta's scale) and a branch leaving it at an angle whose coded stretch inside the parent's
// tube crosses the lumen sideways to the parent's point, as the voxel coder's merged band does.
#include "vtouchBranchEntry.h"
#include "vtouchStitchTestHelpers.h"

#include <gtest/gtest.h>

#include <cmath>

namespace
{
using namespace vtouch;
using namespace vtouch_test;

constexpr double kPi = 3.14159265358979323846;
constexpr double kParentRadius_mm = 6.0;
constexpr double kBranchRadius_mm = 4.0;

/// The parent: 61 centres along y from y = 0, 1 mm apart, at x = z = 0.
SkeletonPath parentAlongY()
{
  std::vector<SkeletonPoint> points;
  for (int i = 0; i <= 60; ++i)
  {
    points.push_back(point(0.0, i, 0.0, kParentRadius_mm));
  }
  return path(0, points);
}

/// Where the branch's true axis meets the parent's: (0, kMeet_mm, 0).
constexpr double kMeet_mm = 30.0;

/// The branch's true axis at arc length `s_mm` from the parent's axis, leaving it at `angle_deg`
/// from the parent's direction -y (toward y = 0).
Vec3 onBranchAxis(double s_mm, double angle_deg)
{
  const double a = angle_deg * kPi / 180.0;
  return { s_mm * std::sin(a), kMeet_mm - s_mm * std::cos(a), 0.0 };
}

/// The branch as the coder codes it, head attached: from the parent's point `codedParentPoint`
/// straight sideways to the true axis where it leaves the parent's tube (a corner across the
/// lumen), then along the true axis, 1 mm apart, out to 40 mm.
QSkeleton codedBranch(double angle_deg, int codedParentPoint)
{
  QSkeleton s;
  s.paths.push_back(parentAlongY());
  std::vector<SkeletonPoint> branch;
  const Vec3 parentPoint{ 0.0, static_cast<double>(codedParentPoint), 0.0 };
  // The first axis point out of the parent's tube (x >= radius).
  double sOut = 0.0;
  while (onBranchAxis(sOut, angle_deg).x < kParentRadius_mm + 0.5)
  {
    sOut += 1.0;
  }
  const Vec3 out = onBranchAxis(sOut, angle_deg);
  const int across = static_cast<int>(std::ceil((out - parentPoint).norm()));
  for (int k = 0; k < across; ++k)
  {
    const Vec3 p = parentPoint + (out - parentPoint) * (static_cast<double>(k) / across);
    if (p.x < kParentRadius_mm - 0.5) // the merged band's centres, inside the parent's tube
    {
      branch.push_back(point(p.x, p.y, p.z, kParentRadius_mm));
    }
  }
  for (double t = sOut; t <= 40.0; t += 1.0)
  {
    const Vec3 p = onBranchAxis(t, angle_deg);
    branch.push_back(point(p.x, p.y, p.z, kBranchRadius_mm));
  }
  s.paths.push_back(path(1, branch));
  attach(s, 1, Junction::End::Head, 0, codedParentPoint);
  return s;
}

/// Distance of `p` from the branch's true axis line (through the meeting point).
double offBranchAxis(const Vec3& p, double angle_deg)
{
  const Vec3 m = onBranchAxis(0.0, angle_deg);
  const Vec3 u = onBranchAxis(1.0, angle_deg) - m;
  const Vec3 r = p - m;
  return (r - u * r.dot(u)).norm();
}

TEST(BranchEntry, ABranchCrossingTheParentsLumenEntersOnItsOwnAxis)
{
  // 30 degrees: the coder's merged band puts the junction 4 mm below where the axes meet and
  // crosses the lumen sideways; the rule carries the branch's axis on to the parent's.
  QSkeleton s = codedBranch(30.0, 26);
  const std::size_t codedPoints = s.paths[1].points.size();
  const BranchEntryReport report = placeBranchEntries(s);
  EXPECT_EQ(s.validate(), "");
  EXPECT_EQ(report.junctionsMoved, 1u);
  EXPECT_GT(report.pointsReplaced, 0u);
  ASSERT_EQ(s.junctions.size(), 1u);
  EXPECT_EQ(s.junctions[0].parentPoint, 30); // where the axes meet, not the coded 26
  // Every point of the branch on its true axis (the coded corner is gone).
  double worst = 0.0;
  for (const SkeletonPoint& p : s.paths[1].points)
  {
    worst = std::max(worst, offBranchAxis(p.position_World_mm, 30.0));
  }
  EXPECT_LT(worst, 0.05);
  // The attached end is the parent's point, a bifurcation; the coded one is ordinary again.
  EXPECT_EQ(
    (s.paths[1].points.front().position_World_mm - s.paths[0].points[30].position_World_mm).norm(),
    0.0);
  EXPECT_EQ(s.paths[1].points.front().label, PointLabel::Bifurcation);
  EXPECT_EQ(s.paths[0].points[30].label, PointLabel::Bifurcation);
  EXPECT_EQ(s.paths[0].points[26].label, PointLabel::Ordinary);
  // The entry is sampled at the branch's own spacing (1 mm here, over the 13-14 mm from the
  // parent's axis to the tube's wall, where the coded corner had fewer centres); the geometry is
  // the line's.
  EXPECT_GT(s.paths[1].points.size(), codedPoints);
  for (std::size_t i = 1; i < s.paths[1].points.size(); ++i)
  {
    const double step =
      (s.paths[1].points[i].position_World_mm - s.paths[1].points[i - 1].position_World_mm).norm();
    EXPECT_NEAR(step, 1.0, 0.05) << "point " << i;
  }
  const Vec3 t = s.paths[1].points[1].tangent_World;
  EXPECT_NEAR(t.dot(onBranchAxis(1.0, 30.0) - onBranchAxis(0.0, 30.0)), 1.0, 1e-9);
  EXPECT_EQ(s.paths[1].points[1].curvature_per_mm, 0.0);
}

TEST(BranchEntry, ATailAttachedBranchAndOneHangingBeyondItsEntryKeepTheirPlaces)
{
  // The same branch reversed (its tail attached), with a third path hanging on it 25 mm out.
  QSkeleton s = codedBranch(45.0, 27);
  std::vector<SkeletonPoint>& b = s.paths[1].points;
  std::reverse(b.begin(), b.end());
  s.junctions[0].childEnd = Junction::End::Tail;
  s.paths[1].head.junction = -1;
  s.paths[1].tail.junction = 0;
  const Vec3 hang = onBranchAxis(25.0, 45.0);
  int hangIndex = -1;
  for (std::size_t i = 0; i < b.size(); ++i)
  {
    if ((b[i].position_World_mm - hang).norm() < 0.6)
    {
      hangIndex = static_cast<int>(i);
    }
  }
  ASSERT_GE(hangIndex, 0);
  s.paths.push_back(path(2, { point(hang.x, hang.y, 5.0), point(hang.x, hang.y, 10.0) }));
  attach(s, 2, Junction::End::Head, 1, hangIndex);
  ASSERT_EQ(s.validate(), "");
  EXPECT_EQ(placeBranchEntries(s).junctionsMoved, 1u);
  EXPECT_EQ(s.validate(), "");
  EXPECT_EQ(s.junctions[0].parentPoint, 30);
  const std::vector<SkeletonPoint>& after = s.paths[1].points;
  EXPECT_EQ((after.back().position_World_mm - s.paths[0].points[30].position_World_mm).norm(), 0.0);
  // The third path still hangs at the same centre of the branch.
  const int moved = s.junctions[1].parentPoint;
  ASSERT_GE(moved, 0);
  EXPECT_LT((after[static_cast<std::size_t>(moved)].position_World_mm - hang).norm(), 1e-12);

  // Head attached, so the hanging point's index shifts with the entry's new length.
  QSkeleton h = codedBranch(45.0, 27);
  int headHang = -1;
  for (std::size_t i = 0; i < h.paths[1].points.size(); ++i)
  {
    if ((h.paths[1].points[i].position_World_mm - hang).norm() < 0.6)
    {
      headHang = static_cast<int>(i);
    }
  }
  h.paths.push_back(path(2, { point(hang.x, hang.y, 5.0), point(hang.x, hang.y, 10.0) }));
  attach(h, 2, Junction::End::Head, 1, headHang);
  EXPECT_EQ(placeBranchEntries(h).junctionsMoved, 1u);
  EXPECT_EQ(h.validate(), "");
  const int shifted = h.junctions[1].parentPoint;
  EXPECT_LT(
    (h.paths[1].points[static_cast<std::size_t>(shifted)].position_World_mm - hang).norm(), 1e-12);
}

TEST(BranchEntry, WhatIsNotABranchEnteringItsParentIsKeptAsCoded)
{
  // Along the parent (5 degrees: a vessel going on past a root, a loop's two fronts).
  {
    QSkeleton s = codedBranch(5.0, 2);
    const QSkeleton before = s;
    EXPECT_EQ(placeBranchEntries(s).junctionsMoved, 0u);
    EXPECT_TRUE(allPointsNear(s, before, 0.0) && allPointsNear(before, s, 0.0));
  }
  // Another path hangs on the stretch inside the parent's tube: it would lose its point.
  {
    QSkeleton s = codedBranch(30.0, 26);
    s.paths.push_back(path(2, { point(2.0, 26.0, 3.0), point(2.0, 26.0, 9.0) }));
    attach(s, 2, Junction::End::Head, 1, 2);
    const QSkeleton before = s;
    EXPECT_EQ(placeBranchEntries(s).junctionsMoved, 0u);
    EXPECT_EQ(s.junctions[0].parentPoint, 26);
    EXPECT_TRUE(allPointsNear(s, before, 0.0));
  }
  // A branch whose axis misses the parent's (offset 5 mm out of the plane: more than half the
  // parent's radius from every parent centre).
  {
    QSkeleton s = codedBranch(30.0, 26);
    for (std::size_t i = 0; i < s.paths[1].points.size(); ++i)
    {
      SkeletonPoint& p = s.paths[1].points[i];
      const double out = std::min(1.0, static_cast<double>(i) / 3.0) * 5.0;
      p.position_World_mm.z += out;
    }
    EXPECT_EQ(placeBranchEntries(s).junctionsMoved, 0u);
    EXPECT_EQ(s.junctions[0].parentPoint, 26);
  }
  // Too short to have an axis of its own past the parent's tube (two centres out of it).
  {
    QSkeleton s = codedBranch(30.0, 26);
    std::vector<SkeletonPoint>& b = s.paths[1].points;
    std::size_t firstOut = 0;
    while (b[firstOut].position_World_mm.x < kParentRadius_mm)
    {
      ++firstOut;
    }
    b.resize(firstOut + 2);
    b.back().label = PointLabel::EndPoint;
    EXPECT_EQ(placeBranchEntries(s).junctionsMoved, 0u);
  }
  // Hanging on an end of its parent (the parent runs from y = 26 on, its head is the coded
  // point): the two paths join there; moved to y = 30, the parent's head would be a free end.
  {
    QSkeleton s = codedBranch(30.0, 26);
    std::vector<SkeletonPoint>& parent = s.paths[0].points;
    parent.erase(parent.begin(), parent.begin() + 26);
    parent.front().label = PointLabel::EndPoint;
    s.junctions[0].parentPoint = 0;
    ASSERT_EQ(s.validate(), "");
    const QSkeleton before = s;
    EXPECT_EQ(placeBranchEntries(s).junctionsMoved, 0u);
    EXPECT_EQ(s.junctions[0].parentPoint, 0);
    EXPECT_TRUE(allPointsNear(s, before, 0.0) && allPointsNear(before, s, 0.0));
  }
  // Leaving the parent's tube at once: nothing inside to replace.
  {
    QSkeleton s;
    s.paths.push_back(parentAlongY());
    std::vector<SkeletonPoint> b{ point(0.0, 30.0, 0.0, kBranchRadius_mm) };
    for (int k = 7; k <= 30; ++k)
    {
      b.push_back(point(k, 30.0, 0.0, kBranchRadius_mm));
    }
    s.paths.push_back(path(1, b));
    attach(s, 1, Junction::End::Head, 0, 30);
    const QSkeleton before = s;
    EXPECT_EQ(placeBranchEntries(s).junctionsMoved, 0u);
    EXPECT_TRUE(allPointsNear(s, before, 0.0));
  }
}

TEST(BranchEntry, TheRuleIsStableItsSecondRunChangesNothing)
{
  QSkeleton s = codedBranch(30.0, 26);
  placeBranchEntries(s);
  const QSkeleton once = s;
  placeBranchEntries(s);
  EXPECT_EQ(s.junctions[0].parentPoint, once.junctions[0].parentPoint);
  EXPECT_TRUE(allPointsNear(s, once, 1e-9) && allPointsNear(once, s, 1e-9));
  EXPECT_EQ(s.paths[1].points.size(), once.paths[1].points.size());
}

} // namespace

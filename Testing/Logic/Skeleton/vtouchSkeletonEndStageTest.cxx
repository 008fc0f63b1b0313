// Stage 6 of the voxel coder alone: rounded ends trimmed to the cap's centre, stubs cut.
#include "vtouchPieceOwnership.h"
#include "vtouchSkeletonStageTestSupport.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstddef>
#include <vector>

namespace
{
using namespace vtouch;
using namespace vtouch::skeleton;
using namespace vtouch::skeleton::test;

/// A capsule of radius 4 mm, axis (10..40, 10, 10): apexes at x = 6 and 44.
SparseVesselMask capsule()
{
  return makeMask({ 51, 21, 21 },
    [](const Point_mm& p) {
      return distanceToSegment(p, { 10, 10, 10 }, { 40, 10, 10 }) <= 4.0;
    });
}

TEST(SkeletonEndStage, RoundedEndsEndAtTheCapCentre)
{
  const SparseVesselMask mask = capsule();
  Pipeline run(mask);
  run.code(run.lin(6, 10, 10));
  run.cluster();
  ASSERT_EQ(run.trace(), 1U);
  const RawSkeletonPath& path = run.draft.skeleton.paths[0];
  // Traced from apex to apex.
  EXPECT_NEAR(path.center_mm.front()[0], 6.0, 1.0);
  EXPECT_NEAR(path.center_mm.back()[0], 44.0, 1.0);
  const std::size_t traced = path.center_mm.size();
  run.ends();
  // Each end moved back by about one radius, onto the axis.
  EXPECT_NEAR(path.center_mm.front()[0], 10.0, 1.0);
  EXPECT_NEAR(path.center_mm.back()[0], 40.0, 1.0);
  for (const Point_mm& end : { path.center_mm.front(), path.center_mm.back() })
  {
    EXPECT_NEAR(end[1], 10.0, 0.5);
    EXPECT_NEAR(end[2], 10.0, 0.5);
  }
  EXPECT_LT(path.center_mm.size(), traced - 4);
  EXPECT_EQ(path.voxels.size(), path.center_mm.size());
  EXPECT_EQ(path.radius_mm.size(), path.center_mm.size());
}

TEST(SkeletonEndStage, MaskValueAndDistanceToTheWall)
{
  const SparseVesselMask mask = capsule();
  Pipeline run(mask);
  const EndStage stage(run.grid, 2.5, run.draft, 0);
  EXPECT_DOUBLE_EQ(stage.maskValueAt({ 20, 10, 10 }), 1.0);
  EXPECT_DOUBLE_EQ(stage.maskValueAt({ 20, 10, 14.5 }), 0.5); // between voxels 14 (in) and 15
  EXPECT_DOUBLE_EQ(stage.maskValueAt({ 20, 10, 16 }), 0.0);
  EXPECT_DOUBLE_EQ(stage.maskValueAt({ 50.5, 10, 10 }), -1.0); // needs a voxel beyond the volume
  EXPECT_NEAR(stage.distanceToWall({ 20, 10, 10 }, { 0, 0, 1 }, 10.0), 4.5, 1e-9);
  EXPECT_LT(stage.distanceToWall({ 20, 10, 10 }, { 0, 0, 1 }, 3.0), 0.0);  // beyond the limit
  EXPECT_LT(stage.distanceToWall({ 20, 10, 16 }, { 0, 0, 1 }, 10.0), 0.0); // not inside
}

/// A path of `n` points 1 mm apart along x from `x0`, radius `radius_mm`.
RawSkeletonPath straightPath(int n, double x0, double radius_mm)
{
  RawSkeletonPath p;
  for (int i = 0; i < n; ++i)
  {
    p.voxels.push_back({ static_cast<std::int64_t>(x0) + i, 0, 0 });
    p.center_mm.push_back({ x0 + i, 0.0, 0.0 });
    p.radius_mm.push_back(radius_mm);
  }
  return p;
}

/// A vessel tapering to its tail, as a path: points 1 mm apart along x from x = 10 to 49 (1 mm
/// voxels), radius 8 mm up to x = 37 and 2 mm from x = 38 on (its last 12 points), the tail a
/// free end. No vessel in the mask around it: the cap cannot be measured there, so the
/// inscribed-ball rule alone answers (measureEndCap's fallback).
RawSkeletonPath taperingPath()
{
  RawSkeletonPath p;
  for (int x = 10; x < 50; ++x)
  {
    p.voxels.push_back({ x, 2, 2 });
    p.center_mm.push_back({ static_cast<double>(x), 2.0, 2.0 });
    p.radius_mm.push_back(x >= 38 ? 2.0 : 8.0);
  }
  return p;
}

/// One vessel voxel far from the path (the grid needs one).
SparseVesselMask farVoxel()
{
  return makeMask({ 60, 5, 5 }, [](const Point_mm& p) { return p == Point_mm{ 0, 0, 0 }; });
}

TEST(SkeletonEndStage, ThinEndOfATaperingVesselIsTrimmedByItsOwnRadius)
{
  const SparseVesselMask mask = farVoxel();
  Pipeline run(mask);
  const EndStage stage(run.grid, 2.5, run.draft, 0);
  RawSkeletonPath path = taperingPath();
  const std::vector<char> pinned(path.voxels.size(), 0);
  // The end points inside the inscribed ball of a point further in, within 0.5 voxel + 0.1 of
  // the radius near the end (2 mm): point k (k mm in) holds the end for k <= 2 + 0.7. The radius
  // at the path's middle point (8 mm, x = 29) widened that to k <= 3.3 (until h19e: trim 3, one
  // point past the cap's centre).
  const EndStage::EndCap tail = stage.measureEndCap(path, true, pinned);
  EXPECT_EQ(tail.trim, 2U);
  EXPECT_FALSE(tail.centre_mm.has_value()); // no cap on the mask: the fallback answered
  // The same end as a head.
  std::reverse(path.voxels.begin(), path.voxels.end());
  std::reverse(path.center_mm.begin(), path.center_mm.end());
  std::reverse(path.radius_mm.begin(), path.radius_mm.end());
  EXPECT_EQ(stage.measureEndCap(path, false, pinned).trim, 2U);
}

TEST(SkeletonEndStage, EndCapIsTheSameOnAPathCutBeyondTheGhostMargin)
{
  // A distributed run (issue 19 item 2): a rank whose grown piece cuts the path sees only its
  // part of it, from the end to the cut, at least the ghost margin from an end the rank owns.
  // The end's cap reads the path within that margin only, so every such part gives the whole
  // path's cap.
  const SparseVesselMask mask = farVoxel();
  Pipeline run(mask);
  const EndStage stage(run.grid, 2.5, run.draft, 0);
  const RawSkeletonPath whole = taperingPath();
  const EndStage::EndCap expected =
    stage.measureEndCap(whole, true, std::vector<char>(whole.voxels.size(), 0));
  GhostMarginRule rule;
  rule.largestRadius_mm = 2.0; // the vessel's radius at the end
  const int margin = rule.voxels({ 1.0, 1.0, 1.0 });
  ASSERT_EQ(margin, 17);
  for (std::size_t kept = static_cast<std::size_t>(margin); kept < whole.voxels.size(); ++kept)
  {
    RawSkeletonPath part = whole;
    const auto cut = static_cast<std::ptrdiff_t>(whole.voxels.size() - kept);
    part.voxels.erase(part.voxels.begin(), part.voxels.begin() + cut);
    part.center_mm.erase(part.center_mm.begin(), part.center_mm.begin() + cut);
    part.radius_mm.erase(part.radius_mm.begin(), part.radius_mm.begin() + cut);
    const EndStage::EndCap cap = stage.measureEndCap(part, true, std::vector<char>(kept, 0));
    EXPECT_EQ(cap.trim, expected.trim) << kept << " points kept";
    EXPECT_TRUE(cap.centre_mm == expected.centre_mm) << kept << " points kept";
  }
}

TEST(SkeletonEndStage, StubBeyondTheLastJunctionIsCut)
{
  const SparseVesselMask mask = capsule();
  Pipeline run(mask);
  RawSkeleton& s = run.draft.skeleton;
  s.paths.push_back(straightPath(20, 0.0, 4.0)); // points 0..19
  RawSkeletonPath branch;
  branch.voxels = { { 10, 0, 0 }, { 10, 1, 0 } };
  branch.center_mm = { { 10, 0, 0 }, { 10, 1, 0 } };
  branch.radius_mm = { 4.0, 4.0 };
  branch.headJunction = 0;
  s.paths.push_back(branch);
  s.junctions.push_back({ 1, false, 0, 10 });
  run.draft.closedEnd = { { false, false }, { false, false } };
  EndStage(run.grid, 2.5, run.draft, 0).pruneStubEnds();
  // Tail: 9 mm beyond the junction < 2.5 radii (10 mm): cut there. Head: 10 mm, kept.
  EXPECT_EQ(s.paths[0].center_mm.size(), 11U);
  EXPECT_EQ(s.paths[0].voxels.size(), 11U);
  EXPECT_DOUBLE_EQ(s.paths[0].center_mm.front()[0], 0.0);
  EXPECT_DOUBLE_EQ(s.paths[0].center_mm.back()[0], 10.0);
  EXPECT_EQ(s.junctions[0].parentPoint, 10);
}

TEST(SkeletonEndStage, TheRootsOwnEndIsAStubOnlyWithinOneRadiusOfTheJunction)
{
  // A trunk on the capsule's axis (radius 4 mm) from x = 10, a branch joined at x = 20, the
  // trunk's tail the root's own end (its voxel in the SS code's first band): the seed the user
  // picked. 9 mm past the junction is under a spur's 10 mm but over one radius: kept; 2 mm is
  // inside the junction's lumen: cut. Without the SS code the 9 mm are cut as any spur.
  const SparseVesselMask mask = capsule();
  const auto run = [&mask](int trunkPoints, bool withCode)
  {
    Pipeline p(mask);
    RawSkeleton& s = p.draft.skeleton;
    RawSkeletonPath trunk;
    for (int i = 0; i < trunkPoints; ++i)
    {
      trunk.voxels.push_back({ 10 + i, 10, 10 });
      trunk.center_mm.push_back({ 10.0 + i, 10.0, 10.0 });
      trunk.radius_mm.push_back(4.0);
    }
    s.paths.push_back(trunk);
    RawSkeletonPath branch;
    branch.voxels = { { 20, 10, 10 }, { 20, 11, 10 } };
    branch.center_mm = { { 20, 10, 10 }, { 20, 11, 10 } };
    branch.radius_mm = { 4.0, 4.0 };
    branch.headJunction = 0;
    s.paths.push_back(branch);
    s.junctions.push_back({ 1, false, 0, 10 });
    p.draft.closedEnd = { { false, false }, { false, false } };
    std::vector<float> ss(mask.vesselCount(), 100.0F);
    ss[p.rank(10 + trunkPoints - 1, 10, 10)] = 0.0F;
    EndStage(p.grid, 2.5, p.draft, 0, withCode ? &ss : nullptr).pruneStubEnds();
    return s.paths[0].center_mm.size();
  };
  EXPECT_EQ(run(20, true), 20U);  // the root's end, 9 mm past the junction: kept
  EXPECT_EQ(run(20, false), 11U); // any end: a spur, cut at the junction
  EXPECT_EQ(run(13, true), 11U);  // the root's end, 2 mm past it: inside the junction, cut
}

} // namespace

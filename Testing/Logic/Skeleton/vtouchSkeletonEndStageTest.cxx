// Stage 6 of the voxel coder alone: rounded ends trimmed to the cap's centre, stubs cut.
#include "vtouchSkeletonStageTestSupport.h"

#include <gtest/gtest.h>

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

} // namespace

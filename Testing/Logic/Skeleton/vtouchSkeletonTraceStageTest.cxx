// Stage 4 of the voxel coder alone: back-tracing a Y into a parent path and a branch.
#include "vtouchSkeletonStageTestSupport.h"

#include <gtest/gtest.h>

namespace
{
using namespace vtouch;
using namespace vtouch::skeleton;
using namespace vtouch::skeleton::test;

TEST(SkeletonTraceStage, YGivesAParentPathAndOneBranchJoinedAtTheFork)
{
  const SparseVesselMask mask = yShape();
  Pipeline run(mask);
  run.code(run.lin(20, 1, 10)); // the trunk cap's apex
  run.cluster();
  ASSERT_EQ(run.trace(), 2U);
  const RawSkeleton& s = run.draft.skeleton;
  ASSERT_EQ(s.junctions.size(), 1U);
  EXPECT_EQ(s.junctions[0].childPath, 1);
  EXPECT_FALSE(s.junctions[0].childTail);
  EXPECT_EQ(s.junctions[0].parentPath, 0);
  EXPECT_EQ(s.paths[1].headJunction, 0);
  EXPECT_EQ(s.paths[0].headJunction, -1);
  // The branch starts at its parent's point, near the fork.
  EXPECT_EQ(s.paths[1].center_mm.front(), s.paths[0].center_mm[s.junctions[0].parentPoint]);
  EXPECT_LT(distance(s.paths[1].center_mm.front(), kYFork), 3.0);
  // The path runs from the root to a tip (the end caps are trimmed later, by EndStage).
  EXPECT_LT(distance(s.paths[0].center_mm.front(), { 20, 1, 10 }), 1.5);
  for (const RawSkeletonPath& path : s.paths)
  {
    ASSERT_EQ(path.voxels.size(), path.center_mm.size());
    ASSERT_EQ(path.voxels.size(), path.radius_mm.size());
    for (std::size_t i = 0; i < path.center_mm.size(); ++i)
    {
      // On the axes (within 1.25 mm of a radius of 3 mm), or on their extension into the end caps.
      const Point_mm& c = path.center_mm[i];
      const double cap =
        std::min({ distance(c, kYTrunkEnd), distance(c, kYLeftEnd), distance(c, kYRightEnd) });
      EXPECT_LE(distanceToY(c), cap < 3.5 ? 3.0 : 1.25) << i;
      EXPECT_LE(path.radius_mm[i], 4.5);
    }
  }
  // The middle of the trunk: the radius of the capsule (BS reaches the background voxel centres).
  const RawSkeletonPath& trunk = s.paths[0];
  const auto middle = std::min_element(trunk.center_mm.begin(),
    trunk.center_mm.end(),
    [](const Point_mm& a, const Point_mm& b) {
      return distance(a, { 20, 13, 10 }) < distance(b, { 20, 13, 10 });
    });
  EXPECT_NEAR(trunk.radius_mm[middle - trunk.center_mm.begin()], 3.5, 0.5);
  // Both rounded ends of the parent, and the branch's tip, are closed vessel ends.
  ASSERT_EQ(run.draft.closedEnd.size(), 2U);
  EXPECT_TRUE(run.draft.closedEnd[0][0]);
  EXPECT_TRUE(run.draft.closedEnd[0][1]);
  EXPECT_FALSE(run.draft.closedEnd[1][0]);
  EXPECT_TRUE(run.draft.closedEnd[1][1]);
}

TEST(SkeletonTraceStage, ASpurShorterThanTheMinimumBranchLengthIsDropped)
{
  // A tube with a bump of 2 mm on its side: a tip of its own, far shorter than 2.5 radii.
  const SparseVesselMask mask = makeMask({ 50, 21, 15 },
    [](const Point_mm& p)
    {
      return distanceToSegment(p, { 5, 8, 7 }, { 44, 8, 7 }) <= 3.0 ||
             distanceToSegment(p, { 25, 8, 7 }, { 25, 13, 7 }) <= 1.5;
    });
  Pipeline run(mask);
  run.code(run.lin(2, 8, 7));
  run.cluster();
  EXPECT_EQ(run.trace(), 1U);
  EXPECT_TRUE(run.draft.skeleton.junctions.empty());
}

} // namespace

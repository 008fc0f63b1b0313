// Stage 5 of the voxel coder alone: a torus's two SS fronts closed into a loop.
#include "vtouchSkeletonStageTestSupport.h"

#include <gtest/gtest.h>

namespace
{
using namespace vtouch;
using namespace vtouch::skeleton;
using namespace vtouch::skeleton::test;

/// Distance from `p` to the circle of radius 12 around (18, 18) in the plane z = 6.
double distanceToRing(const Point_mm& p)
{
  const double inPlane = std::hypot(p[0] - 18.0, p[1] - 18.0) - 12.0;
  return std::hypot(inPlane, p[2] - 6.0);
}

TEST(SkeletonLoopStage, TorusIsClosedIntoOneLoop)
{
  const SparseVesselMask mask =
    makeMask({ 37, 37, 13 }, [](const Point_mm& p) { return distanceToRing(p) <= 3.5; });
  Pipeline run(mask);
  run.code(run.lin(30, 18, 6));
  run.cluster();
  ASSERT_GE(run.trace(), 1U);
  const RawSkeleton& s = run.draft.skeleton;
  EXPECT_EQ(s.loops, 0);
  run.loops();
  EXPECT_EQ(s.loops, 1);
  // The loop's path is attached at both ends.
  int closing = 0;
  for (const RawSkeletonPath& path : s.paths)
  {
    closing += path.headJunction >= 0 && path.tailJunction >= 0 ? 1 : 0;
  }
  EXPECT_EQ(closing, 1);
  // The tree's tip where the two fronts met is on the outer wall (the geodesic's longest way);
  // beyond the loop's junction it is a stub, which the end stage cuts. Then the skeleton goes
  // round the ring on its axis.
  run.ends();
  double covered = 0.0;
  for (const RawSkeletonPath& path : s.paths)
  {
    for (std::size_t i = 0; i < path.center_mm.size(); ++i)
    {
      EXPECT_LT(distanceToRing(path.center_mm[i]), 1.5) << i;
      if (i > 0)
      {
        covered += distance(path.center_mm[i], path.center_mm[i - 1]);
      }
    }
  }
  EXPECT_NEAR(covered, 2.0 * 3.14159265358979 * 12.0, 10.0);
}

TEST(SkeletonLoopStage, AStraightTubeHasNoLoop)
{
  const SparseVesselMask mask = makeMask({ 40, 13, 13 },
    [](const Point_mm& p) {
      return distanceToSegment(p, { 5, 6, 6 }, { 34, 6, 6 }) <= 3.0;
    });
  Pipeline run(mask);
  run.code(run.lin(2, 6, 6));
  run.cluster();
  ASSERT_EQ(run.trace(), 1U);
  run.loops();
  EXPECT_EQ(run.draft.skeleton.loops, 0);
  EXPECT_EQ(run.draft.skeleton.paths.size(), 1U);
}

} // namespace

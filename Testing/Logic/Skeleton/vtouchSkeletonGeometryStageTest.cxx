// Stage 7 of the voxel coder alone: a path through a bifurcation straightened beyond it.
#include "vtouchSkeletonGeometryStage.h"
#include "vtouchSkeletonVoxelGrid.h"

#include <gtest/gtest.h>

#include <cmath>

namespace
{
using namespace vtouch;
using namespace vtouch::skeleton;

/// A parent along x (points 0..20, radius 2.5 mm) with a child attached at point 10 and the two
/// points after the junction pulled 0.5 mm toward the crotch (+y), as the merged lumen's ridge
/// pulls a trace.
RawSkeleton kinkedBifurcation()
{
  RawSkeleton s;
  RawSkeletonPath parent;
  for (int i = 0; i <= 20; ++i)
  {
    parent.voxels.push_back({ i, 0, 0 });
    parent.center_mm.push_back({ static_cast<double>(i), i == 11 || i == 12 ? 0.5 : 0.0, 0.0 });
    parent.radius_mm.push_back(2.5);
  }
  RawSkeletonPath child;
  for (int j = 0; j <= 10; ++j)
  {
    child.voxels.push_back({ 10, j, 0 });
    child.center_mm.push_back({ 10.0, static_cast<double>(j), 0.0 });
    child.radius_mm.push_back(2.0);
  }
  child.headJunction = 0;
  s.paths = { parent, child };
  s.junctions.push_back({ 1, false, 0, 10 });
  return s;
}

TEST(SkeletonGeometryStage, ThroughPathIsStraightenedWithinOneRadiusBeyondTheJunction)
{
  RawSkeleton s = kinkedBifurcation();
  GeometryStage(s, 0, 1.0).straightenThroughPaths({});
  const RawSkeletonPath& p = s.paths[0];
  // Points 11 and 12 lie within one radius (2.5 mm) of the junction; point 13 is the first
  // beyond: they go onto the line from the junction to it, as far along as they were from it.
  for (int i : { 11, 12 })
  {
    const double t = std::hypot(static_cast<double>(i) - 10.0, 0.5) / 3.0;
    EXPECT_DOUBLE_EQ(p.center_mm[i][0], 10.0 + 3.0 * t) << i;
    EXPECT_DOUBLE_EQ(p.center_mm[i][1], 0.0) << i;
  }
  EXPECT_DOUBLE_EQ(p.center_mm[13][0], 13.0);
  EXPECT_DOUBLE_EQ(p.center_mm[10][0], 10.0);
  EXPECT_EQ(p.voxels.size(), 21U);
  EXPECT_EQ(s.paths[1].center_mm, kinkedBifurcation().paths[1].center_mm); // the child stays
}

TEST(SkeletonGeometryStage, RecentredJunctionsAreLeftAlone)
{
  RawSkeleton s = kinkedBifurcation();
  GeometryStage(s, 0, 1.0).straightenThroughPaths({ true });
  EXPECT_DOUBLE_EQ(s.paths[0].center_mm[11][1], 0.5);
}

TEST(SkeletonGeometryStage, PathsBeforeTheComponentAreNotMoved)
{
  RawSkeleton s = kinkedBifurcation();
  GeometryStage(s, 1, 1.0).straightenThroughPaths({});
  EXPECT_DOUBLE_EQ(s.paths[0].center_mm[11][1], 0.5);
}

} // namespace

// A path crossing a piece face is smoothed as one path (issue 19 item 2): the smoothing windows
// scale with a path's median radius (skeletonPathWindows), and a rank sees only its part of a
// path, so the ranks keep the coder's centres and the stitched whole paths are smoothed
// (smoothSkeletonPaths; the 256^3, 512 x 512 x 256 and 1024 x 1024 x 512 scaling trees were up to
// 0.16, 0.61 and 0.74 voxel off with each rank's own windows). Ranks as threads, the filter's
// distributed path (vtouchDistributedStitchRun.h), 2 pieces along z.
//
// The scene: a thick trunk (radius 5) rises from the lower piece through the shared face and
// narrows to a thin vessel (radius 1.5) that turns in the upper piece. The whole path's median
// radius is the trunk's; the upper rank's part is mostly the thin vessel.
#include "vtouchDistributedStitchRun.h"
#include "vtouchStitchRunExpectations.h"
#include "vtouchDistributedTestScenes.h"
#include "vtouchPieceGrid.h"

#include "vtouchPieceOwnership.h"

#include <gtest/gtest.h>

#include <cstdio>

namespace vtouch
{
namespace
{
constexpr double kTolerance_voxels = 0.1; // the 0.1 voxel (1 mm voxels here)

TEST(DistributedStitchGeometry, AThickTrunkNarrowingToABendAcrossTheFaceIsSmoothedAsOnePath)
{
  const test::Dims dims{ 64, 64, 128 };
  const std::array<int, 3> split{ 1, 1, 2 };
  GhostMarginRule rule;
  rule.largestRadius_mm = 5.0;
  const int ghost = rule.voxels({ 1.0, 1.0, 1.0 });
  const std::vector<PieceLayout> pieces = test::layouts(dims, split, ghost);
  const double face = static_cast<double>(pieces[1].owned[1].lo[2]);
  // The trunk from z = 2 to 2 voxels above the face (about 63 points, 40 of them in the upper
  // rank's grown piece), then the thin vessel (about 50 points) up and turning at a right angle:
  // the whole path's median radius is the trunk's, the upper rank's part's the thin vessel's, so
  // its own windows are a third as wide at the bend.
  const skeleton::Point_mm a{ 32.0, 32.0, 2.0 };
  const skeleton::Point_mm b{ 32.0, 32.0, face + 2.0 };
  const skeleton::Point_mm c{ 32.0, 32.0, face + 25.0 };
  const skeleton::Point_mm d{ 59.0, 32.0, face + 25.0 };
  const std::vector<float> volume =
    test::capsuleVolume(dims, { { a, b, 5.0 }, { b, c, 1.5 }, { c, d, 1.5 } });
  const test::DistributedStitchRun run =
    test::runDistributedStitch(volume, dims, 550.0, split, ghost);
  std::printf("trunk narrowing to a bend across the face z = %.0f (ghost %d): farthest %.3f / "
              "%.3f voxel (stitched from single / single from stitched), paths %zu / %zu\n",
    face,
    ghost,
    test::farthestPoint_mm(run.stitched, run.single),
    test::farthestPoint_mm(run.single, run.stitched),
    run.stitched.paths.size(),
    run.single.paths.size());
  test::expectSameNetwork(run);
  EXPECT_LE(test::farthestPoint_mm(run.stitched, run.single), kTolerance_voxels);
  EXPECT_LE(test::farthestPoint_mm(run.single, run.stitched), kTolerance_voxels);
}

} // namespace
} // namespace vtouch

// A vessel entering a piece obliquely (issue 19 item 2, h19k): its face tip there is a sliver.
//
// Where a vessel crosses a piece's face at a slant, the piece's part of the slab the face cuts
// is a sliver at the wall (BS about a voxel), and its descent runs along the face, across the
// vessel, to its ridge before it meets the chain of the single run's tip beyond the face.
// DistributedFaceTips searched that descent over 3 bands plus two radii *of the sliver*, ended
// short of the chain and answered "none" (a loop's second side): the root's rank traced the
// branch last, attached where it touched, and its junction departed (the 512 x 512 x 256
// scaling tree on 2 ranks: 11 points up to 1.47 voxels, Docs/CLIENT-SERVER.md). The window's
// radius is now the vessel's (the largest BS of the clusters the descent has crossed). And where
// the vessel runs nearly along the face, its axis stays outside the piece's held box for several
// radii while the descent runs beside it along the face: the window now starts where the descent
// leaves the face (ABranchRunningAlmostAlongTheFace...: 1.50 voxels before, the same tree split
// in z: 0.93 / 1.47).
//
// The scene: a trunk along x in the upper piece, a branch of the same radius leaving it at
// about 49 degrees down into the lower piece, split in y between them; the filter's distributed
// path with ranks as threads (vtouchDistributedStitchRun.h), the ghost margin of the filter's
// rule for the radius.
#include "vtouchDistributedStitchRun.h"
#include "vtouchDistributedTestScenes.h"
#include "vtouchPieceOwnership.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <vector>

namespace vtouch
{
namespace
{
constexpr double kTolerance_voxels = 0.1; // the 0.1 voxel (1 mm voxels here)
constexpr double kRadius_voxels = 5.0;

const test::Dims kDims{ 192, 200, 96 };

std::vector<test::Capsule> trunkAndObliqueBranch()
{
  return { { { 8.0, 120.0, 48.0 }, { 184.0, 120.0, 48.0 }, kRadius_voxels },
    { { 160.0, 120.0, 48.0 }, { 40.0, 50.0, 48.0 }, kRadius_voxels } };
}

/// The same trunk; the branch bends 50 voxels below it and runs on nearly along the face (about
/// 79 degrees from its normal) into the lower piece.
std::vector<test::Capsule> trunkAndBranchAlongTheFace()
{
  return { { { 8.0, 120.0, 48.0 }, { 184.0, 120.0, 48.0 }, kRadius_voxels },
    { { 160.0, 120.0, 48.0 }, { 120.0, 70.0, 48.0 }, kRadius_voxels },
    { { 120.0, 70.0, 48.0 }, { 20.0, 50.0, 48.0 }, kRadius_voxels } };
}

int ghostFor(double radius_mm)
{
  GhostMarginRule rule;
  rule.largestRadius_mm = radius_mm;
  return rule.voxels({ 1.0, 1.0, 1.0 });
}

void report(const char* scene, const test::DistributedStitchRun& run)
{
  std::printf("%s: root (%lld, %lld, %lld), ghost %d; %zu paths (single %zu), farthest %.3f / "
              "%.3f voxel\n",
    scene,
    static_cast<long long>(run.root[0]),
    static_cast<long long>(run.root[1]),
    static_cast<long long>(run.root[2]),
    ghostFor(kRadius_voxels),
    run.stitched.paths.size(),
    run.single.paths.size(),
    test::farthestPoint_mm(run.stitched, run.single),
    test::farthestPoint_mm(run.single, run.stitched));
}

/// The scene on 2 pieces split in y (the trunk in the upper one), unseeded and seeded at the
/// junction (160, 120, 48): the single run's topology and every point within 0.1 voxel.
void expectTheSingleRunOnTwoPieces(const char* scene, const std::vector<test::Capsule>& capsules)
{
  const std::vector<float> volume = test::capsuleVolume(kDims, capsules);
  for (const bool seeded : { false, true })
  {
    const test::DistributedStitchRun run = test::runDistributedStitch(
      volume, kDims, 500.0, { 1, 2, 1 }, ghostFor(kRadius_voxels), seeded, { 160, 120, 48 });
    SCOPED_TRACE(std::string(scene) + (seeded ? ", seeded at the junction" : ", automatic root"));
    report(scene, run);
    EXPECT_EQ(test::freeEnds(run.stitched), test::freeEnds(run.single));
    EXPECT_EQ(run.stitched.junctions.size(), run.single.junctions.size());
    EXPECT_EQ(run.report.cutEndsUnmatched, 0);
    EXPECT_EQ(run.report.pointsDropped, 0);
    EXPECT_LE(test::farthestPoint_mm(run.stitched, run.single), kTolerance_voxels);
    EXPECT_LE(test::farthestPoint_mm(run.single, run.stitched), kTolerance_voxels);
  }
}

TEST(DistributedStitchGeometry, ABranchEnteringThePieceObliquelyIsTheSingleRuns)
{
  // 2.49 (automatic root) and 2.70 voxels (seeded) before the vessel's radius in the window.
  expectTheSingleRunOnTwoPieces("oblique branch", trunkAndObliqueBranch());
}

TEST(DistributedStitchGeometry, ABranchRunningAlmostAlongTheFaceIsTheSingleRuns)
{
  // 1.02 and 1.50 voxels before the window started where the descent leaves the face.
  expectTheSingleRunOnTwoPieces("branch along the face", trunkAndBranchAlongTheFace());
}

} // namespace
} // namespace vtouch

// A vessel that runs along the upper rank's grown piece, just outside it or in and out of it,
// before it rises through the shared face into a junction above the face (issue 19 item 2, h19j:
// the 256^3 scaling tree's junction at (138, 137, 138) on 2 and 4 pieces, Docs/CLIENT-SERVER.md,
// "Where the distributed geometry departs"). Ranks as threads, the filter's distributed path
// (vtouchDistributedStitchRun.h), 2 pieces along z.
//
// The scenes: a far tip's vessel (leg A, radius 2.5) runs along the lowest plane of the upper
// rank's grown piece, then rises through the shared face into a junction 11 voxels above it; a
// nearer tip's vessel (leg B) rises straight into the same junction; a thicker trunk (3.5) goes
// on up to the root. The single run traces A's tip through the junction first (the farther tip).
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

using skeleton::Point_mm;

const test::Dims kDims{ 64, 64, 112 };
const std::array<int, 3> kSplit{ 1, 1, 2 };

/// The filter's ghost margin for the trunk's radius, 3.5 voxels (28 voxels).
int ghost()
{
  GhostMarginRule rule;
  rule.largestRadius_mm = 3.5;
  return rule.voxels({ 1.0, 1.0, 1.0 });
}

/// The upper rank's grown piece's lowest plane and its first owned plane (the shared face).
std::pair<double, double> grownLowAndFace()
{
  const std::vector<PieceLayout> pieces = test::layouts(kDims, kSplit, ghost());
  return { static_cast<double>(pieces[1].held[1].lo[2]),
    static_cast<double>(pieces[1].owned[1].lo[2]) };
}

/// Leg A along `legA` (from its tip to its last point, then on to the junction), leg B and the
/// trunk; the distributed run on 2 pieces, printed.
test::DistributedStitchRun runScene(const char* name, const std::vector<Point_mm>& legA)
{
  const auto [grownLo, face] = grownLowAndFace();
  const Point_mm junction{ 32.0, 32.0, face + 11.0 };
  std::vector<test::Capsule> capsules;
  for (std::size_t i = 0; i < legA.size(); ++i)
  {
    capsules.push_back({ legA[i], i + 1 < legA.size() ? legA[i + 1] : junction, 2.5 });
  }
  capsules.push_back({ { 54.0, 44.0, grownLo - 15.5 }, junction, 2.5 }); // B
  capsules.push_back({ junction, { 32.0, 32.0, static_cast<double>(kDims[2]) - 7.0 }, 3.5 });
  const std::vector<float> volume = test::capsuleVolume(kDims, capsules);
  const test::DistributedStitchRun run =
    test::runDistributedStitch(volume, kDims, 550.0, kSplit, ghost());
  std::printf("%s (ghost %d, grown piece from z = %.0f, face z = %.0f): farthest %.3f / %.3f "
              "voxel (stitched from single / single from stitched), paths %zu / %zu\n",
    name,
    ghost(),
    grownLo,
    face,
    test::farthestPoint_mm(run.stitched, run.single),
    test::farthestPoint_mm(run.single, run.stitched),
    run.stitched.paths.size(),
    run.single.paths.size());
  return run;
}

using test::expectSameNetwork;

TEST(DistributedStitchGeometry, ALegGrazingTheGrownPiecesFaceIsTracedThroughItsJunctionFirst)
{
  // A's axis 1.5 voxels below the grown piece for 26 voxels, its top two voxel layers inside: the
  // grown piece cuts it lengthwise. The upper rank sees A's top as a face tip where the graze
  // starts, while the chain of A's tip stays outside until the rise, 26 mm of SS further down:
  // the face tips' answer window counted from the tip's start alone (3 bands and 2 radii) missed
  // it and answered "no tip beyond" (a loop's second side), so the rank traced B through the
  // junction first (0.572 / 0.877 voxel before h19j); the window now runs on from the last slab
  // a face cuts.
  const double graze = grownLowAndFace().first - 1.5;
  const test::DistributedStitchRun run = runScene("a leg grazing the grown piece",
    { { 10.0, 40.0, graze - 21.0 }, { 10.0, 16.0, graze }, { 36.0, 16.0, graze } });
  expectSameNetwork(run);
  EXPECT_LE(test::farthestPoint_mm(run.stitched, run.single), kTolerance_voxels);
  EXPECT_LE(test::farthestPoint_mm(run.single, run.stitched), kTolerance_voxels);
}

TEST(DistributedStitchGeometry, AChainLeavingTheGrownPieceAndEnteringAgainIsTracedInItsOrder)
{
  // A's tip lies in the upper rank's grown piece; A dips 3.5 voxels out of it (a V 9 voxels
  // wide) and comes back: the rank sees the true tip and, where A enters again, a face tip
  // answered with the same band. The single run's one trace meets the true tip first; the rank
  // traced the face tip first (the lower cluster number): the true tip's trace joined its path
  // as a branch, and the points at the junction moved by 0.088 voxel (before h19j). Tips tied
  // in rank now go by their own band, higher first: the single run's points, point for point.
  const double lo = grownLowAndFace().first;
  const test::DistributedStitchRun run = runScene("a chain leaving the grown piece and back",
    { { 8.0, 44.0, lo + 8.0 },
      { 8.0, 16.0, lo + 2.0 },
      { 14.0, 16.0, lo + 2.0 },
      { 18.5, 16.0, lo - 3.5 },
      { 23.0, 16.0, lo + 2.0 } });
  expectSameNetwork(run);
  EXPECT_LE(test::farthestPoint_mm(run.stitched, run.single), 1e-3);
  EXPECT_LE(test::farthestPoint_mm(run.single, run.stitched), 1e-3);
}

} // namespace
} // namespace vtouch

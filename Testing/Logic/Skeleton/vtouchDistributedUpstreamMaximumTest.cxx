// vtouch::DistributedUpstreamMaximum (issue 19 item 2, h19q): the farthest tip above every
// vessel voxel (the largest SS along a rising path) across 2, 4 and 8 pieces, ranks as threads,
// against the one-process definition on the whole mask.
#include "vtouchDistributedUpstreamMaximum.h"

#include "vtouchDistributedTestScenes.h"
#include "vtouchEveryRank.h"
#include "vtouchPieceGrid.h"
#include "vtouchSeedCodeRun.h"
#include "vtouchSkeletonStageTestSupport.h"

#include <gtest/gtest.h>

#include <random>
#include <string>

namespace vtouch
{
namespace
{
using skeleton::test::Dims;
using test::layouts;
using test::pieceMask;
using test::VoxelIndex;

struct RankResult
{
  RoundsOutcome outcome;
  int differing = 0; ///< held vessel voxels whose U is not the whole mask's
  int raised = 0;    ///< held vessel voxels whose U is above their own SS
  std::string firstDiffering;
};

/// The whole mask's field restricted to `l`'s held box (indexed by the piece mask's rank).
std::vector<float> pieceField(const SparseVesselMask& whole,
  const std::vector<float>& field,
  const SparseVesselMask& piece,
  const PieceLayout& l)
{
  std::vector<float> out(piece.vesselCount());
  const Dims d = piece.dims();
  piece.forEach(
    [&](std::uint64_t lin)
    {
      const auto i = static_cast<std::int64_t>(lin);
      const VoxelIndex c = l.toWhole({ i % d[0], (i / d[0]) % d[1], i / (d[0] * d[1]) });
      out[piece.rank(lin)] = field[whole.rank(static_cast<std::uint64_t>(l.wholeLinear(c)))];
    });
  return out;
}

std::vector<RankResult> runOnRanks(const SparseVesselMask& whole,
  const std::vector<float>& ss,
  const std::vector<float>& expected,
  const std::vector<PieceLayout>& pieces,
  int maximumRounds = DistributedUpstreamMaximum::kDefaultMaximumRounds)
{
  return test::onEveryRank<RankResult>(pieces,
    [&](const PieceLayout& l, RankCollectives& c, RankResult& out)
    {
      const SparseVesselMask mask = pieceMask(whole, l);
      const std::vector<float> field = pieceField(whole, ss, mask, l);
      DistributedUpstreamMaximum up(l, mask, field);
      out.outcome = up.run(c, maximumRounds);
      const std::vector<float> want = pieceField(whole, expected, mask, l);
      for (std::size_t r = 0; r < want.size(); ++r)
      {
        out.raised += up.upstream_mm()[r] > field[r];
        if (up.upstream_mm()[r] != want[r] && out.differing++ == 0)
        {
          out.firstDiffering = "rank " + std::to_string(r) + ": " +
                               std::to_string(up.upstream_mm()[r]) + " instead of " +
                               std::to_string(want[r]);
        }
      }
    });
}

TEST(DistributedUpstreamMaximum, TheWholeMasksDefinitionOnATube)
{
  // A straight tube rooted at one end: every voxel's farthest tip is the far end's SS.
  const SparseVesselMask tube = skeleton::test::makeMask({ 30, 9, 9 },
    [](const skeleton::Point_mm& p)
    { return p[0] >= 2 && p[0] <= 27 && (p[1] - 4) * (p[1] - 4) + (p[2] - 4) * (p[2] - 4) <= 4; });
  const std::vector<float> ss = test::singleRunField(tube, { 1, 1, 1 }, { { 2, 4, 4 } });
  const std::vector<float> up = DistributedUpstreamMaximum::wholeVolume(tube, ss);
  const float far = *std::max_element(ss.begin(), ss.end());
  int atFar = 0;
  for (std::size_t r = 0; r < up.size(); ++r)
  {
    EXPECT_GE(up[r], ss[r]);
    atFar += up[r] == far;
  }
  EXPECT_GT(atFar, static_cast<int>(up.size()) / 2); // the axis rises all the way to the far end
  EXPECT_EQ(up[tube.rank(tube.dims()[0] * (4 + 9 * 4) + 2)], far); // the root sees the far end
}

TEST(DistributedUpstreamMaximum, EveryRankHoldsTheWholeMasksValuesIn2And4And8Pieces)
{
  const Dims dims{ 44, 40, 48 };
  std::mt19937 random(19);
  int multiRound = 0;
  for (unsigned trial = 0; trial < 4; ++trial)
  {
    const SparseVesselMask whole = test::randomTree(dims, 1900 + trial);
    const VoxelIndex root = test::randomVesselVoxel(whole, random);
    const std::vector<float> ss = test::singleRunField(whole, { 1, 1, 1 }, { root });
    const std::vector<float> expected = DistributedUpstreamMaximum::wholeVolume(whole, ss);
    for (const std::array<int, 3>& counts : test::kSplitsIn2And4And8)
    {
      const int margin = 1 + static_cast<int>(trial % 3);
      const std::vector<RankResult> results =
        runOnRanks(whole, ss, expected, layouts(dims, counts, margin));
      int raised = 0;
      for (std::size_t r = 0; r < results.size(); ++r)
      {
        SCOPED_TRACE("trial " + std::to_string(trial) + ", " + std::to_string(results.size()) +
                     " pieces, rank " + std::to_string(r));
        EXPECT_TRUE(results[r].outcome.settled) << results[r].outcome.message;
        EXPECT_EQ(results[r].outcome.rounds, results.front().outcome.rounds);
        EXPECT_EQ(results[r].differing, 0) << results[r].firstDiffering;
        raised += results[r].raised;
      }
      EXPECT_GT(raised, 200); // not the SS itself
      multiRound += results.front().outcome.rounds > 2;
    }
  }
  EXPECT_GT(multiRound, 0); // some value was relayed through a third piece
}

TEST(DistributedUpstreamMaximum, OneRoundIsNotEnoughAndTheCapStopsEveryRank)
{
  const Dims dims{ 44, 40, 48 };
  const SparseVesselMask whole = test::randomTree(dims, 1900);
  std::mt19937 random(19);
  const VoxelIndex root = test::randomVesselVoxel(whole, random);
  const std::vector<float> ss = test::singleRunField(whole, { 1, 1, 1 }, { root });
  const std::vector<float> expected = DistributedUpstreamMaximum::wholeVolume(whole, ss);
  const std::vector<RankResult> capped =
    runOnRanks(whole, ss, expected, layouts(dims, { 2, 2, 2 }, 1), 1);
  int differing = 0;
  for (const RankResult& r : capped)
  {
    EXPECT_FALSE(r.outcome.settled);
    EXPECT_NE(r.outcome.message.find("did not settle in 1 rounds"), std::string::npos)
      << r.outcome.message;
    differing += r.differing;
  }
  EXPECT_GT(differing, 0); // a piece alone does not know the tips beyond it
}

TEST(DistributedUpstreamMaximum, ALayoutWithoutAGhostLayerOrAWrongFieldIsRefused)
{
  const Dims dims{ 20, 20, 20 };
  const SparseVesselMask whole = test::randomTree(dims, 1901);
  const PieceLayout bare = layouts(dims, { 1, 1, 2 }, 0)[1];
  const SparseVesselMask mask = pieceMask(whole, bare);
  const std::vector<float> field(mask.vesselCount(), 1.0f);
  EXPECT_THROW(DistributedUpstreamMaximum(bare, mask, field), std::invalid_argument);
  const PieceLayout ghost = layouts(dims, { 1, 1, 2 }, 1)[1];
  const SparseVesselMask held = pieceMask(whole, ghost);
  EXPECT_THROW(DistributedUpstreamMaximum(ghost, held, std::vector<float>(held.vesselCount() + 1)),
    std::invalid_argument);
}

} // namespace
} // namespace vtouch

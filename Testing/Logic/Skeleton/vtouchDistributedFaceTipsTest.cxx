// vtouch::DistributedFaceTips' collective contract (issue 19 item 2): every rank joins every
// round, also a rank whose piece holds no vessel or whose coder never ran, and a round cap stops
// every rank in the same round with the same message. Ranks as threads (InProcessWorld).
#include "vtouchDistributedFaceTips.h"
#include "vtouchDistributedSeedCode.h"
#include "vtouchEveryRank.h"
#include "vtouchPieceGrid.h"
#include "vtouchSkeletonStageTestSupport.h"

#include <gtest/gtest.h>

#include <string>

namespace vtouch
{
namespace
{
using skeleton::Point_mm;
using Index = std::array<std::int64_t, 3>;

/// A tube of radius 3.2 along z from `z0` to `z1`, its axis at x = 60.3, y = 60.6.
SparseVesselMask tube(double z0, double z1)
{
  return skeleton::test::makeMask({ 128, 128, 128 },
    [&](const Point_mm& p)
    {
      const double dx = p[0] - 60.3, dy = p[1] - 60.6;
      return p[2] >= z0 && p[2] <= z1 && dx * dx + dy * dy <= 3.2 * 3.2;
    });
}

struct RankRun
{
  RoundsOutcome outcome;
  std::string error;
  std::size_t paths = 0;
};

/// Codes `whole` seeded at `root` on 4 pieces along z with the face tips' answers (cap
/// `maximumRounds`); rank `joinOnly` (or none: -1) joins without coding.
std::vector<RankRun> codeOnFourPieces(const SparseVesselMask& whole,
  const Index& root,
  int maximumRounds,
  int joinOnly)
{
  const std::vector<PieceLayout> pieces = test::layouts({ 128, 128, 128 }, { 1, 1, 4 }, 26);
  return test::onEveryRank<RankRun>(pieces,
    [&](const PieceLayout& l, RankCollectives& c, RankRun& out)
    {
      const SparseVesselMask mask = test::pieceMask(whole, l);
      DistributedSeedCode code(l, mask, { 1.0, 1.0, 1.0 });
      code.run(c, { root });
      DistributedFaceTips faceTips(c, l, maximumRounds);
      try
      {
        if (l.rank == joinOnly)
        {
          faceTips.join();
        }
        else
        {
          VoxelCodingParameters global;
          global.globalSs_mm = &code.ss();
          global.faceTipBands = [&faceTips](const skeleton::SkeletonTracer& t)
          { return faceTips.answer(t); };
          out.paths = VoxelCoder(mask, global).run().paths.size();
        }
      }
      catch (const DistributedFaceTipsError& e)
      {
        out.error = e.what();
      }
      out.outcome = faceTips.outcome();
    });
}

TEST(DistributedFaceTips, ARoundCapStopsEveryRankInTheSameRoundWithTheSameMessage)
{
  // The lower end's chain crosses two owner changes (pieces 0 -> 1 -> 2): one round is too few.
  const std::vector<RankRun> runs = codeOnFourPieces(tube(10.0, 120.0), { 62, 60, 75 }, 1, -1);
  for (const RankRun& r : runs)
  {
    EXPECT_EQ(r.outcome.rounds, 1);
    EXPECT_FALSE(r.outcome.settled);
    EXPECT_NE(r.error.find("the face tips' traces across the pieces did not settle in 1 rounds"),
      std::string::npos)
      << r.error;
    EXPECT_EQ(r.error, runs[0].error);
  }
}

TEST(DistributedFaceTips, ARankWithoutVesselOrWithoutItsCoderStillTakesEveryRound)
{
  // A short tube (z 10-40): piece 3 (held z 69-127) holds no vessel, its coder joins the rounds
  // without clusters; piece 1 joins without coding at all (as a rank whose run stopped before its
  // coder does through DistributedGlobalField::finish). No rank waits for ever: every rank ends
  // in the same round, settled.
  const std::vector<RankRun> runs = codeOnFourPieces(tube(10.0, 40.0), { 60, 61, 25 }, 1000, 1);
  ASSERT_EQ(runs.size(), 4U);
  for (const RankRun& r : runs)
  {
    EXPECT_TRUE(r.outcome.settled) << r.error;
    EXPECT_EQ(r.outcome.rounds, runs[0].outcome.rounds);
  }
  EXPECT_GT(runs[0].paths, 0U);
  EXPECT_EQ(runs[3].paths, 0U);
}

} // namespace
} // namespace vtouch

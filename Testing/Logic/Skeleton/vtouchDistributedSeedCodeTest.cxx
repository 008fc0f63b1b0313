// The SS code across pieces in rounds (vtouch::DistributedSeedCode, issue 19 item 2), ranks as
// threads of one process (InProcessWorld, no MPI): on random trees split in 2, 4 and 8 pieces,
// every rank's SS equals the single run's (SeedCodeStage::propagate on the whole mask) on every
// voxel it holds; the rounds end; the cap stops every rank at the same round; bad input throws on
// every rank. And SeedCodeStage::relax, the round's Dijkstra, against a brute-force Bellman-Ford.
#include "vtouchDistributedSeedCode.h"

#include "vtouchDistributedTestScenes.h"
#include "vtouchEveryRank.h"
#include "vtouchHeldFieldDifference.h"
#include "vtouchPieceGrid.h"
#include "vtouchSeedCodeRun.h"

#include <gtest/gtest.h>

#include <random>
#include <string>

namespace vtouch
{
namespace
{
using test::capsuleMask;
using test::compareWithSingleRun;
using test::Dims;
using test::HeldFieldDifference;
using test::kSplitsIn2And4And8;
using test::layouts;
using test::onEveryRank;
using test::pieceMask;
using test::randomTree;
using test::randomVesselVoxel;
using test::SeedCodeRun;
using test::singleRunField;
using test::VoxelIndex;

/// A U: up a tube in the lower piece, across in the upper piece, and down again into the lower
/// piece far from where it left; the root at the foot of the first leg.
SparseVesselMask uTube(const Dims& d)
{
  return capsuleMask(d,
    { { { 6, 12, 4 }, { 6, 12, 40 }, 2.0 },
      { { 6, 12, 40 }, { 33, 12, 40 }, 2.0 },
      { { 33, 12, 40 }, { 33, 12, 4 }, 2.0 } });
}

struct RankResult
{
  DistributedSeedCode::Outcome outcome;
  HeldFieldDifference held; ///< the held vessel voxels against the single run's field
};

/// Runs the distributed SS code on `pieces` and compares every rank's held voxels.
std::vector<RankResult> runDistributed(const SparseVesselMask& whole,
  const std::vector<float>& single,
  const std::array<double, 3>& spacing_mm,
  const std::vector<PieceLayout>& pieces,
  const VoxelIndex& root,
  int maximumRounds = DistributedSeedCode::kDefaultMaximumRounds)
{
  return onEveryRank<RankResult>(pieces,
    [&](const PieceLayout& l, RankCollectives& c, RankResult& out)
    {
      const SparseVesselMask mask = pieceMask(whole, l);
      DistributedSeedCode code(l, mask, spacing_mm);
      out.outcome = code.run(c, { root }, maximumRounds);
      mask.forEach(
        [&](std::uint64_t lin) { EXPECT_EQ(code.ssAt(lin), code.ss()[mask.rank(lin)]); });
      out.held = compareWithSingleRun(whole, single, l, mask, code.ss(), l.mine());
    });
}

/// The U of the round tests (uTube) in 40 x 24 x 48 voxels of 1 mm, the root at the first
/// leg's foot, the single run's field, and the distributed run on 2 pieces along z (margin 2)
/// stopped after `maximumRounds`.
struct UTubeRun
{
  explicit UTubeRun(int maximumRounds = DistributedSeedCode::kDefaultMaximumRounds)
    : whole(uTube(dims))
    , single(singleRunField(whole, spacing_mm, { root }))
    , results(runDistributed(whole,
        single,
        spacing_mm,
        layouts(dims, { 1, 1, 2 }, 2),
        root,
        maximumRounds))
  {
  }
  const Dims dims{ 40, 24, 48 };
  const std::array<double, 3> spacing_mm{ 1, 1, 1 };
  const VoxelIndex root{ 6, 12, 5 };
  const SparseVesselMask whole;
  const std::vector<float> single;
  const std::vector<RankResult> results;
};

TEST(DistributedSeedCode, EveryRankHoldsTheSingleRunsCodeOnRandomTreesIn2And4And8Pieces)
{
  const Dims dims{ 44, 40, 48 };
  std::mt19937 random(19);
  int multiRound = 0;
  for (unsigned trial = 0; trial < 4; ++trial)
  {
    const SparseVesselMask whole = randomTree(dims, 1000 + trial);
    // Isotropic, then anisotropic voxels (the queue's bucket is the smallest spacing).
    const std::array<double, 3> spacing_mm =
      trial % 2 ? std::array<double, 3>{ 0.9, 0.75, 1.2 } : std::array<double, 3>{ 1, 1, 1 };
    const VoxelIndex root = randomVesselVoxel(whole, random);
    const std::vector<float> single = singleRunField(whole, spacing_mm, { root });
    for (const std::array<int, 3>& counts : kSplitsIn2And4And8)
    {
      const int margin = 1 + static_cast<int>(trial % 2);
      const std::vector<RankResult> results =
        runDistributed(whole, single, spacing_mm, layouts(dims, counts, margin), root);
      const int rounds = results.front().outcome.rounds;
      int reached = 0;
      for (std::size_t r = 0; r < results.size(); ++r)
      {
        SCOPED_TRACE("trial " + std::to_string(trial) + ", " + std::to_string(results.size()) +
                     " pieces, rank " + std::to_string(r));
        EXPECT_TRUE(results[r].outcome.settled) << results[r].outcome.message;
        EXPECT_EQ(results[r].outcome.rounds, rounds); // every rank stops at the same round
        EXPECT_EQ(results[r].held.differing, 0) << results[r].held.firstDiffer;
        reached += results[r].held.reached;
      }
      EXPECT_GT(reached, 200); // the tree is reached, not only the root
      EXPECT_GE(rounds, 2);    // at least one exchange carried distances, one found none
      multiRound += rounds > 2;
    }
  }
  EXPECT_GT(multiRound, 0); // some run needed distances relayed more than once
}

TEST(DistributedSeedCode, APathLeavingThePieceAndComingBackTakesRoundsAndMatches)
{
  for (const RankResult& r : UTubeRun().results)
  {
    EXPECT_TRUE(r.outcome.settled);
    EXPECT_EQ(r.held.differing, 0) << r.held.firstDiffer;
    // Root's piece -> upper piece -> back down -> nothing new: four exchanges.
    EXPECT_EQ(r.outcome.rounds, 4);
    EXPECT_GT(r.outcome.reportedVoxels, 0U);
  }
}

TEST(DistributedSeedCode, TheRoundCapStopsEveryRankTogether)
{
  const std::vector<RankResult> results = UTubeRun(2).results;
  for (const RankResult& r : results)
  {
    EXPECT_FALSE(r.outcome.settled);
    EXPECT_EQ(r.outcome.rounds, 2);
    EXPECT_NE(r.outcome.message.find("did not settle in 2 rounds"), std::string::npos);
  }
  // Stopped early, the lower piece lacks the second leg: the cap did cut the work short.
  EXPECT_GT(results[0].held.differing, 0);
}

TEST(DistributedSeedCode, ARootOutsideTheVesselsThrowsOnEveryRank)
{
  const Dims dims{ 40, 24, 48 };
  const SparseVesselMask whole = uTube(dims);
  const std::vector<std::string> messages = onEveryRank<std::string>(layouts(dims, { 1, 1, 2 }, 1),
    [&](const PieceLayout& l, RankCollectives& c, std::string& message)
    {
      const SparseVesselMask mask = pieceMask(whole, l);
      DistributedSeedCode code(l, mask, { 1, 1, 1 });
      try
      {
        code.run(c, { { 20, 2, 30 } }); // background, in the upper piece
      }
      catch (const std::invalid_argument& e)
      {
        message = e.what();
      }
    });
  for (const std::string& message : messages)
  {
    EXPECT_NE(message.find("(20, 2, 30) is not a vessel voxel"), std::string::npos) << message;
  }
}

TEST(DistributedSeedCode, ALayoutWithoutGhostLayersIsRefused)
{
  const Dims dims{ 40, 24, 48 };
  const SparseVesselMask whole = uTube(dims);
  const PieceLayout l = layouts(dims, { 1, 1, 2 }, 0)[1];
  const SparseVesselMask mask = pieceMask(whole, l);
  EXPECT_THROW(DistributedSeedCode(l, mask, { 1, 1, 1 }), std::invalid_argument);
  EXPECT_THROW(DistributedSeedCode(layouts(dims, { 1, 1, 2 }, 1)[1], mask, { 1, 1, 1 }),
    std::invalid_argument); // a mask of another size
  const PieceLayout good = layouts(dims, { 1, 1, 2 }, 1)[1];
  EXPECT_THROW(
    DistributedSeedCode(good, pieceMask(whole, good), { 1, 0, 1 }), std::invalid_argument);
}

TEST(VoxelCoderGlobalField, TheWholeMasksFieldGivesTheSeededRunsSkeleton)
{
  // Path for path, point for point, junction for junction: the clusters' numbers, which break
  // the ties of the tips' order (tips of one band) and order the loop stage's visits, do not
  // depend on the order the voxels were coded in (the single run's SS queue leaves one bucket's
  // voxels in an order that depends on the whole volume; the global field is sorted by SS, ties
  // by index). Numbered in those orders (before 27 Nov), the trees traced tied tips in another
  // order (bridges a voxel or two apart), and the 512 x 512 x 256 scaling tree on 2 ranks gained
  // a loop.
  const Dims dims{ 44, 40, 48 };
  std::mt19937 random(11);
  std::size_t paths = 0;
  for (unsigned trial = 0; trial < 6; ++trial)
  {
    SCOPED_TRACE("trial " + std::to_string(trial));
    const SparseVesselMask whole = randomTree(dims, 300 + trial);
    const VoxelIndex root = randomVesselVoxel(whole, random);
    const RawSkeleton expected = test::seededSkeleton(whole, { 1, 1, 1 }, root);
    const std::vector<float> ss = singleRunField(whole, { 1, 1, 1 }, { root });
    VoxelCodingParameters global;
    global.globalSs_mm = &ss;
    const RawSkeleton got = VoxelCoder(whole, global).run();
    ASSERT_GT(got.paths.size(), 0U);
    ASSERT_EQ(got.paths.size(), expected.paths.size());
    for (std::size_t p = 0; p < got.paths.size(); ++p)
    {
      EXPECT_EQ(got.paths[p].voxels, expected.paths[p].voxels) << "path " << p;
      EXPECT_EQ(got.paths[p].center_mm, expected.paths[p].center_mm) << "path " << p;
    }
    ASSERT_EQ(got.junctions.size(), expected.junctions.size());
    for (std::size_t k = 0; k < got.junctions.size(); ++k)
    {
      EXPECT_EQ(got.junctions[k].childPath, expected.junctions[k].childPath) << "junction " << k;
      EXPECT_EQ(got.junctions[k].parentPath, expected.junctions[k].parentPath) << "junction " << k;
      EXPECT_EQ(got.junctions[k].parentPoint, expected.junctions[k].parentPoint)
        << "junction " << k;
    }
    paths += got.paths.size();
  }
  EXPECT_GE(paths, 6U * 3U); // trees with branches, not single tubes
  // A field of the wrong size is refused.
  const SparseVesselMask whole = randomTree(dims, 300);
  const std::vector<float> wrong(3, 0.0F);
  VoxelCodingParameters bad;
  bad.globalSs_mm = &wrong;
  EXPECT_THROW(VoxelCoder(whole, bad), std::invalid_argument);
}

TEST(VoxelCoderGlobalField, PiecesCodedWithItHaveTheSingleRunsEndsAndJunctions)
{
  // Each rank codes its piece with the distributed SS field: inside its owned box (3 voxels from
  // the shared faces) it places the single run's free ends and junctions; coded from roots of
  // their own (today), the pieces differ (the test asserts that the trees show it somewhere).
  const Dims dims{ 44, 40, 48 };
  const std::array<double, 3> spacing_mm{ 1, 1, 1 };
  constexpr int kInset = 3;
  std::mt19937 random(23);
  int ownRootsDiffer = 0, globalJunctionsDiffer = 0, boxes = 0;
  for (unsigned trial = 0; trial < 8; ++trial)
  {
    const SparseVesselMask whole = randomTree(dims, 500 + trial);
    const VoxelIndex root = randomVesselVoxel(whole, random);
    const RawSkeleton single = test::seededSkeleton(whole, spacing_mm, root);
    for (const std::array<int, 3>& counts : kSplitsIn2And4And8)
    {
      const auto topology =
        onEveryRank<std::array<std::pair<int, int>, 3>>(layouts(dims, counts, 8),
          [&](const PieceLayout& l, RankCollectives& c, std::array<std::pair<int, int>, 3>& out)
          {
            const SparseVesselMask mask = pieceMask(whole, l);
            DistributedSeedCode code(l, mask, spacing_mm);
            code.run(c, { root });
            out = test::ownedBoxTopology(single, l, mask, code.ss(), spacing_mm, kInset);
          });
      for (std::size_t r = 0; r < topology.size(); ++r)
      {
        SCOPED_TRACE("trial " + std::to_string(trial) + ", " + std::to_string(topology.size()) +
                     " pieces, rank " + std::to_string(r));
        // The free ends (the spurs at the pieces' own roots were the defect) always.
        EXPECT_EQ(topology[r][2].first, topology[r][0].first);
        globalJunctionsDiffer += topology[r][2].second != topology[r][0].second;
        ownRootsDiffer += topology[r][1] != topology[r][0];
        ++boxes;
      }
    }
  }
  std::printf("%d owned boxes: own roots differ in %d, the global field's junctions in %d\n",
    boxes,
    ownRootsDiffer,
    globalJunctionsDiffer);
  EXPECT_GT(ownRootsDiffer, 0);
  EXPECT_LT(globalJunctionsDiffer, ownRootsDiffer);
}

/// Brute-force Bellman-Ford in float from sources with initial distances (the reference of relax).
std::vector<float> bellmanFord(const skeleton::VoxelGrid& grid,
  const std::vector<skeleton::SeedCodeStage::Source>& sources)
{
  std::vector<float> ss(grid.mask.vesselCount(), skeleton::VoxelCodes::kInf);
  for (const auto& s : sources)
  {
    ss[grid.mask.rank(s.lin)] = std::min(ss[grid.mask.rank(s.lin)], s.ss_mm);
  }
  for (bool changed = true; changed;)
  {
    changed = false;
    grid.mask.forEach(
      [&](std::uint64_t lin)
      {
        const float d = ss[grid.mask.rank(lin)];
        if (d == skeleton::VoxelCodes::kInf)
        {
          return;
        }
        grid.forNeighbours(lin,
          [&](std::uint64_t, int n, std::uint32_t ru)
          {
            const float nd = d + grid.offLenF[n];
            if (nd < ss[ru])
            {
              ss[ru] = nd;
              changed = true;
            }
          });
      });
  }
  return ss;
}

TEST(SeedCodeStageRelax, SourcesAtDifferentDistancesGiveTheBellmanFordField)
{
  const Dims dims{ 44, 40, 48 };
  const SparseVesselMask mask = randomTree(dims, 4242);
  SeedCodeRun run(mask, { 0.9, 0.75, 1.2 });
  const skeleton::VoxelGrid& grid = run.grid;
  std::mt19937 random(3);
  std::vector<std::uint64_t> all;
  mask.forEach([&](std::uint64_t lin) { all.push_back(lin); });
  // Two calls, as two rounds: far-apart initial distances (beyond the queue's circular window).
  std::vector<skeleton::SeedCodeStage::Source> first, second;
  for (int q = 0; q < 6; ++q)
  {
    const auto pick = [&] { return static_cast<std::uint32_t>(all[random() % all.size()]); };
    first.push_back({ pick(), static_cast<float>(q * 37.5) });
    second.push_back({ pick(), static_cast<float>(5.0 + q * 11.25) });
  }
  // Each call is Dijkstra: every voxel it lowers is settled once (the sources enter the queue
  // at their own buckets; pushed all at first they would wrap around the circular queue and be
  // settled too early, then again).
  const auto distinct = [](std::vector<std::uint32_t> v)
  {
    std::sort(v.begin(), v.end());
    return static_cast<std::size_t>(std::unique(v.begin(), v.end()) - v.begin());
  };
  std::vector<std::uint32_t> lowered;
  const std::size_t firstSettled = run.stage.relax(first, lowered);
  EXPECT_EQ(firstSettled, distinct(lowered));
  EXPECT_EQ(run.codes.ss, bellmanFord(grid, first));
  EXPECT_GT(firstSettled, 500U);
  lowered.clear();
  const std::size_t secondSettled = run.stage.relax(second, lowered);
  EXPECT_EQ(secondSettled, distinct(lowered));
  EXPECT_GT(secondSettled, 0U);
  std::vector<skeleton::SeedCodeStage::Source> both = first;
  both.insert(both.end(), second.begin(), second.end());
  const std::vector<float> expected = bellmanFord(grid, both);
  EXPECT_EQ(run.codes.ss, expected);
  // `lowered` names exactly the voxels the second call changed.
  const std::vector<float> before = bellmanFord(grid, first);
  std::sort(lowered.begin(), lowered.end());
  lowered.erase(std::unique(lowered.begin(), lowered.end()), lowered.end());
  std::size_t changed = 0;
  for (std::size_t r = 0; r < expected.size(); ++r)
  {
    changed += expected[r] != before[r];
  }
  EXPECT_EQ(lowered.size(), changed);
}

TEST(SeedCodeStageRelax, OneSourceAtZeroEqualsPropagate)
{
  const Dims dims{ 44, 40, 48 };
  const SparseVesselMask mask = randomTree(dims, 99);
  const std::array<double, 3> spacing_mm{ 0.9, 0.75, 1.2 };
  std::mt19937 random(8);
  const VoxelIndex root = randomVesselVoxel(mask, random);
  SeedCodeRun run(mask, spacing_mm);
  std::vector<std::uint32_t> lowered;
  run.stage.relax({ { run.linOf(root), 0.0F } }, lowered);
  EXPECT_EQ(run.codes.ss, singleRunField(mask, spacing_mm, { root }));
}

} // namespace
} // namespace vtouch

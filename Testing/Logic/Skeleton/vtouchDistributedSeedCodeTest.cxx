// The SS code across pieces in rounds (vtouch::DistributedSeedCode, issue 19 item 2), ranks as
// threads of one process (InProcessWorld, no MPI): on random trees split in 2, 4 and 8 pieces,
// every rank's SS equals the single run's (SeedCodeStage::propagate on the whole mask) on every
// voxel it holds; the rounds end; the cap stops every rank at the same round; bad input throws on
// every rank. And SeedCodeStage::relax, the round's Dijkstra, against a brute-force Bellman-Ford.
#include "vtouchDistributedSeedCode.h"
#include "vtouchInProcessCollectives.h"
#include "vtouchPieceGrid.h"
#include "vtouchSkeletonStageTestSupport.h"

#include <gtest/gtest.h>

#include <mutex>
#include <random>
#include <string>

namespace vtouch
{
namespace
{
using skeleton::Point_mm;
using skeleton::test::Dims;
using test::InProcessWorld;
using test::layouts;
using test::pieceMask;

struct Capsule
{
  Point_mm a, b; // voxel indices
  double radius; // voxels
};

/// A random tree of capsules (a trunk, 2-3 levels of branches) and a small blob apart, in the
/// voxel index frame; `seed` makes it.
std::vector<Capsule> randomTree(const Dims& d, unsigned seed)
{
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const auto inside = [&](double margin)
  {
    return Point_mm{ margin + unit(random) * (static_cast<double>(d[0]) - 2 * margin),
      margin + unit(random) * (static_cast<double>(d[1]) - 2 * margin),
      margin + unit(random) * (static_cast<double>(d[2]) - 2 * margin) };
  };
  std::vector<Capsule> tree{ { inside(4), inside(4), 1.5 + unit(random) } };
  for (int level = 0; level < 3; ++level)
  {
    const std::size_t parents = tree.size();
    for (std::size_t p = 0; p < parents; ++p)
    {
      if (unit(random) < 0.35)
      {
        continue;
      }
      const Capsule c = tree[p];
      const double t = 0.2 + 0.6 * unit(random);
      const Point_mm from{ c.a[0] + t * (c.b[0] - c.a[0]),
        c.a[1] + t * (c.b[1] - c.a[1]),
        c.a[2] + t * (c.b[2] - c.a[2]) };
      tree.push_back({ from, inside(3), std::max(1.0, c.radius * (0.6 + 0.3 * unit(random))) });
    }
  }
  tree.push_back({ { 2, 2, 2 }, { 2, 2, 2 }, 1.2 }); // a blob apart (or touching: either way)
  return tree;
}

SparseVesselMask maskOf(const Dims& d, const std::vector<Capsule>& tree)
{
  return skeleton::test::makeMask(d,
    [&](const Point_mm& p)
    {
      for (const Capsule& c : tree)
      {
        const bool point = c.a == c.b;
        if ((point ? skeleton::distance(p, c.a) : skeleton::test::distanceToSegment(p, c.a, c.b)) <=
            c.radius)
        {
          return true;
        }
      }
      return false;
    });
}

/// The single run's SS code from `root` on the whole mask (indexed by rank), as VoxelCoder runs it.
std::vector<float> singleRun(const SparseVesselMask& mask,
  const std::array<double, 3>& spacing_mm,
  const std::array<std::int64_t, 3>& root)
{
  skeleton::VoxelGrid grid(mask, spacing_mm, 0.0);
  skeleton::VoxelCodes codes;
  codes.ss.assign(mask.vesselCount(), skeleton::VoxelCodes::kInf);
  codes.flags.assign(mask.vesselCount(), 0);
  const std::function<bool(double)> none;
  skeleton::RunMeter meter(none);
  skeleton::SeedCodeStage stage(grid, meter, codes, 0.0);
  stage.propagate({ static_cast<std::uint32_t>(grid.linOf(root[0], root[1], root[2])) });
  return codes.ss;
}

/// A vessel voxel of `mask` picked by `random`.
std::array<std::int64_t, 3> randomVesselVoxel(const SparseVesselMask& mask, std::mt19937& random)
{
  std::vector<std::uint64_t> all;
  mask.forEach([&](std::uint64_t lin) { all.push_back(lin); });
  const std::uint64_t lin =
    all[std::uniform_int_distribution<std::size_t>(0, all.size() - 1)(random)];
  const Dims& d = mask.dims();
  return { static_cast<std::int64_t>(lin) % d[0],
    (static_cast<std::int64_t>(lin) / d[0]) % d[1],
    static_cast<std::int64_t>(lin) / (d[0] * d[1]) };
}

struct RankResult
{
  DistributedSeedCode::Outcome outcome;
  int differing = 0;       ///< held vessel voxels whose SS differs from the single run's
  int reached = 0;         ///< held vessel voxels with a finite SS
  std::string firstDiffer; ///< the first of them, for the message
};

/// Runs the distributed SS code on `pieces` and compares every rank's held voxels.
std::vector<RankResult> runDistributed(const SparseVesselMask& whole,
  const std::vector<float>& single,
  const std::array<double, 3>& spacing_mm,
  const std::vector<PieceLayout>& pieces,
  const std::array<std::int64_t, 3>& root,
  int maximumRounds = DistributedSeedCode::kDefaultMaximumRounds)
{
  const int ranks = static_cast<int>(pieces.size());
  std::vector<RankResult> results(static_cast<std::size_t>(ranks));
  InProcessWorld world(ranks);
  world.run(
    [&](int r, RankCollectives& c)
    {
      const PieceLayout& l = pieces[static_cast<std::size_t>(r)];
      const SparseVesselMask mask = pieceMask(whole, l);
      DistributedSeedCode code(l, mask, spacing_mm);
      RankResult& out = results[static_cast<std::size_t>(r)];
      out.outcome = code.run(c, { root }, maximumRounds);
      const Dims d = l.pieceDims();
      mask.forEach(
        [&](std::uint64_t lin)
        {
          const auto li = static_cast<std::int64_t>(lin);
          const std::array<std::int64_t, 3> w =
            l.toWhole({ li % d[0], (li / d[0]) % d[1], li / (d[0] * d[1]) });
          const float expected = single[whole.rank(static_cast<std::uint64_t>(l.wholeLinear(w)))];
          const float got = code.ssAt(lin);
          EXPECT_EQ(got, code.ss()[mask.rank(lin)]);
          out.reached += got != skeleton::VoxelCodes::kInf;
          if (got != expected)
          {
            if (out.differing++ == 0)
            {
              out.firstDiffer = "(" + std::to_string(w[0]) + "," + std::to_string(w[1]) + "," +
                                std::to_string(w[2]) + "): " + std::to_string(got) + " vs " +
                                std::to_string(expected);
            }
          }
        });
    });
  return results;
}

TEST(DistributedSeedCode, EveryRankHoldsTheSingleRunsCodeOnRandomTreesIn2And4And8Pieces)
{
  const Dims dims{ 44, 40, 48 };
  std::mt19937 random(19);
  int multiRound = 0;
  for (unsigned trial = 0; trial < 4; ++trial)
  {
    const SparseVesselMask whole = maskOf(dims, randomTree(dims, 1000 + trial));
    // Isotropic, then anisotropic voxels (the queue's bucket is the smallest spacing).
    const std::array<double, 3> spacing_mm =
      trial % 2 ? std::array<double, 3>{ 0.9, 0.75, 1.2 } : std::array<double, 3>{ 1, 1, 1 };
    const std::array<std::int64_t, 3> root = randomVesselVoxel(whole, random);
    const std::vector<float> single = singleRun(whole, spacing_mm, root);
    for (const std::array<int, 3>& counts : { std::array<int, 3>{ 1, 1, 2 },
           std::array<int, 3>{ 1, 2, 2 },
           std::array<int, 3>{ 2, 2, 2 } })
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
        EXPECT_EQ(results[r].differing, 0) << results[r].firstDiffer;
        reached += results[r].reached;
      }
      EXPECT_GT(reached, 200); // the tree is reached, not only the root
      EXPECT_GE(rounds, 2);    // at least one exchange carried distances, one found none
      multiRound += rounds > 2;
    }
  }
  EXPECT_GT(multiRound, 0); // some run needed distances relayed more than once
}

/// A U: up a tube in the lower piece, across in the upper piece, and down again into the lower
/// piece far from where it left; the root at the foot of the first leg.
SparseVesselMask uTube(const Dims& d)
{
  return maskOf(d,
    { { { 6, 12, 4 }, { 6, 12, 40 }, 2.0 },
      { { 6, 12, 40 }, { 33, 12, 40 }, 2.0 },
      { { 33, 12, 40 }, { 33, 12, 4 }, 2.0 } });
}

TEST(DistributedSeedCode, APathLeavingThePieceAndComingBackTakesRoundsAndMatches)
{
  const Dims dims{ 40, 24, 48 };
  const SparseVesselMask whole = uTube(dims);
  const std::array<double, 3> spacing_mm{ 1, 1, 1 };
  const std::array<std::int64_t, 3> root{ 6, 12, 5 };
  const std::vector<float> single = singleRun(whole, spacing_mm, root);
  const std::vector<RankResult> results =
    runDistributed(whole, single, spacing_mm, layouts(dims, { 1, 1, 2 }, 2), root);
  for (const RankResult& r : results)
  {
    EXPECT_TRUE(r.outcome.settled);
    EXPECT_EQ(r.differing, 0) << r.firstDiffer;
    // Root's piece -> upper piece -> back down -> nothing new: four exchanges.
    EXPECT_EQ(r.outcome.rounds, 4);
    EXPECT_GT(r.outcome.reportedVoxels, 0U);
  }
}

TEST(DistributedSeedCode, TheRoundCapStopsEveryRankTogether)
{
  const Dims dims{ 40, 24, 48 };
  const SparseVesselMask whole = uTube(dims);
  const std::array<double, 3> spacing_mm{ 1, 1, 1 };
  const std::array<std::int64_t, 3> root{ 6, 12, 5 };
  const std::vector<float> single = singleRun(whole, spacing_mm, root);
  const std::vector<RankResult> results =
    runDistributed(whole, single, spacing_mm, layouts(dims, { 1, 1, 2 }, 2), root, 2);
  for (const RankResult& r : results)
  {
    EXPECT_FALSE(r.outcome.settled);
    EXPECT_EQ(r.outcome.rounds, 2);
    EXPECT_NE(r.outcome.message.find("did not settle in 2 rounds"), std::string::npos);
  }
  // Stopped early, the lower piece lacks the second leg: the cap did cut the work short.
  EXPECT_GT(results[0].differing, 0);
}

TEST(DistributedSeedCode, ARootOutsideTheVesselsThrowsOnEveryRank)
{
  const Dims dims{ 40, 24, 48 };
  const SparseVesselMask whole = uTube(dims);
  const std::vector<PieceLayout> pieces = layouts(dims, { 1, 1, 2 }, 1);
  std::mutex m;
  std::vector<std::string> messages;
  InProcessWorld world(2);
  world.run(
    [&](int r, RankCollectives& c)
    {
      const PieceLayout& l = pieces[static_cast<std::size_t>(r)];
      const SparseVesselMask mask = pieceMask(whole, l);
      DistributedSeedCode code(l, mask, { 1, 1, 1 });
      try
      {
        code.run(c, { { 20, 2, 30 } }); // background, in the upper piece
      }
      catch (const std::invalid_argument& e)
      {
        const std::lock_guard<std::mutex> lock(m);
        messages.emplace_back(e.what());
      }
    });
  ASSERT_EQ(messages.size(), 2U);
  EXPECT_NE(messages[0].find("(20, 2, 30) is not a vessel voxel"), std::string::npos);
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
  const Dims dims{ 44, 40, 48 };
  std::mt19937 random(11);
  for (unsigned trial = 0; trial < 3; ++trial)
  {
    const SparseVesselMask whole = maskOf(dims, randomTree(dims, 300 + trial));
    const std::array<std::int64_t, 3> root = randomVesselVoxel(whole, random);
    VoxelCodingParameters seeded;
    seeded.hasSeed = true;
    seeded.seedIndex = root;
    const RawSkeleton expected = VoxelCoder(whole, seeded).run();
    const std::vector<float> ss = singleRun(whole, seeded.spacing_mm, root);
    VoxelCodingParameters global;
    global.globalSs_mm = &ss;
    const RawSkeleton got = VoxelCoder(whole, global).run();
    // The same tree; the paths may come in another order (the tips' ties are broken in SS
    // order, which the sorted field breaks by index, the single run's queue by its pops).
    const auto voxelsOf = [](const RawSkeleton& k)
    {
      std::vector<std::array<std::int64_t, 3>> v;
      for (const RawSkeletonPath& p : k.paths)
      {
        v.insert(v.end(), p.voxels.begin(), p.voxels.end());
      }
      std::sort(v.begin(), v.end());
      v.erase(std::unique(v.begin(), v.end()), v.end());
      return v;
    };
    ASSERT_GT(got.paths.size(), 0U);
    EXPECT_EQ(got.paths.size(), expected.paths.size());
    EXPECT_EQ(got.junctions.size(), expected.junctions.size());
    // Where a branch joins, the bridge to its parent may differ by a voxel or two: the parent is
    // the branch traced first.
    const auto farthestFrom = [](const std::vector<std::array<std::int64_t, 3>>& a,
                                const std::vector<std::array<std::int64_t, 3>>& b)
    {
      double worst = 0.0;
      for (const auto& p : a)
      {
        double best = 1e300;
        for (const auto& q : b)
        {
          best = std::min(best,
            std::sqrt(double((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) +
                             (p[2] - q[2]) * (p[2] - q[2]))));
        }
        worst = std::max(worst, best);
      }
      return worst;
    };
    const double hausdorff = std::max(farthestFrom(voxelsOf(got), voxelsOf(expected)),
      farthestFrom(voxelsOf(expected), voxelsOf(got)));
    std::printf("trial %u: %zu paths, skeleton voxels %.2f voxel apart at most\n",
      trial,
      got.paths.size(),
      hausdorff);
    EXPECT_LE(hausdorff, 2.0);
  }
  // A field of the wrong size is refused.
  const SparseVesselMask whole = maskOf(dims, randomTree(dims, 300));
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
    const SparseVesselMask whole = maskOf(dims, randomTree(dims, 500 + trial));
    const std::array<std::int64_t, 3> root = randomVesselVoxel(whole, random);
    VoxelCodingParameters seeded;
    seeded.hasSeed = true;
    seeded.seedIndex = root;
    const RawSkeleton single = VoxelCoder(whole, seeded).run();
    for (const std::array<int, 3>& counts : { std::array<int, 3>{ 1, 1, 2 },
           std::array<int, 3>{ 1, 2, 2 },
           std::array<int, 3>{ 2, 2, 2 } })
    {
      const std::vector<PieceLayout> pieces = layouts(dims, counts, 8);
      std::vector<std::array<std::pair<int, int>, 3>> topology(pieces.size());
      InProcessWorld world(static_cast<int>(pieces.size()));
      world.run(
        [&](int r, RankCollectives& c)
        {
          const PieceLayout& l = pieces[static_cast<std::size_t>(r)];
          const SparseVesselMask mask = pieceMask(whole, l);
          DistributedSeedCode code(l, mask, spacing_mm);
          code.run(c, { root });
          VoxelCodingParameters own;
          VoxelCodingParameters global;
          global.globalSs_mm = &code.ss();
          const VoxelBox& owned = l.owned[static_cast<std::size_t>(r)];
          topology[static_cast<std::size_t>(r)] = { test::endsAndJunctionsIn(
                                                      single, { 0, 0, 0 }, owned, dims, kInset),
            test::endsAndJunctionsIn(VoxelCoder(mask, own).run(), l.mine().lo, owned, dims, kInset),
            test::endsAndJunctionsIn(
              VoxelCoder(mask, global).run(), l.mine().lo, owned, dims, kInset) };
        });
      for (std::size_t r = 0; r < topology.size(); ++r)
      {
        SCOPED_TRACE("trial " + std::to_string(trial) + ", " + std::to_string(pieces.size()) +
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
  const SparseVesselMask mask = maskOf(dims, randomTree(dims, 4242));
  const std::array<double, 3> spacing_mm{ 0.9, 0.75, 1.2 };
  skeleton::VoxelGrid grid(mask, spacing_mm, 0.0);
  skeleton::VoxelCodes codes;
  codes.ss.assign(mask.vesselCount(), skeleton::VoxelCodes::kInf);
  codes.flags.assign(mask.vesselCount(), 0);
  const std::function<bool(double)> none;
  skeleton::RunMeter meter(none);
  skeleton::SeedCodeStage stage(grid, meter, codes, 0.0);
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
  const std::size_t firstSettled = stage.relax(first, lowered);
  EXPECT_EQ(firstSettled, distinct(lowered));
  EXPECT_EQ(codes.ss, bellmanFord(grid, first));
  EXPECT_GT(firstSettled, 500U);
  lowered.clear();
  const std::size_t secondSettled = stage.relax(second, lowered);
  EXPECT_EQ(secondSettled, distinct(lowered));
  EXPECT_GT(secondSettled, 0U);
  std::vector<skeleton::SeedCodeStage::Source> both = first;
  both.insert(both.end(), second.begin(), second.end());
  const std::vector<float> expected = bellmanFord(grid, both);
  EXPECT_EQ(codes.ss, expected);
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
  const SparseVesselMask mask = maskOf(dims, randomTree(dims, 99));
  const std::array<double, 3> spacing_mm{ 0.9, 0.75, 1.2 };
  std::mt19937 random(8);
  const std::array<std::int64_t, 3> root = randomVesselVoxel(mask, random);
  skeleton::VoxelGrid grid(mask, spacing_mm, 0.0);
  skeleton::VoxelCodes codes;
  codes.ss.assign(mask.vesselCount(), skeleton::VoxelCodes::kInf);
  codes.flags.assign(mask.vesselCount(), 0);
  const std::function<bool(double)> none;
  skeleton::RunMeter meter(none);
  skeleton::SeedCodeStage stage(grid, meter, codes, 0.0);
  std::vector<std::uint32_t> lowered;
  stage.relax(
    { { static_cast<std::uint32_t>(grid.linOf(root[0], root[1], root[2])), 0.0F } }, lowered);
  EXPECT_EQ(codes.ss, singleRun(mask, spacing_mm, root));
}

} // namespace
} // namespace vtouch

// The automatic root across pieces (vtouch::DistributedRootChoice, issue 19 item 2), ranks as
// threads of one process (InProcessWorld, no MPI): on random trees split in 2, 4 and 8 pieces,
// small ones (the exact double propagation) and ones of 2^17 vessel voxels or more (the
// exploration on 2x2x2 blocks), every rank gets the single run's root (VoxelCoder's
// RawSkeleton::roots, the extremity before the move to the thickest end) and the single run's SS
// field from it on every voxel it holds; bad input and round caps give every rank the same
// message. And the far-voxel rule the single run now shares (SeedCodeStage::farVoxel).
#include "vtouchDistributedRootChoice.h"
#include "vtouchDistributedTestScenes.h"
#include "vtouchInProcessCollectives.h"
#include "vtouchPieceGrid.h"
#include "vtouchSkeletonStageTestSupport.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <string>
#include <tuple>

namespace vtouch
{
namespace
{
using skeleton::Point_mm;
using skeleton::test::Dims;
using test::InProcessWorld;
using test::layouts;
using test::pieceMask;
using test::randomTree; // the trees this test was measured on (vtouchDistributedTestScenes)
using Index = std::array<std::int64_t, 3>;

/// The single run: VoxelCoder without a seed, its components' final roots (the thickest end's
/// when moved, else the extremity), first roots (the extremity, sorted) and moves, and the SS
/// field from the final roots (SeedCodeStage::propagate on the whole mask, indexed by rank).
struct SingleRun
{
  std::vector<std::vector<Index>> roots;
  std::vector<std::vector<Index>> extremities;
  std::vector<bool> moved;
  std::vector<float> ss;
};

SingleRun singleRun(const SparseVesselMask& mask,
  const std::array<double, 3>& spacing_mm,
  double clusterWidth_mm = 0.0)
{
  VoxelCodingParameters p;
  p.spacing_mm = spacing_mm;
  p.clusterWidth_mm = clusterWidth_mm;
  const RawSkeleton skeleton = VoxelCoder(mask, p).run();
  SingleRun out;
  skeleton::VoxelGrid grid(mask, spacing_mm, 0.0);
  std::vector<std::uint32_t> sources;
  for (const RawComponentRoot& c : skeleton.roots)
  {
    std::vector<Index> r = c.extremity;
    std::sort(r.begin(),
      r.end(),
      [](const Index& a, const Index& b)
      { return std::make_tuple(a[2], a[1], a[0]) < std::make_tuple(b[2], b[1], b[0]); });
    out.extremities.push_back(r);
    out.moved.push_back(c.moved);
    if (c.moved)
    {
      r = { c.thickest };
    }
    out.roots.push_back(r);
    for (const Index& v : r)
    {
      sources.push_back(static_cast<std::uint32_t>(grid.linOf(v[0], v[1], v[2])));
    }
  }
  skeleton::VoxelCodes codes;
  codes.ss.assign(mask.vesselCount(), skeleton::VoxelCodes::kInf);
  codes.flags.assign(mask.vesselCount(), 0);
  const std::function<bool(double)> none;
  skeleton::RunMeter meter(none);
  skeleton::SeedCodeStage(grid, meter, codes, 0.0).propagate(sources);
  out.ss = codes.ss;
  return out;
}

struct RankResult
{
  DistributedRootChoice::Result result;
  int differing = 0; ///< held vessel voxels whose SS differs from the single run's
  std::string firstDiffer;
};

std::vector<RankResult> runDistributed(const SparseVesselMask& whole,
  const SingleRun* single,
  const std::array<double, 3>& spacing_mm,
  const std::vector<PieceLayout>& pieces,
  const DistributedRootChoice::Parameters& parameters = {},
  int wrongMaskRank = -1)
{
  std::vector<RankResult> results(pieces.size());
  InProcessWorld world(static_cast<int>(pieces.size()));
  world.run(
    [&](int r, RankCollectives& c)
    {
      const PieceLayout& l = pieces[static_cast<std::size_t>(r)];
      const SparseVesselMask mask =
        r == wrongMaskRank ? SparseVesselMask({ 3, 3, 3 }) : pieceMask(whole, l);
      RankResult& out = results[static_cast<std::size_t>(r)];
      out.result = DistributedRootChoice::choose(l, mask, spacing_mm, c, parameters);
      if (!single || !out.result.ok)
      {
        return;
      }
      const Dims d = l.pieceDims();
      mask.forEach(
        [&](std::uint64_t lin)
        {
          const auto li = static_cast<std::int64_t>(lin);
          const Index w = l.toWhole({ li % d[0], (li / d[0]) % d[1], li / (d[0] * d[1]) });
          const float expected =
            single->ss[whole.rank(static_cast<std::uint64_t>(l.wholeLinear(w)))];
          const float got = out.result.ss_mm[mask.rank(lin)];
          if (got != expected && out.differing++ == 0)
          {
            out.firstDiffer = "(" + std::to_string(w[0]) + "," + std::to_string(w[1]) + "," +
                              std::to_string(w[2]) + "): " + std::to_string(got) + " vs " +
                              std::to_string(expected);
          }
        });
    });
  return results;
}

/// What rank 0 saw: components found on blocks, roots moved to the thickest end.
struct Seen
{
  int fromBlocks = 0;
  int moved = 0;
  int kept = 0;
  Seen& operator+=(const Seen& o)
  {
    fromBlocks += o.fromBlocks;
    moved += o.moved;
    kept += o.kept;
    return *this;
  }
};

/// Every rank's roots (final and first), moves and field are the single run's.
Seen expectTheSingleRuns(const std::vector<RankResult>& results, const SingleRun& single)
{
  Seen seen;
  for (std::size_t r = 0; r < results.size(); ++r)
  {
    SCOPED_TRACE("rank " + std::to_string(r));
    const DistributedRootChoice::Result& got = results[r].result;
    EXPECT_TRUE(got.ok) << got.message;
    EXPECT_EQ(got.components.size(), single.roots.size());
    for (std::size_t c = 0; c < std::min(got.components.size(), single.roots.size()); ++c)
    {
      EXPECT_EQ(got.components[c].roots_Whole, single.roots[c]) << "component " << c;
      EXPECT_EQ(got.components[c].extremity_Whole, single.extremities[c]) << "component " << c;
      EXPECT_EQ(got.components[c].moved, single.moved[c]) << "component " << c;
      if (r == 0)
      {
        seen.fromBlocks += got.components[c].fromBlocks;
        seen.moved += got.components[c].moved;
        seen.kept += !got.components[c].moved;
      }
    }
    EXPECT_EQ(results[r].differing, 0) << results[r].firstDiffer;
    EXPECT_EQ(got.rounds, results.front().result.rounds); // every rank took every step
    EXPECT_EQ(got.moveExchanges, results.front().result.moveExchanges);
  }
  return seen;
}

const auto& kSplits = test::kSplitsIn2And4And8;

TEST(DistributedRootChoice, EveryRankGetsTheSingleRunsRootOnSmallRandomTreesIn2And4And8Pieces)
{
  const Dims dims{ 44, 40, 48 };
  Seen seen;
  for (unsigned trial = 0; trial < 6; ++trial)
  {
    const SparseVesselMask whole = randomTree(dims, 1900 + trial, 2.0);
    const std::array<double, 3> spacing_mm =
      trial % 2 ? std::array<double, 3>{ 0.9, 0.75, 1.2 } : std::array<double, 3>{ 1, 1, 1 };
    const SingleRun single = singleRun(whole, spacing_mm);
    ASSERT_FALSE(single.roots.empty());
    for (const std::array<int, 3>& counts : kSplits)
    {
      SCOPED_TRACE("trial " + std::to_string(trial) + ", split " + std::to_string(counts[0]) +
                   std::to_string(counts[1]) + std::to_string(counts[2]));
      const int margin = 1 + static_cast<int>(trial % 3);
      seen += expectTheSingleRuns(
        runDistributed(whole, &single, spacing_mm, layouts(dims, counts, margin)), single);
    }
  }
  // Neither half of the rule was vacuous: some roots moved to the thickest end, some stayed.
  EXPECT_GT(seen.moved, 0);
  EXPECT_GT(seen.kept, 0);
}

TEST(DistributedRootChoice, EveryRankGetsTheSingleRunsRootOnLargeTreesExploredOnBlocks)
{
  const Dims dims{ 120, 112, 128 };
  Seen seen;
  unsigned seed = 1950;
  for (unsigned trial = 0; trial < 3; ++trial)
  {
    // The next seeded tree of 2^17 vessel voxels or more (the exploration on blocks runs).
    SparseVesselMask whole = randomTree(dims, seed++, 14.0);
    for (int attempt = 0;
         attempt < 20 && whole.vesselCount() < skeleton::SeedCodeStage::kCoarseFromVoxels;
         ++attempt)
    {
      whole = randomTree(dims, seed++, 14.0);
    }
    ASSERT_GE(whole.vesselCount(), skeleton::SeedCodeStage::kCoarseFromVoxels);
    const std::array<double, 3> spacing_mm =
      trial % 2 ? std::array<double, 3>{ 0.9, 0.75, 1.2 } : std::array<double, 3>{ 1, 1, 1 };
    const SingleRun single = singleRun(whole, spacing_mm);
    ASSERT_FALSE(single.roots.empty());
    for (const std::array<int, 3>& counts : kSplits)
    {
      SCOPED_TRACE("trial " + std::to_string(trial) + ", split " + std::to_string(counts[0]) +
                   std::to_string(counts[1]) + std::to_string(counts[2]));
      const int margin = 2 + 6 * static_cast<int>(trial % 2);
      seen += expectTheSingleRuns(
        runDistributed(whole, &single, spacing_mm, layouts(dims, counts, margin)), single);
    }
  }
  EXPECT_GT(seen.fromBlocks, 0); // the exploration on blocks ran and its root was kept
  EXPECT_GT(seen.moved, 0);      // and roots found on blocks moved to the thickest end
}

TEST(DistributedRootChoice, EveryComponentIsRootedAsTheSingleRunRootsItAmongSpecks)
{
  // Two vessels apart (a straight tube and a bent one, both across the pieces' faces) and 40
  // specks of one voxel scattered (seeded): the single run codes the two in scan order and skips
  // the specks; so must every rank, whatever the split.
  const Dims dims{ 40, 36, 44 };
  std::mt19937 random(1919);
  std::vector<Point_mm> specks;
  for (int s = 0; s < 40; ++s)
  {
    specks.push_back({ static_cast<double>(random() % 40),
      static_cast<double>(random() % 36),
      static_cast<double>(random() % 44) });
  }
  const SparseVesselMask mask = skeleton::test::makeMask(dims,
    [&](const Point_mm& p)
    {
      using skeleton::test::distanceToSegment;
      if (distanceToSegment(p, { 8, 8, 3 }, { 8, 30, 40 }) <= 2.5 ||
          std::min(distanceToSegment(p, { 34, 4, 5 }, { 26, 20, 22 }),
            distanceToSegment(p, { 26, 20, 22 }, { 33, 30, 40 })) <= 2.0)
      {
        return true;
      }
      return std::find(specks.begin(), specks.end(), p) != specks.end();
    });
  for (const std::array<double, 3>& spacing_mm :
    { std::array<double, 3>{ 1, 1, 1 }, std::array<double, 3>{ 0.8, 1.1, 0.95 } })
  {
    const SingleRun single = singleRun(mask, spacing_mm);
    ASSERT_EQ(single.roots.size(), 2U);
    for (const std::array<int, 3>& counts : kSplits)
    {
      SCOPED_TRACE("split " + std::to_string(counts[0]) + std::to_string(counts[1]) +
                   std::to_string(counts[2]) + ", spacing x " + std::to_string(spacing_mm[0]));
      const std::vector<RankResult> results =
        runDistributed(mask, &single, spacing_mm, layouts(dims, counts, 2));
      expectTheSingleRuns(results, single);
      EXPECT_GT(results.front().result.propagations, 30); // the specks were explored, one each
    }
  }
}

TEST(DistributedRootChoice, AnEndCapLeavingItsPieceAndComingBackIsGrownInRounds)
{
  // A tube up the left piece, across the face x = 15 into the right one, up, and back into the
  // left piece (its far end). With 40 mm bands the far end cap runs back along the whole hook:
  // its first leg in the left piece is joined to the far end only through the right piece, so
  // the left rank learns of it from the right rank's report, a round later.
  const Dims dims{ 31, 12, 40 };
  const std::vector<std::pair<Point_mm, Point_mm>> legs{ { { 5, 6, 2 }, { 5, 6, 30 } },
    { { 5, 6, 30 }, { 25, 6, 30 } },
    { { 25, 6, 30 }, { 25, 6, 34 } },
    { { 25, 6, 34 }, { 8, 6, 34 } } };
  const SparseVesselMask hook = skeleton::test::makeMask(dims,
    [&](const Point_mm& p)
    {
      double d = 1e9;
      for (const auto& leg : legs)
      {
        d = std::min(d, skeleton::test::distanceToSegment(p, leg.first, leg.second));
      }
      return d <= 1.5;
    });
  DistributedRootChoice::Parameters p;
  p.clusterWidth_mm = 40.0;
  const SingleRun single = singleRun(hook, { 1, 1, 1 }, p.clusterWidth_mm);
  ASSERT_EQ(single.roots.size(), 1U);
  const std::vector<RankResult> results =
    runDistributed(hook, &single, { 1, 1, 1 }, layouts(dims, { 2, 1, 1 }, 1), p);
  expectTheSingleRuns(results, single);
}

TEST(DistributedRootChoice, AMarginTooNarrowForTheBlocksIsRefusedOnEveryRank)
{
  const Dims dims{ 120, 112, 128 };
  SparseVesselMask whole = randomTree(dims, 1950, 14.0);
  for (unsigned seed = 1951;
       whole.vesselCount() < skeleton::SeedCodeStage::kCoarseFromVoxels && seed < 1970;
       ++seed)
  {
    whole = randomTree(dims, seed, 14.0);
  }
  ASSERT_GE(whole.vesselCount(), skeleton::SeedCodeStage::kCoarseFromVoxels);
  const std::vector<RankResult> results =
    runDistributed(whole, nullptr, { 1, 1, 1 }, layouts(dims, { 1, 2, 2 }, 1));
  for (const RankResult& r : results)
  {
    EXPECT_FALSE(r.result.ok);
    EXPECT_NE(r.result.message.find("ghost margin of at least 2"), std::string::npos)
      << r.result.message;
    EXPECT_EQ(r.result.message, results.front().result.message);
  }
}

TEST(DistributedRootChoice, AWrongMaskOnOneRankGivesEveryRankTheSameMessage)
{
  const Dims dims{ 44, 40, 48 };
  const SparseVesselMask whole = randomTree(dims, 1900, 2.0);
  const std::vector<RankResult> results =
    runDistributed(whole, nullptr, { 1, 1, 1 }, layouts(dims, { 2, 2, 1 }, 2), {}, 2);
  for (const RankResult& r : results)
  {
    EXPECT_FALSE(r.result.ok);
    EXPECT_NE(r.result.message.find("size is not the held box's"), std::string::npos)
      << r.result.message;
    EXPECT_NE(r.result.message.find("(rank 2)"), std::string::npos) << r.result.message;
    EXPECT_TRUE(r.result.components.empty());
  }
}

TEST(DistributedRootChoice, TheRoundCapStopsEveryRankWithTheSameMessage)
{
  const Dims dims{ 44, 40, 48 };
  const SparseVesselMask whole = randomTree(dims, 1901, 2.0);
  DistributedRootChoice::Parameters p;
  p.maximumRounds = 1; // a tree crossing the faces needs more than one exchange
  const std::vector<RankResult> results =
    runDistributed(whole, nullptr, { 1, 1, 1 }, layouts(dims, { 2, 2, 2 }, 2), p);
  for (const RankResult& r : results)
  {
    EXPECT_FALSE(r.result.ok);
    EXPECT_NE(r.result.message.find("did not settle in 1 rounds"), std::string::npos)
      << r.result.message;
    EXPECT_EQ(r.result.message, results.front().result.message);
  }
}

/// The SS code of `mask` (1 mm voxels) from `root`, and the stage that computed it.
struct RodCode
{
  explicit RodCode(const SparseVesselMask& m, const Index& root)
    : grid(m, { 1, 1, 1 }, 0.0)
    , meter(none)
    , stage(grid, meter, codes, 0.0)
  {
    codes.ss.assign(m.vesselCount(), skeleton::VoxelCodes::kInf);
    codes.flags.assign(m.vesselCount(), 0);
    stage.propagate({ static_cast<std::uint32_t>(grid.linOf(root[0], root[1], root[2])) });
  }
  float ssAt(const Index& v) const
  {
    return codes.ss[grid.mask.rank(grid.linOf(v[0], v[1], v[2]))];
  }
  skeleton::VoxelGrid grid;
  skeleton::VoxelCodes codes;
  std::function<bool(double)> none;
  skeleton::RunMeter meter;
  skeleton::SeedCodeStage stage;
};

TEST(SeedCodeStageFarVoxel, IsTheLargestIndexInTheLastBucket)
{
  // A rod one voxel thick along x, x = 1 .. 20, with one diagonal step at its left end to
  // (0, 0, 1), coded from (10, 1, 1): the left end lies 9 + sqrt(2) = 10.41 mm away, the right
  // end 10 mm, both in the last 1 mm bucket. The far end is the right one (the larger index),
  // not the largest code.
  const SparseVesselMask rod = skeleton::test::makeMask({ 21, 3, 3 },
    [](const Point_mm& p)
    {
      return (p[1] == 1.0 && p[2] == 1.0 && p[0] >= 1.0) ||
             (p[0] == 0.0 && p[1] == 0.0 && p[2] == 1.0);
    });
  RodCode code(rod, { 10, 1, 1 });
  ASSERT_GT(code.ssAt({ 0, 0, 1 }), code.ssAt({ 20, 1, 1 }));
  EXPECT_EQ(code.stage.farVoxel(), code.grid.linOf(20, 1, 1));
  // The end cap: the voxels within one band (1 mm) of the far one, (19..20, 1, 1); the voxel at
  // its centroid (x = 19.5, rounded away from zero).
  const std::vector<std::uint32_t> cap = code.stage.extremityRegion();
  ASSERT_EQ(cap.size(), 1U);
  EXPECT_EQ(cap.front(), code.grid.linOf(20, 1, 1));
}

TEST(SeedCodeStageFarVoxel, IsNotTheLastVoxelTheQueuePopped)
{
  // A rod x = 0 .. 19 ending in a 3 x 3 plate at x = 20, coded from (0, 1, 1): the plate's nine
  // voxels (20 to 20.73 mm) share the last bucket; the queue pops them in the order they were
  // pushed from (19, 1, 1), last in first out, not by index. The far voxel is the plate's last
  // in scan order, (20, 2, 2); the cap (the plate) is centred on the rod.
  const SparseVesselMask rod = skeleton::test::makeMask(
    { 21, 3, 3 }, [](const Point_mm& p) { return (p[1] == 1.0 && p[2] == 1.0) || p[0] == 20.0; });
  RodCode code(rod, { 0, 1, 1 });
  EXPECT_NE(code.codes.order.back(), code.grid.linOf(20, 2, 2)); // the rule is not the queue's
  EXPECT_EQ(code.stage.farVoxel(), code.grid.linOf(20, 2, 2));
  const std::vector<std::uint32_t> cap = code.stage.extremityRegion();
  ASSERT_EQ(cap.size(), 1U);
  EXPECT_EQ(cap.front(), code.grid.linOf(20, 1, 1));
}

} // namespace
} // namespace vtouch

// The raw seeded mode across pieces (issue 19 item 2, issue 16 item 1), with 2-4 ranks as threads
// of one process (InProcessWorld, no MPI): the growth's rounds against a one-process flood fill
// (a network that leaves the seed's piece and comes back), the round cap, and the whole
// candidate region against VesselCandidateRegion's single run, with its verdicts on every rank.
#include "vtouchDistributedCandidateRegion.h"
#include "vtouchDistributedRegionGrowth.h"
#include "vtouchEveryRank.h"
#include "vtouchPieceGrid.h"
#include "vtouchRankPiece.h"
#include "vtouchRawAngiogramTestImages.h"
#include "vtouchSeedComponentSplit.h"
#include "vtouchVesselCandidateRegion.h"

#include <gtest/gtest.h>
#include <itkMultiThreaderBase.h>

#include <stdexcept>
#include <string>

namespace vtouch
{
namespace
{
using test::onEveryRank;
using test::SyntheticAngiogram;

constexpr double kContrast = 900.0; // background 100, vessel 1000

/// ITK's smoothing (the tubularity) runs on the calling thread, each rank's own thread here: ITK's
/// thread pool is not what these tests are about, and TSan, which does not see into the
/// uninstrumented ITK library, reports the pool's internal hand-offs (as in the cancellation
/// tests).
void itkOnTheCallingThread()
{
  itk::MultiThreaderBase::SetGlobalDefaultNumberOfThreads(1);
}

/// `ranks` pieces of `dims` as the executive splits by cells (neighbours share a face layer,
/// owned by the upper piece): slabs along z for 2 and 3, quarters in y and z for 4; held boxes
/// grown by `margin` on shared faces.
std::vector<PieceLayout> layouts(std::array<std::int64_t, 3> dims, int ranks, int margin)
{
  const std::array<int, 3> counts =
    ranks == 4 ? std::array<int, 3>{ 1, 2, 2 } : std::array<int, 3>{ 1, 1, ranks };
  return test::layouts(dims, counts, margin);
}


/// A tube that runs from piece 0 up into piece 1, across, and back down into piece 0 far from
/// where it left (a U), and a tube of its own that the growth must not reach.
SyntheticAngiogram uVolume()
{
  SyntheticAngiogram g({ 40, 24, 48 });
  g.addTube({ 6, 12, 6 }, { 6, 12, 40 }, 2.0, kContrast);
  g.addTube({ 6, 12, 40 }, { 33, 12, 40 }, 2.0, kContrast);
  g.addTube({ 33, 12, 40 }, { 33, 12, 6 }, 2.0, kContrast);
  g.addTube({ 20, 4, 4 }, { 20, 4, 20 }, 1.5, kContrast); // apart
  return g;
}

/// Whole-volume flood fill from `seed` through voxels >= `threshold` (26-connected).
std::vector<char> floodFill(const SyntheticAngiogram& g,
  std::array<std::int64_t, 3> seed,
  float threshold)
{
  const auto& d = g.dims;
  std::vector<char> in(static_cast<std::size_t>(d[0] * d[1] * d[2]), 0);
  std::vector<std::array<std::int64_t, 3>> stack{ seed };
  in[static_cast<std::size_t>(seed[0] + d[0] * (seed[1] + d[1] * seed[2]))] = 1;
  while (!stack.empty())
  {
    const auto c = stack.back();
    stack.pop_back();
    for (int dk = -1; dk <= 1; ++dk)
      for (int dj = -1; dj <= 1; ++dj)
        for (int di = -1; di <= 1; ++di)
        {
          const std::int64_t i = c[0] + di, j = c[1] + dj, k = c[2] + dk;
          if (i < 0 || j < 0 || k < 0 || i >= d[0] || j >= d[1] || k >= d[2])
          {
            continue;
          }
          const auto lin = static_cast<std::size_t>(i + d[0] * (j + d[1] * k));
          if (!in[lin] && g.voxels[lin] >= threshold)
          {
            in[lin] = 1;
            stack.push_back({ i, j, k });
          }
        }
  }
  return in;
}

TEST(DistributedRegionGrowth, NetworkLeavingThePieceAndComingBackMatchesOneProcess)
{
  const SyntheticAngiogram g = uVolume();
  const std::array<std::int64_t, 3> seed{ 6, 12, 8 };
  const float threshold = 550.0F;
  const std::vector<char> single = floodFill(g, seed, threshold);
  for (int ranks : { 2, 3, 4 })
  {
    struct Grown
    {
      int rounds = 0;
      int differ = 0; ///< voxels the rank decides otherwise than the single run
    };
    const std::vector<Grown> grown = onEveryRank<Grown>(layouts(g.dims, ranks, 2),
      [&](const PieceLayout& l, RankCollectives& c, Grown& out)
      {
        const test::RankPiece piece(g.voxels, g.dims, l);
        const VolumeView<float>& v = piece.view;
        SparseVesselMask mask(v.dims);
        const DistributedRegionGrowth growth(l);
        const auto outcome = growth.run(
          c,
          mask,
          piece.seedsOwned(seed),
          [&v, threshold](std::uint64_t lin) { return v.voxels[lin] >= threshold; },
          DistributedRegionGrowth::OnJoin());
        out.rounds = outcome.settled ? outcome.rounds : -1;
        // The rank's region equals the single run's on every voxel it decides.
        const VoxelBox e = l.evaluable(l.rank);
        for (std::int64_t k = e.lo[2]; k <= e.hi[2]; ++k)
          for (std::int64_t j = e.lo[1]; j <= e.hi[1]; ++j)
            for (std::int64_t i = e.lo[0]; i <= e.hi[0]; ++i)
            {
              const bool local = mask.test(piece.linear({ i, j, k }));
              out.differ +=
                local !=
                (single[static_cast<std::size_t>(i + g.dims[0] * (j + g.dims[1] * k))] != 0);
            }
      });
    for (std::size_t r = 0; r < grown.size(); ++r)
    {
      EXPECT_EQ(grown[r].differ, 0) << ranks << " ranks, rank " << r << ": voxels differ";
      EXPECT_EQ(grown[r].rounds, grown[0].rounds) << "every rank, the same rounds";
    }
    // Up the U's first leg into the upper piece, back down its second into the lower: at least
    // two exchanges carry voxels, one more finds nothing new.
    EXPECT_GE(grown[0].rounds, 3) << ranks << " ranks";
  }
  // The tube apart is not reached (the single run, hence every rank, leaves it out).
  EXPECT_EQ(single[static_cast<std::size_t>(20 + 40 * (4 + 24 * 12))], 0);
}

TEST(DistributedRegionGrowth, RoundCapStopsEveryRankWithAMessage)
{
  const SyntheticAngiogram g = uVolume();
  const std::vector<std::string> messages = onEveryRank<std::string>(layouts(g.dims, 2, 2),
    [&](const PieceLayout& l, RankCollectives& c, std::string& message)
    {
      const test::RankPiece piece(g.voxels, g.dims, l); // the seed in rank 0's piece
      const VolumeView<float>& v = piece.view;
      SparseVesselMask mask(v.dims);
      const auto o = DistributedRegionGrowth(l).run(
        c,
        mask,
        piece.seedsOwned({ 6, 12, 8 }),
        [&v](std::uint64_t lin) { return v.voxels[lin] >= 550.0F; },
        DistributedRegionGrowth::OnJoin(),
        2);
      message = o.settled ? "" : o.message;
    });
  EXPECT_NE(messages[0].find("did not settle in 2 rounds"), std::string::npos) << messages[0];
  EXPECT_EQ(messages[0], messages[1]);
}

TEST(DistributedRegionGrowth, AcceptThrowingOnOneRankThrowsOnEveryRank)
{
  // The upper rank's rule fails the first time it is asked (round 2, once the lower rank has
  // reported the U's first leg): the lower rank must not wait for it in the next exchange
  // (CollectiveRounds' shared failure; InProcessWorld would fail after 60 s instead).
  const SyntheticAngiogram g = uVolume();
  const std::vector<std::string> thrown = onEveryRank<std::string>(layouts(g.dims, 2, 2),
    [&](const PieceLayout& l, RankCollectives& c, std::string& what)
    {
      const int r = l.rank;
      const test::RankPiece piece(g.voxels, g.dims, l); // the seed in rank 0's piece
      const VolumeView<float>& v = piece.view;
      SparseVesselMask mask(v.dims);
      const std::vector<std::uint64_t> seeds = piece.seedsOwned({ 6, 12, 8 });
      const DistributedRegionGrowth::Accept accept = [&v, r](std::uint64_t lin)
      {
        if (r == 1)
        {
          throw std::out_of_range("the upper piece's voxels are gone");
        }
        return v.voxels[lin] >= 550.0F;
      };
      try
      {
        DistributedRegionGrowth(l).run(c, mask, seeds, accept, DistributedRegionGrowth::OnJoin());
        what = "nothing";
      }
      catch (const std::out_of_range& e)
      {
        what = std::string("own: ") + e.what();
      }
      catch (const std::runtime_error& e)
      {
        what = e.what();
      }
    });
  EXPECT_EQ(thrown[1], "own: the upper piece's voxels are gone");
  EXPECT_EQ(thrown[0],
    "the region growth across the pieces: rank 1 failed in round 2: the upper piece's voxels "
    "are gone");
}

/// A raw angiogram with a bifurcating tree crossing the pieces' faces, a plate touching one
/// vessel and noise.
SyntheticAngiogram treeVolume()
{
  SyntheticAngiogram g({ 64, 56, 80 });
  g.addTube({ 30, 28, 4 }, { 30, 28, 40 }, 3.0, kContrast);
  g.addTube({ 30, 28, 40 }, { 12, 20, 74 }, 2.0, kContrast);
  g.addTube({ 30, 28, 40 }, { 52, 36, 70 }, 2.0, kContrast);
  g.addTube({ 52, 36, 70 }, { 52, 46, 30 }, 1.5, kContrast); // back down into the lower piece
  g.addBox({ 34, 26, 10 }, { 38, 40, 30 }, kContrast);       // a plate touching the trunk
  g.addNoise(20.0, 11);
  return g;
}

struct RankRegion
{
  bool ok = false;
  std::string message;
  IntensityRange range;
  int rounds = 0;
  bool seedHere = false;
  int differ = 0; ///< owned voxels whose membership differs from the single run
  std::uint64_t ownedRegion = 0;
};

std::vector<RankRegion> distributedRegion(const SyntheticAngiogram& g,
  std::array<std::int64_t, 3> seed,
  int ranks,
  int margin,
  const VesselCandidateRegion::Result* single)
{
  return onEveryRank<RankRegion>(layouts(g.dims, ranks, margin),
    [&](const PieceLayout& l, RankCollectives& c, RankRegion& mine)
    {
      const test::RankPiece piece(g.voxels, g.dims, l);
      VesselCandidateRegion::Settings s;
      s.useSeed = true;
      const auto result = DistributedCandidateRegion::extract(piece.view, l, seed, s, c);
      mine.ok = result.region.ok;
      mine.message = result.region.message;
      mine.range = result.region.range;
      mine.rounds = result.growthRounds;
      mine.seedHere = result.seedHere;
      if (!single || !result.region.ok)
      {
        return;
      }
      const VoxelBox& o = l.owned[static_cast<std::size_t>(l.rank)];
      for (std::int64_t k = o.lo[2]; k <= o.hi[2]; ++k)
        for (std::int64_t j = o.lo[1]; j <= o.hi[1]; ++j)
          for (std::int64_t i = o.lo[0]; i <= o.hi[0]; ++i)
          {
            const bool here = result.region.mask.test(piece.linear({ i, j, k }));
            const bool there =
              single->mask.test(static_cast<std::uint64_t>(i + g.dims[0] * (j + g.dims[1] * k)));
            mine.differ += here != there;
            mine.ownedRegion += here;
          }
    });
}

TEST(DistributedCandidateRegion, SameRangeAndRegionAsOneProcessOnTwoToFourPieces)
{
  itkOnTheCallingThread();
  const SyntheticAngiogram g = treeVolume();
  const std::array<std::int64_t, 3> seed{ 30, 28, 12 };
  VesselCandidateRegion::Settings s;
  s.useSeed = true;
  s.seed = seed;
  const VesselCandidateRegion::Result single = VesselCandidateRegion::extract(g.view(), s);
  ASSERT_TRUE(single.ok) << single.message;
  const int margin = DistributedCandidateRegion::rangeMarginVoxels() + 2;
  for (int ranks : { 2, 3, 4 })
  {
    const std::vector<RankRegion> regions = distributedRegion(g, seed, ranks, margin, &single);
    int differ = 0;
    int seedRanks = 0;
    for (const RankRegion& r : regions)
    {
      ASSERT_TRUE(r.ok) << ranks << " ranks: " << r.message;
      EXPECT_EQ(r.range.lower, single.range.lower) << "the seed's rank estimates the same range";
      EXPECT_EQ(r.range.upper, single.range.upper);
      EXPECT_EQ(r.range.weakLower, single.range.weakLower);
      EXPECT_EQ(r.rounds, regions[0].rounds);
      differ += r.differ;
      seedRanks += r.seedHere ? 1 : 0;
    }
    EXPECT_EQ(seedRanks, 1);
    EXPECT_GE(regions[0].rounds, 2) << "the tree crosses the pieces' faces";
    // Slabs along z and quarters in y and z: every owned voxel as the single run decides it
    // (on quarters 48 of 3301 differed while the tubularity's grids started at each piece's
    // first voxel; DistributedTubularity puts them on the whole volume's lattice, h19t).
    EXPECT_EQ(differ, 0) << ranks << " ranks: owned voxels differ from the single run";
  }
}

TEST(DistributedCandidateRegion, SeedOnBackgroundOrOutsideGivesEveryRankTheMessage)
{
  itkOnTheCallingThread();
  const SyntheticAngiogram g = treeVolume();
  VesselCandidateRegion::Settings s;
  s.useSeed = true;
  s.seed = { 8, 8, 60 };
  const auto single = VesselCandidateRegion::extract(g.view(), s);
  ASSERT_FALSE(single.ok);
  for (int ranks : { 2, 4 })
  {
    for (const RankRegion& r : distributedRegion(g, s.seed, ranks, 26, nullptr))
    {
      EXPECT_FALSE(r.ok);
      EXPECT_EQ(r.message, single.message) << "the single run's message on every rank";
    }
    for (const RankRegion& r : distributedRegion(g, { 8, 8, 200 }, ranks, 26, nullptr))
    {
      EXPECT_FALSE(r.ok);
      EXPECT_EQ(r.message, IntensityRangeEstimator::outsideMessage());
    }
  }
}

TEST(DistributedCandidateRegion, GhostMarginNarrowerThanTheSeedsNeighbourhoodSaysSo)
{
  itkOnTheCallingThread();
  const SyntheticAngiogram g = treeVolume();
  // Seeds 3 voxels below and above the face z = 39 (owned by the lower and the upper piece):
  // their 24-voxel cubes reach beyond a 4-voxel margin, on either side.
  for (std::int64_t z : { 36, 42 })
  {
    for (const RankRegion& r : distributedRegion(g, { 30, 28, z }, 2, 4, nullptr))
    {
      EXPECT_FALSE(r.ok);
      EXPECT_NE(r.message.find("ghost margin"), std::string::npos)
        << "z " << z << ": " << r.message;
    }
  }
}

TEST(SeedComponentSplit, PartsReachingTheSeedOutsideThePieceAreTheRest)
{
  // A piece of a U: the seed's leg, and the other leg that joins it only beyond the piece.
  SparseVesselMask mask({ 12, 6, 10 });
  const auto lin = [](std::int64_t i, std::int64_t j, std::int64_t k)
  { return static_cast<std::uint64_t>(i + 12 * (j + 6 * k)); };
  for (std::int64_t k = 0; k < 10; ++k)
  {
    mask.set(lin(2, 3, k));
    mask.set(lin(9, 3, k));
  }
  mask.finalize();
  const SeedComponentSplit::Parts parts = SeedComponentSplit::split(mask, { 2, 3, 1 });
  EXPECT_EQ(parts.seedComponent.vesselCount(), 10u);
  EXPECT_EQ(parts.rest.vesselCount(), 10u);
  EXPECT_TRUE(parts.seedComponent.test(lin(2, 3, 9)));
  EXPECT_TRUE(parts.rest.test(lin(9, 3, 0)));
  EXPECT_FALSE(parts.rest.test(lin(2, 3, 0)));
  // A seed whose component is the whole mask leaves no rest.
  EXPECT_EQ(SeedComponentSplit::split(parts.seedComponent, { 2, 3, 4 }).rest.vesselCount(), 0u);
}

TEST(SeedComponentSplit, AppendedSkeletonShiftsPathAndJunctionIndices)
{
  const auto path = [](int id, int head, int tail)
  {
    SkeletonPath p;
    p.id = id;
    p.head.junction = head;
    p.tail.junction = tail;
    p.points.resize(3);
    return p;
  };
  QSkeleton a, b;
  a.paths = { path(0, -1, -1), path(1, 0, -1) };
  a.junctions.push_back(Junction{ 1, Junction::End::Head, 0, 1 });
  b.paths = { path(0, -1, 0), path(1, -1, -1) };
  b.junctions.push_back(Junction{ 0, Junction::End::Tail, 1, 2 });
  ASSERT_EQ(a.validate(), "");
  ASSERT_EQ(b.validate(), "");
  const QSkeleton c = SeedComponentSplit::appended(a, b);
  EXPECT_EQ(c.validate(), "") << "ids and back references still consistent";
  ASSERT_EQ(c.paths.size(), 4u);
  ASSERT_EQ(c.junctions.size(), 2u);
  EXPECT_EQ(c.paths[2].id, 2);
  EXPECT_EQ(c.paths[2].tail.junction, 1);
  EXPECT_EQ(c.paths[3].head.junction, -1);
  EXPECT_EQ(c.junctions[1].childPath, 2);
  EXPECT_EQ(c.junctions[1].parentPath, 3);
  EXPECT_EQ(c.junctions[1].parentPoint, 2);
  EXPECT_EQ(c.junctions[0].childPath, 1) << "a's junctions unchanged";
}

} // namespace
} // namespace vtouch

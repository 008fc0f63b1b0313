// The raw mode without a seed across pieces (issue 19 item 2, issue 16 item 1 "Without a seed the
// automatic range applies to the whole volume"), 2, 4 and 8 ranks as threads of one process
// (InProcessWorld, no MPI), on VesselPhantom's raw angiogram (a random tree with partial volume,
// tissue, clutter at vessel intensity, bias and noise): the range against fromVolume's bit for
// bit, the region against VesselCandidateRegion's single run on every owned voxel, every rank's
// held voxels taken from their owners, and the verdicts on every rank.
#include "vtouchDistributedCandidateRegion.h"
#include "vtouchDistributedVolumeRange.h"
#include "vtouchEveryRank.h"
#include "vtouchHeldRegionFromOwners.h"
#include "vtouchPieceGrid.h"
#include "vtouchRawPhantomVolume.h"
#include "vtouchRankPiece.h"
#include "vtouchVesselCandidateRegion.h"

#include <gtest/gtest.h>
#include <itkMultiThreaderBase.h>

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

namespace vtouch
{
namespace
{
using test::onEveryRank;

/// ITK's smoothing (the tubularity) on each rank's own thread (as vtouchDistributedRegionTest).
void itkOnTheCallingThread()
{
  itk::MultiThreaderBase::SetGlobalDefaultNumberOfThreads(1);
}

/// The ghost margin of these tests (voxels): past the deepest region voxel of the phantom (its
/// root radius is 4 voxels) and the tubularity's largest smoothing support.
constexpr int kMargin = 16;

using Volume = test::FloatVolume;

/// VesselPhantom's raw angiogram (the client/server test's recipe at a smaller size).
Volume rawPhantom(int n, std::uint32_t seed)
{
  Volume v = test::rawPhantomVolume(n, seed, 40, 20.0);
  EXPECT_TRUE(v.ok) << v.error;
  return v;
}


struct RankRegion
{
  bool ok = false;
  std::string message;
  IntensityRange range;
  int ownedDiffer = 0;   ///< owned voxels decided otherwise than the single run
  int heldNotOwners = 0; ///< held voxels that are not their owner's decision
  std::uint64_t ownedRegion = 0;
  std::uint64_t fromOwners = 0; ///< heldVoxelsFromOwners
  SparseVesselMask mask;
  PieceLayout layout;
};

std::vector<RankRegion> unseeded(const Volume& g, const std::array<int, 3>& counts, int margin)
{
  VesselCandidateRegion::Settings s; // automatic, tubes only, no seed
  return onEveryRank<RankRegion>(test::layouts(g.dims, counts, margin),
    [&](const PieceLayout& l, RankCollectives& c, RankRegion& mine)
    {
      const test::RankPiece piece(g.voxels, g.dims, l);
      const DistributedCandidateRegion::Result result =
        DistributedCandidateRegion::extract(piece.view, l, { -1, -1, -1 }, s, c);
      mine.ok = result.region.ok;
      mine.message = result.region.message;
      mine.range = result.region.range;
      mine.fromOwners = result.heldVoxelsFromOwners;
      mine.mask = result.region.mask;
      mine.layout = l;
    });
}

/// Every rank's owned voxels against the single run's region, and every held voxel against its
/// owner's decision.
void compare(std::vector<RankRegion>& ranks, const Volume& g, const SparseVesselMask& single)
{
  for (RankRegion& r : ranks)
  {
    const PieceLayout& l = r.layout;
    const VoxelBox& h = l.mine();
    const std::array<std::int64_t, 3> d = l.pieceDims();
    for (std::int64_t k = h.lo[2]; k <= h.hi[2]; ++k)
      for (std::int64_t j = h.lo[1]; j <= h.hi[1]; ++j)
        for (std::int64_t i = h.lo[0]; i <= h.hi[0]; ++i)
        {
          const auto q = l.toLocal({ i, j, k });
          const bool here =
            r.mask.test(static_cast<std::uint64_t>(q[0] + d[0] * (q[1] + d[1] * q[2])));
          const int owner = l.ownerOf({ i, j, k });
          if (owner == l.rank)
          {
            const bool there =
              single.test(static_cast<std::uint64_t>(i + g.dims[0] * (j + g.dims[1] * k)));
            r.ownedDiffer += here != there;
            r.ownedRegion += here;
            continue;
          }
          const RankRegion& o = ranks[static_cast<std::size_t>(owner)];
          const auto qo = o.layout.toLocal({ i, j, k });
          const std::array<std::int64_t, 3> od = o.layout.pieceDims();
          const bool owners =
            o.mask.test(static_cast<std::uint64_t>(qo[0] + od[0] * (qo[1] + od[1] * qo[2])));
          r.heldNotOwners += here != owners;
        }
  }
}

TEST(DistributedRawUnseeded, RangeIsTheSingleRunsBitForBitOnTwoFourAndEightPieces)
{
  for (std::uint32_t seed : { 3U, 7U })
  {
    const Volume g = rawPhantom(72, seed);
    // Every voxel sampled (72^3 is below the 2^21 cap), and every 7th (the cap lowered: a
    // lattice that does not follow the pieces' rows).
    for (const std::uint64_t cap : { std::uint64_t{ 1 } << 21, std::uint64_t{ 60000 } })
    {
      IntensityRangeParameters p;
      p.wholeVolumeSamples = cap;
      const IntensityRange single = IntensityRangeEstimator::fromVolume(g.view(), p);
      ASSERT_TRUE(single.ok) << single.message;
      for (const std::array<int, 3>& counts : test::kSplitsIn2And4And8)
      {
        const std::vector<IntensityRange> ranges =
          onEveryRank<IntensityRange>(test::layouts(g.dims, counts, kMargin),
            [&](const PieceLayout& l, RankCollectives& c, IntensityRange& mine)
            {
              const test::RankPiece piece(g.voxels, g.dims, l);
              const IntensityRangeEstimator::Scan local = IntensityRangeEstimator::scan(piece.view);
              // The whole scan from the pieces' (DistributedCandidateRegion's step 1 combines them
              // so).
              std::vector<double> all;
              for (const std::vector<double>& v :
                c.allGather(std::vector<double>{ local.minimum, local.maximum }))
              {
                all.insert(all.end(), v.begin(), v.end());
              }
              IntensityRangeEstimator::Scan whole;
              whole.minimum = *std::min_element(all.begin(), all.end());
              whole.maximum = *std::max_element(all.begin(), all.end());
              whole.twoValued = false; // a raw volume
              mine = DistributedVolumeRange::estimate(piece.view, l, whole, c, p);
            });
        for (const IntensityRange& r : ranges)
        {
          ASSERT_TRUE(r.ok) << r.message;
          // Bit for bit: the same sample, the same order statistics and histogram.
          EXPECT_EQ(r.lower, single.lower) << counts[2] * counts[1] * counts[0] << " pieces";
          EXPECT_EQ(r.upper, single.upper);
          EXPECT_EQ(r.weakLower, single.weakLower);
          EXPECT_EQ(r.background, single.background);
          EXPECT_EQ(r.backgroundNoise, single.backgroundNoise);
          EXPECT_EQ(r.vessel, single.vessel);
        }
      }
    }
  }
}

TEST(DistributedRawUnseeded, OwnedSamplesTileFromVolumesLattice)
{
  // A volume larger than the sample cap's stride 1 (IntensityRangeParameters::wholeVolumeSamples
  // lowered): each rank's part holds the lattice voxels it owns, all of them together once.
  IntensityRangeParameters p;
  p.wholeVolumeSamples = 1000; // 30 x 26 x 22 = 17160 voxels: stride 17 (not a row's divisor)
  Volume g{ { 30, 26, 22 }, {} };
  for (std::size_t i = 0; i < 30U * 26U * 22U; ++i)
  {
    g.voxels.push_back(static_cast<float>(i)); // the value is its linear index
  }
  const std::uint64_t stride = IntensityRangeEstimator::sampleStride(30U * 26U * 22U, p);
  ASSERT_EQ(stride, 17U);
  const std::vector<std::vector<double>> parts =
    onEveryRank<std::vector<double>>(test::layouts(g.dims, { 2, 2, 2 }, 3),
      [&](const PieceLayout& l, RankCollectives&, std::vector<double>& mine)
      {
        const test::RankPiece piece(g.voxels, g.dims, l);
        mine = DistributedVolumeRange::ownedSample(piece.view, l, p);
      });
  std::vector<double> all;
  for (const std::vector<double>& part : parts)
  {
    EXPECT_FALSE(part.empty());
    all.insert(all.end(), part.begin(), part.end());
  }
  std::sort(all.begin(), all.end());
  std::vector<double> lattice;
  for (std::uint64_t i = 0; i < 30U * 26U * 22U; i += stride)
  {
    lattice.push_back(static_cast<double>(i));
  }
  EXPECT_EQ(all, lattice);
}

TEST(DistributedRawUnseeded, RegionIsTheSingleRunsOnOwnedVoxelsAndHeldVoxelsAreTheOwners)
{
  itkOnTheCallingThread();
  const Volume g = rawPhantom(72, 3);
  VesselCandidateRegion::Settings s;
  const VesselCandidateRegion::Result single = VesselCandidateRegion::extract(g.view(), s);
  ASSERT_TRUE(single.ok) << single.message;
  ASSERT_GT(single.mask.vesselCount(), 1000U);
  for (const std::array<int, 3>& counts : test::kSplitsIn2And4And8)
  {
    const int pieces = counts[0] * counts[1] * counts[2];
    std::vector<RankRegion> ranks = unseeded(g, counts, kMargin);
    compare(ranks, g, single.mask);
    int differ = 0;
    std::uint64_t owned = 0, fromOwners = 0;
    for (const RankRegion& r : ranks)
    {
      ASSERT_TRUE(r.ok) << pieces << " pieces: " << r.message;
      EXPECT_EQ(r.range.lower, single.range.lower) << "the single run's range on every rank";
      EXPECT_EQ(r.range.upper, single.range.upper);
      EXPECT_EQ(r.heldNotOwners, 0) << pieces << " pieces: rank " << r.layout.rank
                                    << "'s held voxels are its owners' decisions";
      differ += r.ownedDiffer;
      owned += r.ownedRegion;
      fromOwners += r.fromOwners;
    }
    // Every owned voxel as the single run decides it (24-55 of 10221 differed while the
    // tubularity's grids started at each piece's first voxel; DistributedTubularity, h19t).
    EXPECT_EQ(differ, 0) << pieces << " pieces: owned voxels differ from the single run";
    EXPECT_NEAR(static_cast<double>(owned),
      static_cast<double>(single.mask.vesselCount()),
      static_cast<double>(single.mask.vesselCount() / 100));
    std::printf("%d pieces: %d of %llu owned region voxels differ from the single run's; "
                "%llu held voxels taken from their owners\n",
      pieces,
      differ,
      static_cast<unsigned long long>(single.mask.vesselCount()),
      static_cast<unsigned long long>(fromOwners));
  }
}

TEST(DistributedRawUnseeded, VolumeWithoutVesselsGivesEveryRankTheSingleRunsMessage)
{
  itkOnTheCallingThread();
  const std::array<std::int64_t, 3> dims{ 24, 20, 28 };
  const std::size_t n = 24 * 20 * 28;
  // Nothing above the background's noise: four fifths at 100, the rest at 90 (sigma 10), and
  // one voxel at 120 (not two-valued; below the noise floor 130).
  Volume dark{ dims, std::vector<float>(n, 100.0F) };
  for (std::size_t i = 0; i < n; i += 5)
  {
    dark.voxels[i] = 90.0F;
  }
  dark.voxels[n / 2 + 1] = 120.0F;
  // A single intensity.
  const Volume flat{ dims, std::vector<float>(n, 7.0F) };
  for (const Volume* g : std::vector<const Volume*>{ &dark, &flat })
  {
    const VesselCandidateRegion::Result single =
      VesselCandidateRegion::extract(g->view(), VesselCandidateRegion::Settings{});
    ASSERT_FALSE(single.ok) << "volume " << (g == &dark ? "dark" : "flat");
    for (const std::array<int, 3>& counts : test::kSplitsIn2And4And8)
    {
      for (const RankRegion& r : unseeded(*g, counts, 4))
      {
        EXPECT_FALSE(r.ok);
        EXPECT_EQ(r.message, single.message) << counts[0] * counts[1] * counts[2] << " pieces";
      }
    }
  }
}

TEST(DistributedRawUnseeded, BinaryMaskIsThresholdedAtItsMidpointOnEveryRank)
{
  // A two-valued volume (0 and 255): the combined scan gives the binary range, the region is
  // the threshold, as drawn (no tube cut), on every held voxel of every rank.
  const std::array<std::int64_t, 3> dims{ 30, 26, 40 };
  Volume mask{ dims, std::vector<float>(30U * 26U * 40U, 0.0F) };
  for (std::int64_t k = 2; k < 38; ++k)
    for (std::int64_t j = 10; j < 14; ++j)
      for (std::int64_t i = 12 + k / 4; i < 16 + k / 4; ++i)
      {
        mask.voxels[static_cast<std::size_t>(i + 30 * (j + 26 * k))] = 255.0F;
      }
  const VesselCandidateRegion::Result single =
    VesselCandidateRegion::extract(mask.view(), VesselCandidateRegion::Settings{});
  ASSERT_TRUE(single.ok) << single.message;
  ASSERT_TRUE(single.range.binary);
  for (const std::array<int, 3>& counts : test::kSplitsIn2And4And8)
  {
    std::vector<RankRegion> ranks = unseeded(mask, counts, 4);
    compare(ranks, mask, single.mask);
    for (const RankRegion& r : ranks)
    {
      ASSERT_TRUE(r.ok) << r.message;
      EXPECT_TRUE(r.range.binary);
      EXPECT_EQ(r.range.lower, 127.5);
      EXPECT_EQ(r.ownedDiffer, 0);
      EXPECT_EQ(r.heldNotOwners, 0);
      EXPECT_EQ(r.fromOwners, 0U) << "a threshold is every rank's own decision";
    }
  }
}

TEST(DistributedRawUnseeded, RankWithAnEmptyPieceJoinsEveryCollective)
{
  // Three ranks, the third holding and owning nothing (more ranks than the volume splits
  // into): it takes every collective step with no voxels, and every rank reaches the single
  // run's range and verdict; the two others hold the single run's region.
  itkOnTheCallingThread();
  const Volume g = rawPhantom(48, 7);
  const VesselCandidateRegion::Result single =
    VesselCandidateRegion::extract(g.view(), VesselCandidateRegion::Settings{});
  ASSERT_TRUE(single.ok) << single.message;
  std::vector<PieceLayout> pieces = test::layouts(g.dims, { 1, 1, 2 }, kMargin);
  for (PieceLayout& l : pieces)
  {
    l.held.push_back(VoxelBox{});
    l.owned.push_back(VoxelBox{});
  }
  PieceLayout empty = pieces[0];
  empty.rank = 2;
  pieces.push_back(empty);
  std::vector<RankRegion> ranks = onEveryRank<RankRegion>(pieces,
    [&](const PieceLayout& l, RankCollectives& c, RankRegion& mine)
    {
      const test::RankPiece piece(g.voxels, g.dims, l);
      const DistributedCandidateRegion::Result result = DistributedCandidateRegion::extract(
        piece.view, l, { -1, -1, -1 }, VesselCandidateRegion::Settings{}, c);
      mine.ok = result.region.ok;
      mine.message = result.region.message;
      mine.range = result.region.range;
      mine.mask = result.region.mask;
      mine.layout = l;
    });
  for (const RankRegion& r : ranks)
  {
    ASSERT_TRUE(r.ok) << "rank " << r.layout.rank << ": " << r.message;
    EXPECT_EQ(r.range.lower, single.range.lower);
    EXPECT_EQ(r.range.upper, single.range.upper);
  }
  EXPECT_EQ(ranks[2].mask.vesselCount(), 0U);
  ranks.pop_back(); // compare() walks held boxes: the empty rank has none
  compare(ranks, g, single.mask);
  EXPECT_EQ(ranks[0].ownedDiffer + ranks[1].ownedDiffer, 0);
}

TEST(HeldRegionFromOwners, HeldVoxelsTakeTheOwnersDecisionAndTheChangesAreCounted)
{
  // Two slabs along z sharing a margin of 3: rank 0 marks a column through its whole held box,
  // rank 1 another column through its own; each marks the other's column differently.
  const std::vector<PieceLayout> pieces = test::layouts({ 8, 8, 20 }, { 1, 1, 2 }, 3);
  struct Out
  {
    SparseVesselMask mask;
    std::uint64_t changed = 0;
  };
  const std::vector<Out> out = onEveryRank<Out>(pieces,
    [&](const PieceLayout& l, RankCollectives& c, Out& mine)
    {
      const std::array<std::int64_t, 3> d = l.pieceDims();
      mine.mask = SparseVesselMask(d);
      for (std::int64_t k = 0; k < d[2]; ++k)
      {
        // Column (2, 2) everywhere on rank 0, (5, 5) everywhere on rank 1.
        const std::int64_t x = l.rank == 0 ? 2 : 5;
        mine.mask.set(static_cast<std::uint64_t>(x + d[0] * (x + d[1] * k)));
      }
      mine.mask.finalize();
      mine.changed = HeldRegionFromOwners::adopt(mine.mask, l, c);
    });
  for (int r = 0; r < 2; ++r)
  {
    const PieceLayout& l = pieces[static_cast<std::size_t>(r)];
    const std::array<std::int64_t, 3> d = l.pieceDims();
    std::uint64_t notOwned = 0;
    for (std::int64_t k = 0; k < d[2]; ++k)
    {
      const int owner = l.ownerOf(l.toWhole({ 0, 0, k }));
      const std::int64_t x = owner == 0 ? 2 : 5; // the owner's column
      const std::int64_t other = owner == 0 ? 5 : 2;
      EXPECT_TRUE(out[static_cast<std::size_t>(r)].mask.test(
        static_cast<std::uint64_t>(x + d[0] * (x + d[1] * k))))
        << "rank " << r << " plane " << k;
      EXPECT_FALSE(out[static_cast<std::size_t>(r)].mask.test(
        static_cast<std::uint64_t>(other + d[0] * (other + d[1] * k))))
        << "rank " << r << " plane " << k;
      notOwned += owner != r ? 1 : 0;
    }
    // Each held, not owned plane: one voxel gone, one voxel come.
    EXPECT_EQ(out[static_cast<std::size_t>(r)].changed, 2 * notOwned);
    EXPECT_EQ(
      out[static_cast<std::size_t>(r)].mask.vesselCount(), static_cast<std::uint64_t>(d[2]));
  }
}

} // namespace
} // namespace vtouch

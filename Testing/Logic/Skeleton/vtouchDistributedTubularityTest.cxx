// The raw path's tubularity across pieces (issue 19 item 2, issue 16 item 1), 2, 4 and 8 ranks as
// threads of one process (InProcessWorld, no MPI), on VesselPhantom's raw angiogram: every rank's
// RestrictedTubularity (DistributedTubularity: the whole volume's tile and coarse-grid lattice,
// the blocks of a tile's box beyond the piece from their holders) equals the single run's bit for
// bit at every voxel the rank owns, and the raw region the ranks decide together
// (DistributedCandidateRegion without a seed) is the single run's at every held voxel.
#include "vtouchDistributedCandidateRegion.h"
#include "vtouchDistributedTubularity.h"
#include "vtouchEveryRank.h"
#include "vtouchRawPhantomVolume.h"
#include "vtouchPieceGrid.h"
#include "vtouchRankPiece.h"
#include "vtouchVesselCandidateRegion.h"

#include <gtest/gtest.h>
#include <itkMultiThreaderBase.h>

#include <algorithm>
#include <cstdio>
#include <vector>

namespace vtouch
{
namespace
{
using test::onEveryRank;

/// The filter's ghost margin for this phantom (LargestVesselRadius 4 voxels: G = 31 voxels,
/// GhostMarginRule; ClientServer.DistributedRawSeeded's). It covers the depth of every owned
/// voxel (the phantom's deepest vessel voxel is 5 layers in), not the tiles' boxes: those reach
/// up to 123 voxels past a site and come from the other ranks.
constexpr int kMargin = 31;

using Whole = test::FloatVolume;

Whole rawPhantom(int n, std::uint32_t seed, int segments)
{
  Whole v = test::rawPhantomVolume(n, seed, segments, 20.0);
  EXPECT_TRUE(v.ok) << v.error;
  return v;
}

/// The single run's steps up to the tubularity (VesselCandidateRegion::extract without a seed).
struct SingleTubularity
{
  IntensityRange range;
  SparseVesselMask region;
  std::vector<std::uint16_t> depth;
  RestrictedTubularity::Parameters parameters;
  RestrictedTubularity::Result tube;
};

SingleTubularity singleRun(const Whole& g)
{
  const VesselCandidateRegion::Settings s;
  SingleTubularity out;
  out.range = IntensityRangeEstimator::fromVolume(g.view());
  EXPECT_TRUE(out.range.ok) << out.range.message;
  out.region = SeededRegionGrower::threshold(g.view(), out.range);
  out.depth = RegionDepth::layers(out.region);
  const int deepest =
    std::min<int>(s.maximumDepth_voxels, *std::max_element(out.depth.begin(), out.depth.end()));
  out.parameters =
    VesselCandidateRegion::tubularityParameters(s, out.range, deepest, g.view().spacing_mm);
  out.tube = RestrictedTubularity::compute(g.view(), out.region, out.depth, out.parameters);
  return out;
}

struct RankTubularity
{
  int ownedSites = 0;         ///< owned voxels the single run measured (tubularity > 0)
  int ownedDiffer = 0;        ///< owned region voxels whose tubularity is not the single run's
  int pieceLatticeDiffer = 0; ///< the same with the piece's own lattice (the code before h19t)
  std::uint64_t received = 0, notExact = 0, tiles = 0;
};

/// Each rank: the single run's range (the ranks compute it exactly: DistributedVolumeRange), the
/// threshold and depth on its piece, and the tubularity across the ranks.
std::vector<RankTubularity> ranksAgainst(const SingleTubularity& single,
  const Whole& g,
  const std::array<int, 3>& counts)
{
  return onEveryRank<RankTubularity>(test::layouts(g.dims, counts, kMargin),
    [&](const PieceLayout& l, RankCollectives& c, RankTubularity& mine)
    {
      const test::RankPiece piece(g.voxels, g.dims, l);
      const SparseVesselMask region = SeededRegionGrower::threshold(piece.view, single.range);
      const std::vector<std::uint16_t> depth = RegionDepth::layers(region);
      const DistributedTubularity::Result got =
        DistributedTubularity::compute(piece.view, l, region, depth, single.parameters, c);
      mine.received = got.blocksReceived;
      mine.tiles = got.tilesRequested;
      mine.notExact = got.tube.blocksNotExact;
      // The piece as a volume of its own (its first voxel the lattice's origin): before h19t.
      const RestrictedTubularity::Result own =
        RestrictedTubularity::compute(piece.view, region, depth, single.parameters);
      const VoxelBox& o = l.owned[static_cast<std::size_t>(l.rank)];
      for (std::int64_t k = o.lo[2]; k <= o.hi[2]; ++k)
        for (std::int64_t j = o.lo[1]; j <= o.hi[1]; ++j)
          for (std::int64_t i = o.lo[0]; i <= o.hi[0]; ++i)
          {
            const auto w = static_cast<std::uint64_t>(l.wholeLinear({ i, j, k }));
            if (!single.region.test(w))
            {
              continue;
            }
            const std::uint64_t lin = piece.linear({ i, j, k });
            const float expected = single.tube.tubularity[single.region.rank(w)];
            const float here = got.tube.tubularity[region.rank(lin)];
            mine.ownedSites += expected > 0.0F ? 1 : 0;
            mine.ownedDiffer += here != expected ? 1 : 0;
            mine.pieceLatticeDiffer += own.tubularity[region.rank(lin)] != expected ? 1 : 0;
          }
    });
}

TEST(DistributedTubularity, IsTheSingleRunsBitForBitAtEveryOwnedVoxelOnTwoFourAndEightPieces)
{
  itk::MultiThreaderBase::SetGlobalDefaultNumberOfThreads(1); // ITK on each rank's own thread
  // 96^3 with 40 segments: coarse grids F = 1, 2 and 4 (its clutter is up to 9 layers deep).
  const Whole g = rawPhantom(96, 3, 40);
  const SingleTubularity single = singleRun(g);
  ASSERT_GT(single.tube.sites, 500U);
  for (const std::array<int, 3>& counts : test::kSplitsIn2And4And8)
  {
    const int pieces = counts[0] * counts[1] * counts[2];
    int sites = 0, differ = 0, before = 0;
    std::uint64_t received = 0, tiles = 0;
    for (const RankTubularity& r : ranksAgainst(single, g, counts))
    {
      tiles += r.tiles;
      sites += r.ownedSites;
      differ += r.ownedDiffer;
      before += r.pieceLatticeDiffer;
      received += r.received;
      EXPECT_EQ(r.notExact, 0U) << pieces << " pieces: every block of every box held somewhere";
    }
    EXPECT_EQ(sites,
      static_cast<int>(std::count_if(single.tube.tubularity.begin(),
        single.tube.tubularity.end(),
        [](float v) { return v > 0.0F; })))
      << pieces << " pieces: the owned voxels cover the single run's region once";
    EXPECT_EQ(differ, 0) << pieces
                         << " pieces: owned voxels whose tubularity is not the single run's";
    // The check can fail: the piece's own lattice (the code before h19t) departs.
    EXPECT_GT(before, 0) << pieces << " pieces";
    EXPECT_GT(received, 0U) << pieces << " pieces: the tiles' boxes leave the pieces";
    std::printf("%d pieces: %d owned sites, %d differ (piece's own lattice: %d); %llu tiles "
                "requested, %llu block means received (all ranks; the volume: %lld voxels)\n",
      pieces,
      sites,
      differ,
      before,
      static_cast<unsigned long long>(tiles),
      static_cast<unsigned long long>(received),
      static_cast<long long>(g.dims[0] * g.dims[1] * g.dims[2]));
  }
}

TEST(DistributedTubularity, RegionWithoutASeedIsTheSingleRunsOnEveryHeldVoxel)
{
  // DistributedCandidateRegion without a seed (the range, the threshold, depth, tubularity, the
  // neck cut, the held voxels from their owners): every rank's held region is the single run's.
  itk::MultiThreaderBase::SetGlobalDefaultNumberOfThreads(1);
  const Whole g = rawPhantom(96, 3, 40);
  const VesselCandidateRegion::Settings s;
  const VesselCandidateRegion::Result single = VesselCandidateRegion::extract(g.view(), s);
  ASSERT_TRUE(single.ok) << single.message;
  for (const std::array<int, 3>& counts : test::kSplitsIn2And4And8)
  {
    const int pieces = counts[0] * counts[1] * counts[2];
    struct Out
    {
      bool ok = false;
      std::string message;
      int differ = 0;
      std::uint64_t fromOwners = 0;
    };
    const std::vector<Out> out = onEveryRank<Out>(test::layouts(g.dims, counts, kMargin),
      [&](const PieceLayout& l, RankCollectives& c, Out& mine)
      {
        const test::RankPiece piece(g.voxels, g.dims, l);
        const DistributedCandidateRegion::Result r =
          DistributedCandidateRegion::extract(piece.view, l, { -1, -1, -1 }, s, c);
        mine.ok = r.region.ok;
        mine.message = r.region.message;
        mine.fromOwners = r.heldVoxelsFromOwners;
        const SparseVesselMask expected = test::pieceMask(single.mask, l);
        const VoxelBox& h = l.mine();
        for (std::int64_t k = h.lo[2]; k <= h.hi[2]; ++k)
          for (std::int64_t j = h.lo[1]; j <= h.hi[1]; ++j)
            for (std::int64_t i = h.lo[0]; i <= h.hi[0]; ++i)
            {
              const std::uint64_t lin = piece.linear({ i, j, k });
              mine.differ += r.region.mask.test(lin) != expected.test(lin) ? 1 : 0;
            }
      });
    std::uint64_t fromOwners = 0;
    for (const Out& r : out)
    {
      ASSERT_TRUE(r.ok) << pieces << " pieces: " << r.message;
      EXPECT_EQ(r.differ, 0) << pieces << " pieces: held voxels not the single run's";
      fromOwners += r.fromOwners;
    }
    std::printf("%d pieces: %llu held voxels taken from their owners\n",
      pieces,
      static_cast<unsigned long long>(fromOwners));
  }
}

} // namespace
} // namespace vtouch

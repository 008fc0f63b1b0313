// The end cap of the double propagation across the pieces of a distributed volume (issue 19 item
// 2, the automatic root): the single run's SeedCodeStage::extremityRegion, collectively.
//
// After a DistributedSeedCode run, the far voxel is, in the last SS bucket over all ranks, the one
// with the largest whole linear index (the project rule of vtouchSkeletonEndCapRule.h, which the
// single run now shares; not DistributedSeedCode::farthest's rule). The cap is the set of voxels
// within one SS band of it (SS >= far's SS - band width, float as the single run) connected to
// it: grown in rounds as DistributedRegionGrowth grows, each rank flooding its held box from the
// far voxel and from the voxels the others joined, reporting the voxels it joined and owns
// (whole linear indices, AllGather), until no rank reports one. Exact: the SS field is the
// single run's on every held voxel, and along any path of the cap the owner of a voxel holds the
// next one (a ghost layer of one voxel at least), so the owners end with the single run's cap.
// Its centroid's integer index sums are the owners' sums added: the single run's numbers.
#pragma once

#include "vtouchDistributedSeedCode.h"
#include "vtouchPieceLayout.h"
#include "vtouchRankCollectives.h"
#include "vtouchSparseVesselMask.h"

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace vtouch
{

class DistributedEndCap
{
public:
  struct Cap
  {
    std::array<std::int64_t, 3> far_Whole{ 0, 0, 0 }; ///< the far voxel (whole index)
    double farSs_mm = -1.0;                           ///< its SS; negative: nothing reached
    std::array<std::int64_t, 3> indexSum{ 0, 0, 0 };  ///< the cap's whole indices summed
    std::uint64_t count = 0;                          ///< the cap's voxels
    /// The cap's whole linear indices, ascending, on every rank (only when asked for).
    std::vector<std::int64_t> voxels_Whole;
    int rounds = 0;      ///< exchanges of the growth (the same on every rank)
    bool settled = true; ///< false: stopped at the round cap (`message` says so)
    std::string message;
  };

  /// Collective. `code` has run on this rank's piece (`layout`, `pieceMask`, `spacing_mm` as
  /// given to it); `bandWidth_mm` is the single run's SS band (VoxelGrid::bandWidth).
  /// `gatherVoxels`: also give every rank the cap's voxels (the roots when its centre is not a
  /// vessel voxel).
  static Cap find(RankCollectives& collectives,
    const PieceLayout& layout,
    const SparseVesselMask& pieceMask,
    const std::array<double, 3>& spacing_mm,
    const DistributedSeedCode& code,
    double bandWidth_mm,
    bool gatherVoxels,
    int maximumRounds = DistributedSeedCode::kDefaultMaximumRounds);

private:
  /// Collective: the far voxel and its SS into `cap`; false when no rank reached a voxel.
  static bool farVoxel(RankCollectives& collectives,
    const PieceLayout& layout,
    const SparseVesselMask& pieceMask,
    double bucketWidth_mm,
    const DistributedSeedCode& code,
    Cap& cap);
};

} // namespace vtouch

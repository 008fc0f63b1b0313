// The BS code (boundary distance) of a distributed volume, exact on every rank's owned voxels
// (issue 19 item 2: the move of the automatic root to the thickest end reads the clusters'
// largest BS, ClusterStage::thickerRoot).
//
// The single run's BS is an exact Euclidean distance transform of the whole mask
// (skeleton::BoundaryCodeStage; outside the volume is not background). A rank's held box is its
// owned box plus a ghost margin of 1-2 voxels: near its cut faces the nearest background of a
// thick vessel lies outside it. Two steps, collectively:
// 1. Each rank codes its held box with the same stage: its cut faces count as "outside", not
//    background, so it sees a subset of the true background and every value is an upper bound
//    of the true one. B_r = the largest bound over its owned vessel voxels (gathered).
// 2. Rank r's extended box E_r = its owned box grown by ceil(B_r / spacing) voxels per axis
//    (clipped to the volume): every voxel within B_r mm of an owned voxel. The other ranks send
//    it their owned vessel voxels in E_r that r does not hold (one AllGather of whole indices),
//    and r codes E_r (with the stage's whole-volume origin, setOrigin, so that the floats are the
//    whole volume's). For an owned voxel v the true nearest background b is within BS(v) <= B_r
//    mm, so inside E_r, where the mask is the whole one: the code sees b and no background that
//    is not real; the value is the single run's bit for bit.
// Fails (every rank together) when a rank's held box has no background at all (no bound).
// Memory: the extended box's bit mask and codes (4 bytes per vessel voxel); no whole-volume array
// unless the thickest vessel's radius reaches across the volume.
#pragma once

#include "vtouchPieceLayout.h"
#include "vtouchRankCollectives.h"
#include "vtouchSparseVesselMask.h"

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace vtouch
{

class DistributedBoundaryCode
{
public:
  struct Result
  {
    bool ok = false;
    std::string message; ///< why not ok (the same on every rank)
    /// BS, mm, per vessel voxel of the piece mask (SparseVesselMask::rank): the single run's on
    /// the owned voxels; an upper bound on the other held voxels.
    std::vector<float> bs_mm;
    double largestBound_mm = 0.0;     ///< the largest B_r over the ranks
    std::uint64_t sentVoxels = 0;     ///< voxels sent in step 2, all ranks
    std::uint64_t gatheredValues = 0; ///< 64-bit values both AllGathers carried, all ranks
    std::uint64_t extendedVoxels = 0; ///< this rank's extended box, voxels
    int exchanges = 0;                ///< AllGathers
  };

  /// Collective. `layout`, `pieceMask` (finalized, the whole mask on the held box) and
  /// `spacing_mm` (> 0) as DistributedSeedCode's.
  static Result compute(const PieceLayout& layout,
    const SparseVesselMask& pieceMask,
    const std::array<double, 3>& spacing_mm,
    RankCollectives& collectives);
};

} // namespace vtouch

// The automatic root of the voxel coding (no seed) across the pieces of a distributed volume,
// and the SS field from it (issue 19 item 2, Docs/CLIENT-SERVER.md "The automatic root"): every
// rank gets the single run's root and codes with the single run's field.
//
// The single run (VoxelCoder without a seed), per connected component in scan order: the first
// vessel voxel of the component as start; on volumes of 2^17 vessel voxels or more an
// exploratory propagation on the 2x2x2 block mask from the start's block, its far end cap's
// centre mapped to the nearest vessel voxel (SeedCodeStage::coarseExtremity), used as the root
// when its propagation reaches the start; otherwise (or below 2^17) the exact double
// propagation: the code from the start, its far end cap (SeedCodeStage::extremityRegion) and
// the cap's centre voxel (or the whole cap when that centre is background). Components below
// `minimumComponentSize` are not coded. Each step here, collectively:
// - the start: the smallest whole linear index among the ranks' owned, unexplored vessel voxels;
// - the propagations: vtouch::DistributedSeedCode (exact, in rounds), on the fine piece or on
//   the rank's piece of the block mask (vtouch::DistributedBlockPiece: the block grid aligned to
//   the whole volume, as the single run's is);
// - the far voxel and its cap: vtouch::DistributedEndCap (the far voxel by the project rule the
//   single run now shares: largest SS, ties to the smallest linear index; the cap in rounds;
//   integer index sums);
// - "is this voxel vessel / already explored / reached": its owner's answer, gathered;
// - the nearest vessel voxel to the block cap's centre: the ranks' candidates, the smallest
//   distance, ties to the smallest index (the single run's scan order).
//
// Then, as the single run does, the move to the thickest end (ClusterStage::thickerRoot through
// skeleton::thickerEnd, the one rule both call): the BS code exact on the owned voxels
// (vtouch::DistributedBoundaryCode, once per choice), the component's cluster graph gathered to
// every rank (vtouch::DistributedClusterGraph, in the key order the rule reads), the end's root
// voxel (the vessel voxel at its clusters' integer centroid, else its voxel of largest BS) and,
// when the root moves, the SS code again from it. The roots given are the single run's final
// ones (RawSkeleton::roots[].thickest when moved, else .extremity) and the field the one it
// codes with.
//
// Collective rules: every rank takes every step; a failure (a layout or mask that cannot work, a
// round cap) is a verdict every rank reaches together; no whole-volume array on any rank (the
// piece's codes, the list of its owned vessel voxels and, on large volumes, its block piece).
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

class DistributedRootChoice
{
public:
  struct Parameters
  {
    /// Components with fewer vessel voxels are not coded (VoxelCodingParameters'). Voxels.
    std::uint64_t minimumComponentSize = 100;
    /// The SS band thickness, mm; 0 = the largest spacing (VoxelCodingParameters').
    double clusterWidth_mm = 0.0;
    /// The round cap of every propagation and cap growth (DistributedSeedCode's project rule).
    int maximumRounds = DistributedSeedCode::kDefaultMaximumRounds;
  };

  struct ComponentRoot
  {
    /// The root voxel(s) the SS field is coded from, whole index: the thickest end's root
    /// voxel when `moved`, else `extremity_Whole` (RawSkeleton::roots' final root).
    std::vector<std::array<std::int64_t, 3>> roots_Whole;
    /// The extremity the single run first codes from: one voxel, or the end cap's voxels when
    /// its centre is background (the single run's propagate(region); RawSkeleton::roots[].
    /// extremity).
    std::vector<std::array<std::int64_t, 3>> extremity_Whole;
    bool moved = false;       ///< re-rooted at the thickest end (RawComponentRoot::moved)
    std::uint64_t voxels = 0; ///< the component's vessel voxels (all ranks)
    bool fromBlocks = false;  ///< found by the exploration on the block mask
  };

  struct Result
  {
    bool ok = false;
    std::string message;                   ///< why not ok (the same on every rank)
    std::vector<ComponentRoot> components; ///< coded components, in scan order of their start
    /// The SS field, mm, per vessel voxel of the piece mask (SparseVesselMask::rank): the single
    /// run's code from each component's root; infinite on components not coded.
    std::vector<float> ss_mm;
    int propagations = 0; ///< DistributedSeedCode runs (fine and block)
    int rounds = 0;       ///< exchanges of those runs and of the cap growths, summed
    /// The move to the thickest end: AllGathers of the BS code and of the cluster graphs
    /// (DistributedBoundaryCode, DistributedClusterGraph) and the 64-bit values they sent.
    int moveExchanges = 0;
    std::uint64_t moveValues = 0;
    double boundBs_mm = 0.0; ///< DistributedBoundaryCode's largest bound (0: not computed)
  };

  /// Collective, the one call. `layout`: the pieces (held boxes at least one voxel past the
  /// owned ones; on volumes of 2^17 vessel voxels or more, one 2x2x2 block past them: the
  /// executive's ghost margin of 2, DistributedBlockPiece). `pieceMask`: this rank's
  /// vessel voxels on its held box (local index, finalized), equal to the whole mask there.
  /// `spacing_mm`: the voxel size (> 0, the same on every rank). Never throws on bad input:
  /// every rank returns ok = false with the same message.
  static Result choose(const PieceLayout& layout,
    const SparseVesselMask& pieceMask,
    const std::array<double, 3>& spacing_mm,
    RankCollectives& collectives,
    const Parameters& parameters);
};

} // namespace vtouch

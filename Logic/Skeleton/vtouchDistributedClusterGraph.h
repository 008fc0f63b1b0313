// The cluster graph of one component of a distributed volume, gathered to every rank (issue 19
// item 2: the move of the automatic root to the thickest end, ClusterStage::thickerRoot, reads
// it).
//
// The single run (skeleton::ClusterStage): the connected parts (26-neighbours) of the SS bands
// (band = SS * inverse band width, the float product truncated), each with its band, voxel
// count, largest BS (and the voxel of it), index sums, and the clusters of other bands it touches
// (lower / higher). Across the pieces, collectively:
// - each rank joins its held voxels of the component (owned and ghost) by band with a union-find
//   (every 26-neighbour pair is seen by the owner of either voxel, whose held box holds both);
//   a local set is named by its smallest whole linear index;
// - the sets that continue past a piece face are joined: each rank names, for each ghost voxel,
//   its set (AllGather 1); the ghost's owner answers with its own set (AllGather 2); every rank
//   joins the names (union-find on names): a cluster is named by its smallest voxel index;
// - per set, the owned voxels' count, largest BS (ties to the lower SS, then the smaller index:
//   ClusterStage's rule), integer index sums, smallest index and its SS, and the pairs of sets
//   of different bands that touch (AllGather 3); every rank adds them up per cluster.
// The clusters come out in the key order (skeleton::clusterKeyOrder: the SS of the smallest
// voxel, ties by its index), neighbour lists sorted in it: the order the thickest-end rule reads.
// Exact: counts, sums and maxima of the same values in any order (integers, float maxima).
// Cost: three AllGathers; their size is the ghost layer's component voxels and the clusters.
#pragma once

#include "vtouchPieceLayout.h"
#include "vtouchRankCollectives.h"
#include "vtouchSkeletonClusterGraph.h"
#include "vtouchSparseVesselMask.h"

#include <array>
#include <cstdint>
#include <vector>

namespace vtouch
{

class DistributedClusterGraph
{
public:
  struct Graph
  {
    /// In key order (the root's cluster first): band, count, maxBs, indexSum, lower, higher
    /// (sorted); `bestVoxel` and `firstVoxel` are not set (whole indices below).
    std::vector<skeleton::Cluster> clusters;
    std::vector<std::int64_t> bestVoxel_Whole;  ///< per cluster, its voxel of largest BS
    std::vector<std::int64_t> firstVoxel_Whole; ///< per cluster, its smallest linear index
    std::uint64_t gatheredValues = 0;           ///< 64-bit values sent, all ranks
    int exchanges = 0;                          ///< AllGathers
  };

  /// Collective. `ss_mm`: the component's SS code per piece vessel voxel (the single run's,
  /// infinite off the component; DistributedSeedCode::ss). `bs_mm`: the BS code, exact on the
  /// owned voxels (DistributedBoundaryCode). `inverseBandWidth`: VoxelGrid's (float).
  static Graph build(const PieceLayout& layout,
    const SparseVesselMask& pieceMask,
    const std::array<double, 3>& spacing_mm,
    float inverseBandWidth,
    const std::vector<float>& ss_mm,
    const std::vector<float>& bs_mm,
    RankCollectives& collectives);
};

} // namespace vtouch

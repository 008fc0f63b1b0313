// Private to Logic/Skeleton: stage 3 of vtouch::VoxelCoder, the clusters and the cluster graph.
#pragma once

#include "vtouchSkeletonClusterGraph.h"
#include "vtouchSkeletonRunMeter.h"
#include "vtouchSkeletonVoxelCodes.h"
#include "vtouchSkeletonVoxelGrid.h"

#include <cstdint>
#include <optional>

namespace vtouch
{
namespace skeleton
{

/// Clusters (Zhou & Toga 1999, the voxel coding of Yi & Hayward §3.1): the connected parts of the
/// bands of equal SS code (VoxelGrid::bandWidth thick), linked where clusters of different bands
/// touch; and the choice of the tree's root at its thickest end.
///
/// Input: the grid, the final BS code and the SS code of one component (`codes.order`). Output:
/// `graph` (clusters in SS order, neighbour lists sorted, each voxel's label).
class ClusterStage
{
public:
  ClusterStage(const VoxelGrid& grid,
    RunMeter& meter,
    const VoxelCodes& codes,
    ClusterGraph& graph);

  /// Builds the clusters and their graph from the current codes (replacing the last ones).
  void build();

  /// Any extremity gives a valid SS code, but back-tracing toward a thin end cuts the corners of
  /// the bifurcations on the way (the geodesic hugs the inner wall of a sharp turn). Rooting the
  /// code at the thickest extremity (the inflow trunk of a vascular tree) makes every trace enter
  /// the trunk at an obtuse angle. The root voxel of the thickest end when it is clearly (20 %)
  /// thicker than the current root's end; the caller then propagates again and rebuilds. The
  /// rule is skeleton::thickerEnd (vtouchSkeletonThickerEnd.h, shared with the distributed run,
  /// vtouch::DistributedRootChoice), read in the clusters' key order; the voxel is the one at the
  /// end cluster's integer centroid when vessel, else its voxel of largest BS (ties to the lower
  /// SS, then the smaller index). Project rules (issue 19 item 2): order and centroid are ones a
  /// distributed run reproduces.
  std::optional<std::uint32_t> thickerRoot() const;

  /// Where a trace starts in cluster `c`: the voxel at its centroid when it is vessel (the last
  /// band at a flat or rounded end is a ring or cap centred on the axis), else its most central
  /// voxel.
  static std::uint32_t tipStart(const VoxelGrid& grid, const Cluster& c);

private:
  const VoxelGrid& grid;
  RunMeter& meter;
  const VoxelCodes& codes;
  ClusterGraph& graph;
};

} // namespace skeleton
} // namespace vtouch

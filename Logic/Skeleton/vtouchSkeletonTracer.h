// Private to Logic/Skeleton: back-tracing on the codes, shared by the trace and loop stages.
#pragma once

#include "vtouchSkeletonClusterGraph.h"
#include "vtouchSkeletonDraft.h"
#include "vtouchSkeletonRunMeter.h"
#include "vtouchSkeletonVoxelCodes.h"
#include "vtouchSkeletonVoxelGrid.h"

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <unordered_map>
#include <utility>
#include <vector>

namespace vtouch
{
namespace skeleton
{

/// A descent from a start voxel to the skeleton (or the root).
struct Trace
{
  std::vector<std::uint32_t> voxels; // from the start down, excluding the attachment point
  int path = -1;                     // attachment (path, point); -1 = free end (the root)
  int point = -1;
  double length = 0.0; // mm
};

/// Center-adjusted back-tracing (Zhou & Toga 1999; Yi & Hayward §3.1) and the making of paths from
/// traces: the operations TraceStage and LoopStage share.
///
/// Inputs: the grid, the final codes and the cluster graph of one component. Outputs: the paths
/// and junctions it emits into `draft`, the clusters' (path, point) and the kSkeleton flags (the
/// voxels on a path, which later traces stop at).
class SkeletonTracer
{
public:
  SkeletonTracer(const VoxelGrid& grid,
    RunMeter& meter,
    VoxelCodes& codes,
    ClusterGraph& graph,
    SkeletonDraft& draft);

  /// Center-adjusted back-tracing: from `start`, step to the 26-neighbour of lower SS code with the
  /// largest BS code (the ridge of the distance map, i.e. the vessel centre) until the trace
  /// touches the skeleton already traced, or reaches the root. Touches are ignored while the SS
  /// code is above `ignoreAbove` (a loop closure starts next to the skeleton). If the trace runs
  /// alongside the skeleton through more than `patience` clusters already on it without touching,
  /// it attaches to the current cluster's point.
  Trace descend(std::uint32_t start, float ignoreAbove, std::size_t patience) const;

  /// Makes a path of `t` reversed: head at the attachment (or the root), tail at the start voxel,
  /// or, with `tailPath` >= 0, at point (tailPath, tailPoint) of the skeleton (a loop closure).
  void emitPath(const Trace& t, bool startOnBorder, int tailPath, int tailPoint);

  /// Center adjustment: the centroid of the voxels of `lin`'s cluster (a slab of the SS code across
  /// the vessel) that lie within about one radius of it. Restricting the slab to the neighbourhood
  /// keeps the point in its own branch where a slab still spans two branches near a bifurcation.
  Point_mm adjustedCenter(std::uint32_t lin);

  double radiusAt(std::uint32_t lin) const
  {
    // BS is the distance to the nearest background voxel centre. The wall lies about half a voxel
    // before that centre, and the traced voxel sits up to half a voxel off the true axis (the
    // adjusted centre does not): the two biases cancel on average (calibrated on phantoms).
    return std::max(static_cast<double>(codes.bs[grid.mask.rank(lin)]), 0.5 * grid.minSpacing);
  }

  /// How many clusters already on the skeleton a trace from `c` may run alongside (descend()).
  std::size_t patienceFor(const Cluster& c) const
  {
    return static_cast<std::size_t>(
             std::ceil(4.0 * std::max(1.0, static_cast<double>(c.maxBs)) / grid.bandWidth)) +
           3;
  }

  std::uint32_t clusterOf(std::uint32_t lin) const
  {
    return graph.clusterOfRank(grid.mask.rank(lin));
  }

  /// The vessel radius at a point of a path (vtouch::nearbyRadius).
  double nearbyRadius(int path, int point) const;

  // The stage's inputs and outputs, which the stages that use the tracer share.
  const VoxelGrid& grid;
  RunMeter& meter;
  VoxelCodes& codes; // reads bs and ss; the kRegion and kSkeleton flags
  ClusterGraph& graph;
  SkeletonDraft& draft;
  RawSkeleton& out; // draft.skeleton

private:
  /// The voxel of largest BS in `lin`'s slab (cluster) within the distance the ridge can be from
  /// it: where a trace that was held off the ridge should have been.
  std::uint32_t ridgeVoxelNear(std::uint32_t lin, std::uint32_t cluster);
  /// A skeleton voxel at or next to `lin`, as (path, point), or path -1.
  std::pair<int, int> touchedSkeleton(std::uint32_t lin) const;
  void markPoint(int path, int point, std::uint32_t lin);

  std::unordered_map<std::uint32_t, std::pair<int, int>> skeletonVoxel; // lin -> (path, point)
  std::vector<std::uint32_t> scratch, ridgeScratch;
};

} // namespace skeleton
} // namespace vtouch

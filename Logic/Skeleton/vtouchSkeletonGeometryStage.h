// Private to Logic/Skeleton: stage 7 of vtouch::VoxelCoder, the paths' geometry at junctions.
#pragma once

#include "vtouchVoxelCoding.h"

#include <cstddef>
#include <vector>

namespace vtouch
{
namespace skeleton
{

/// The centres of the paths at their junctions. Back-tracing bends a path toward the crotch of
/// every junction it runs through (the merged lumen's ridge is off both vessels' axes): a vessel
/// running through a junction gets its own axis back there (vtouchJunctionRecentring.h), and a
/// path through a bifurcation is straightened beyond it.
///
/// Input: the paths and junctions from `firstPath` (topology final). Output: the same paths with
/// moved centres near junctions; voxels, radii and junctions unchanged.
class GeometryStage
{
public:
  GeometryStage(RawSkeleton& skeleton, std::size_t firstPath, double minSpacing_mm);

  void run();

  /// The mirror of TraceStage's join along the branch axis for a path that goes on through a
  /// bifurcation: beyond the junction (toward its tail, the other child) its trace runs on the
  /// ridge of the merged lumen, inside the child's own axis. Its centres within one junction
  /// radius of the junction point are put on the straight line from the junction to the first
  /// centre beyond that radius. Junctions already `recentred` (a vessel running through) are left
  /// alone.
  void straightenThroughPaths(const std::vector<bool>& recentred);

private:
  RawSkeleton& out;
  std::size_t firstPath; // the component's first path
  double minSpacing_mm;  // the smallest voxel side
};

} // namespace skeleton
} // namespace vtouch

// Private to Logic/Skeleton: the skeleton of a voxel-coding run while its stages build it.
#pragma once

#include "vtouchVoxelCoding.h"

#include <array>
#include <vector>

namespace vtouch
{
namespace skeleton
{

/// The paths and junctions found so far (over all components) and what the end stage needs to
/// know about each path's free ends.
struct SkeletonDraft
{
  RawSkeleton skeleton;
  /// Per path: its head / tail end is a rounded vessel end inside the volume (not a junction, not
  /// cut by the volume's border, not a loop closure). Written by SkeletonTracer, read by EndStage.
  std::vector<std::array<bool, 2>> closedEnd;
};

} // namespace skeleton
} // namespace vtouch

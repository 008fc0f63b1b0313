// Private to Logic/Skeleton: the per-vessel-voxel arrays of a voxel-coding run (indexed by rank).
#pragma once

#include <cstdint>
#include <limits>
#include <vector>

namespace vtouch
{
namespace skeleton
{

/// The two codes of voxel coding (Zhou & Toga 1999, Yi & Hayward §3.1's ref. [32]) and the flags
/// the stages keep per vessel voxel. Each array is written by one stage (named) and read by the
/// later ones.
struct VoxelCodes
{
  static constexpr float kInf = std::numeric_limits<float>::infinity();
  // Bits of `flags`, each owned by one stage:
  static constexpr std::uint8_t kDone = 1; // SeedCodeStage: finalized in the current propagation
  static constexpr std::uint8_t kComponent =
    2;                                         // VoxelCoder: belongs to a component already handled
  static constexpr std::uint8_t kRegion = 4;   // scratch of a flood fill, cleared after each use
  static constexpr std::uint8_t kSkeleton = 8; // SkeletonTracer: on a traced path

  std::vector<float> bs;            // BoundaryCodeStage: distance to the nearest background, mm
  std::vector<float> ss;            // SeedCodeStage: geodesic distance from the root, mm
  std::vector<std::uint8_t> flags;  // the bits above
  std::vector<std::uint32_t> order; // SeedCodeStage: one component's voxels (lin) in SS order
};

} // namespace skeleton
} // namespace vtouch

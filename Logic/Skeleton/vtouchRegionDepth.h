// Depth of every voxel of a region: the number of 26-connected layers to its border (1 on the
// border: a voxel with a 6-neighbour outside the region or the volume). A chessboard distance
// transform in voxels, linear in the region's voxels (breadth-first from the border), indexed by
// the mask's rank. It is the radius of the largest cube of voxels centred there, the local scale
// the tubularity and the neck cutter work at.
#pragma once

#include "vtouchProgress.h"
#include "vtouchSparseVesselMask.h"

#include <cstdint>
#include <vector>

namespace vtouch
{

class RegionDepth
{
public:
  /// depth[mask.rank(lin)] for every voxel of `mask` (finalized). `progress`: check points every
  /// 2^16 voxels (may throw Cancelled).
  static std::vector<std::uint16_t> layers(const SparseVesselMask& mask,
    const ProgressSpan& progress = ProgressSpan());
};

} // namespace vtouch

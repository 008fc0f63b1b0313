// Reading one box of voxels out of a raw voxel block (vtouchRawVoxelLayout): one file read per run
// of contiguous bytes (a row of the box; a whole slab when the box spans whole rows or slices),
// so a piece of a large volume costs its own bytes, not the file's. Internal to VesselTouchIO.
#ifndef vtouchRawExtentRead_h
#define vtouchRawExtentRead_h

#include "vtouchRawVoxelLayout.h"

namespace vtouch
{

/// Reads `extent` of the `dimensions` volume stored as `layout` (voxels of `voxelBytes` bytes) into
/// `buffer`, x fastest. Byte order is fixed on the way. Progress is reported per slice; returns
/// false when it asks to abort. Throws VolumeIOError when the file cannot be read.
bool readRawExtent(const RawVoxelLayout& layout,
  const std::array<std::size_t, 3>& dimensions,
  std::size_t voxelBytes,
  const VoxelExtent& extent,
  void* buffer,
  const VolumeProgress& progress,
  VolumeReadStatistics& statistics);

/// Copies `extent` out of a whole volume held in memory (x fastest) into `buffer`.
void copyExtent(const void* whole,
  const std::array<std::size_t, 3>& dimensions,
  std::size_t voxelBytes,
  const VoxelExtent& extent,
  void* buffer);

} // namespace vtouch

#endif

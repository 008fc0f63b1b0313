// A piece read again with a larger extent (issue 19: a distributed VesselCenterline asks its
// reader for the rank's piece grown by the ghost margin, after the view had the piece itself):
// the voxels already in memory are copied, and only the boxes of the new extent that the old one
// does not cover are read from the file. Pure index arithmetic on VoxelExtent; no file, no VTK.
#ifndef vtouchExtentReuse_h
#define vtouchExtentReuse_h

#include "vtouchVolumeIO.h"

#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

namespace vtouch
{
/// The voxels both extents hold, or nothing when they do not meet.
std::optional<VoxelExtent> intersectExtents(const VoxelExtent& a, const VoxelExtent& b);

/// `wanted` minus `have`: at most 6 disjoint boxes that with wanted ∩ have tile `wanted` exactly
/// (z slabs below and above the overlap, then y slabs and x slabs inside its z range). `wanted`
/// itself when they do not meet; nothing when `have` covers `wanted`.
std::vector<VoxelExtent> extentDifference(const VoxelExtent& wanted, const VoxelExtent& have);

/// Copies the voxels of `box` from `source` (an array laid out over `sourceExtent`, x fastest)
/// into `target` (laid out over `targetExtent`), one x row at a time. `box` must lie in both
/// extents (checked: throws VolumeIOError otherwise).
void copyExtentVoxels(const void* source,
  const VoxelExtent& sourceExtent,
  void* target,
  const VoxelExtent& targetExtent,
  const VoxelExtent& box,
  std::size_t voxelBytes);

/// True when `inner` lies inside `outer` on every axis.
bool extentContains(const VoxelExtent& outer, const VoxelExtent& inner);

/// What readExtentReusing() took from the file and from memory.
struct ExtentReuseStatistics
{
  VolumeReadStatistics read; ///< summed over the boxes read from the file
  std::uint64_t bytesReused = 0;
};

/// Fills `buffer` (laid out over `extent`, `bytes` long) with the voxels of `extent`: those
/// inside `previousExtent` copied from `previous` (the voxels of that extent, same voxel type,
/// x fastest), the rest read from `source` box by box (extentDifference). `previous` may be null
/// (all read). A source that reads slices whole (readsPartialSlicesAlone() false: DICOM) copies
/// only when the overlap spans the extent's whole x and y range (it spares whole slices; the
/// boxes beside a narrower overlap would read its slices again). Returns false when `progress`
/// asked to abort. Throws VolumeIOError as
/// VolumeSource::readExtent. Only for sources that read extents alone (a compressed source
/// would decode the whole file once per box).
bool readExtentReusing(VolumeSource& source,
  const VoxelExtent& extent,
  void* buffer,
  std::size_t bytes,
  const void* previous,
  const VoxelExtent& previousExtent,
  const VolumeProgress& progress,
  ExtentReuseStatistics& statistics);
} // namespace vtouch

#endif

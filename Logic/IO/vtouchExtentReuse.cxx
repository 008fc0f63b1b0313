#include "vtouchExtentReuse.h"

#include <algorithm>
#include <cstring>

namespace vtouch
{
std::optional<VoxelExtent> intersectExtents(const VoxelExtent& a, const VoxelExtent& b)
{
  VoxelExtent both;
  for (int axis = 0; axis < 3; ++axis)
  {
    both.first[axis] = std::max(a.first[axis], b.first[axis]);
    both.last[axis] = std::min(a.last[axis], b.last[axis]);
    if (both.first[axis] > both.last[axis])
    {
      return std::nullopt;
    }
  }
  return both;
}

bool extentContains(const VoxelExtent& outer, const VoxelExtent& inner)
{
  for (int axis = 0; axis < 3; ++axis)
  {
    if (inner.first[axis] < outer.first[axis] || inner.last[axis] > outer.last[axis])
    {
      return false;
    }
  }
  return true;
}

std::vector<VoxelExtent> extentDifference(const VoxelExtent& wanted, const VoxelExtent& have)
{
  const std::optional<VoxelExtent> both = intersectExtents(wanted, have);
  if (!both)
  {
    return { wanted };
  }
  std::vector<VoxelExtent> boxes;
  // Peel axis by axis, z first (whole slabs are the cheapest reads of an x-fastest file): what
  // lies below and above the overlap on this axis, across the part of the earlier axes' range
  // still left, then narrow that part to the overlap's range on this axis.
  VoxelExtent rest = wanted;
  for (int axis = 2; axis >= 0; --axis)
  {
    if (rest.first[axis] < both->first[axis])
    {
      VoxelExtent below = rest;
      below.last[axis] = both->first[axis] - 1;
      boxes.push_back(below);
    }
    if (rest.last[axis] > both->last[axis])
    {
      VoxelExtent above = rest;
      above.first[axis] = both->last[axis] + 1;
      boxes.push_back(above);
    }
    rest.first[axis] = both->first[axis];
    rest.last[axis] = both->last[axis];
  }
  return boxes;
}

void copyExtentVoxels(const void* source,
  const VoxelExtent& sourceExtent,
  void* target,
  const VoxelExtent& targetExtent,
  const VoxelExtent& box,
  std::size_t voxelBytes)
{
  if (!extentContains(sourceExtent, box) || !extentContains(targetExtent, box))
  {
    throw VolumeIOError("copyExtentVoxels: the box is not inside both extents");
  }
  const std::array<std::size_t, 3> from = sourceExtent.size();
  const std::array<std::size_t, 3> to = targetExtent.size();
  const std::size_t rowBytes = (box.last[0] - box.first[0] + 1) * voxelBytes;
  const auto* in = static_cast<const unsigned char*>(source);
  auto* out = static_cast<unsigned char*>(target);
  for (std::size_t k = box.first[2]; k <= box.last[2]; ++k)
  {
    for (std::size_t j = box.first[1]; j <= box.last[1]; ++j)
    {
      const std::size_t inIndex = ((k - sourceExtent.first[2]) * from[1] +
                                    (j - sourceExtent.first[1])) * from[0] +
        (box.first[0] - sourceExtent.first[0]);
      const std::size_t outIndex = ((k - targetExtent.first[2]) * to[1] +
                                     (j - targetExtent.first[1])) * to[0] +
        (box.first[0] - targetExtent.first[0]);
      std::memcpy(out + outIndex * voxelBytes, in + inIndex * voxelBytes, rowBytes);
    }
  }
}

bool readExtentReusing(VolumeSource& source,
  const VoxelExtent& extent,
  void* buffer,
  std::size_t bytes,
  const void* previous,
  const VoxelExtent& previousExtent,
  const VolumeProgress& progress,
  ExtentReuseStatistics& statistics)
{
  statistics = ExtentReuseStatistics{};
  const std::size_t voxelBytes = voxelSize(source.header().voxelType);
  if (bytes < extent.voxelCount() * voxelBytes)
  {
    throw VolumeIOError("readExtentReusing: the buffer is too small for the extent");
  }
  std::optional<VoxelExtent> both =
    previous ? intersectExtents(extent, previousExtent) : std::nullopt;
  if (both && !source.readsPartialSlicesAlone() &&
      (both->first[0] != extent.first[0] || both->last[0] != extent.last[0] ||
        both->first[1] != extent.first[1] || both->last[1] != extent.last[1]))
  {
    // Slices read whole (DICOM): the boxes beside the overlap would read its slices again, so
    // copying saves nothing there. Reuse only what spares whole slices.
    both.reset();
  }
  if (both)
  {
    copyExtentVoxels(previous, previousExtent, buffer, extent, *both, voxelBytes);
    statistics.bytesReused = both->voxelCount() * voxelBytes;
  }
  const std::vector<VoxelExtent> boxes =
    both ? extentDifference(extent, *both) : std::vector<VoxelExtent>{ extent };
  std::size_t total = 0;
  for (const VoxelExtent& b : boxes)
  {
    total += b.voxelCount();
  }
  std::size_t done = 0;
  std::vector<unsigned char> scratch;
  for (const VoxelExtent& b : boxes)
  {
    const double start = total ? static_cast<double>(done) / total : 0.0;
    const double share = total ? static_cast<double>(b.voxelCount()) / total : 0.0;
    const VolumeProgress scaled = [&](double f)
    { return progress ? progress(start + share * f) : true; };
    const std::size_t boxBytes = b.voxelCount() * voxelBytes;
    // A box spanning the extent's whole x and y range (a z slab) is contiguous in the buffer:
    // read in place; any other box through a scratch buffer, copied row by row.
    const bool slab = b.first[0] == extent.first[0] && b.last[0] == extent.last[0] &&
      b.first[1] == extent.first[1] && b.last[1] == extent.last[1];
    if (slab)
    {
      const std::array<std::size_t, 3> size = extent.size();
      const std::size_t offset = (b.first[2] - extent.first[2]) * size[0] * size[1] * voxelBytes;
      if (!source.readExtent(b, static_cast<unsigned char*>(buffer) + offset, boxBytes, scaled))
      {
        return false;
      }
    }
    else
    {
      scratch.resize(boxBytes);
      if (!source.readExtent(b, scratch.data(), boxBytes, scaled))
      {
        return false;
      }
      copyExtentVoxels(scratch.data(), b, buffer, extent, b, voxelBytes);
    }
    statistics.read.bytesRead += source.lastReadStatistics().bytesRead;
    statistics.read.filesRead += source.lastReadStatistics().filesRead;
    done += b.voxelCount();
  }
  return true;
}
} // namespace vtouch


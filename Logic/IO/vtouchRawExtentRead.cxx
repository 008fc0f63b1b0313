#include "vtouchRawExtentRead.h"

#include <algorithm>
#include <cstring>
#include <fstream>

namespace vtouch
{
namespace
{
void swapEachVoxel(char* bytes, std::size_t count, std::size_t voxelBytes)
{
  for (std::size_t v = 0; v < count; ++v)
  {
    std::reverse(bytes + v * voxelBytes, bytes + (v + 1) * voxelBytes);
  }
}
} // namespace

bool readRawExtent(const RawVoxelLayout& layout,
  const std::array<std::size_t, 3>& dimensions,
  std::size_t voxelBytes,
  const VoxelExtent& extent,
  void* buffer,
  const VolumeProgress& progress,
  VolumeReadStatistics& statistics)
{
  statistics = VolumeReadStatistics();
  std::ifstream in(layout.dataFile, std::ios::binary);
  if (!in)
  {
    throw VolumeIOError("cannot open the voxel data file '" + layout.dataFile + "'");
  }
  statistics.filesRead = 1;
  const std::array<std::size_t, 3> n = extent.size();
  const std::size_t nx = dimensions[0];
  const std::size_t ny = dimensions[1];
  // The longest runs that are contiguous in the file: whole slices of the box when it spans whole
  // rows and columns, whole rows-blocks of a slice when it spans whole rows, else single rows.
  const bool wholeRows = n[0] == nx;
  const bool wholeSlices = wholeRows && n[1] == ny;
  const std::size_t rowBytes = n[0] * voxelBytes;
  char* out = static_cast<char*>(buffer);
  auto readRun = [&](std::size_t i, std::size_t j, std::size_t k, std::size_t bytes)
  {
    const std::uint64_t at = layout.byteOffset + ((k * ny + j) * nx + i) * voxelBytes;
    in.seekg(static_cast<std::streamoff>(at));
    if (!in.read(out, static_cast<std::streamsize>(bytes)))
    {
      throw VolumeIOError(
        "cannot read the voxels of '" + layout.dataFile + "' (truncated or unreadable file)");
    }
    if (layout.swapBytes)
    {
      swapEachVoxel(out, bytes / voxelBytes, voxelBytes);
    }
    out += bytes;
    statistics.bytesRead += bytes;
  };
  if (wholeSlices)
  {
    // One read per slice (not one for the whole slab) keeps progress and abort responsive.
    for (std::size_t k = extent.first[2]; k <= extent.last[2]; ++k)
    {
      if (progress && !progress(static_cast<double>(k - extent.first[2]) / n[2]))
      {
        return false;
      }
      readRun(0, 0, k, n[0] * n[1] * voxelBytes);
    }
  }
  else
  {
    for (std::size_t k = extent.first[2]; k <= extent.last[2]; ++k)
    {
      if (progress && !progress(static_cast<double>(k - extent.first[2]) / n[2]))
      {
        return false;
      }
      if (wholeRows)
      {
        readRun(0, extent.first[1], k, n[1] * rowBytes);
        continue;
      }
      for (std::size_t j = extent.first[1]; j <= extent.last[1]; ++j)
      {
        readRun(extent.first[0], j, k, rowBytes);
      }
    }
  }
  return progress ? progress(1.0) : true;
}

void copyExtent(const void* whole,
  const std::array<std::size_t, 3>& dimensions,
  std::size_t voxelBytes,
  const VoxelExtent& extent,
  void* buffer)
{
  const std::array<std::size_t, 3> n = extent.size();
  const char* in = static_cast<const char*>(whole);
  char* out = static_cast<char*>(buffer);
  const std::size_t rowBytes = n[0] * voxelBytes;
  for (std::size_t k = extent.first[2]; k <= extent.last[2]; ++k)
  {
    for (std::size_t j = extent.first[1]; j <= extent.last[1]; ++j)
    {
      const std::size_t at = ((k * dimensions[1] + j) * dimensions[0] + extent.first[0]);
      std::memcpy(out, in + at * voxelBytes, rowBytes);
      out += rowBytes;
    }
  }
}

} // namespace vtouch

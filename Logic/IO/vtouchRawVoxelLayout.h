// Where the voxels of an uncompressed volume file sit on disk, so that a part of the volume can be
// read without reading the rest (issue 19: every rank of a parallel pvserver reads only its piece).
// Found from the file's own header for the three formats that store voxels as one raw block:
// NIfTI-1 (.nii, .hdr/.img), NRRD (raw encoding, attached or one detached data file) and MetaImage
// (LOCAL or one raw data file). Anything else (gzip, lists of data files, NIfTI intensity scaling,
// more than three axes) has no raw layout and is read whole by ITK. Internal to VesselTouchIO.
#ifndef vtouchRawVoxelLayout_h
#define vtouchRawVoxelLayout_h

#include "vtouchVolumeIO.h"

#include <cstdint>
#include <optional>
#include <string>

namespace vtouch
{

/// Voxel (i, j, k) of an nx x ny x nz volume sits at byteOffset + ((k * ny + j) * nx + i) * size
/// in dataFile, `size` bytes in the file's byte order.
struct RawVoxelLayout
{
  std::string dataFile;
  std::uint64_t byteOffset = 0;
  /// The file's byte order differs from this machine's: each voxel's bytes are reversed on read.
  bool swapBytes = false;
};

/// The raw layout of `path` (a .nii, .hdr, .nrrd, .nhdr, .mha or .mhd file whose header ITK has
/// already accepted as `header`), or nothing when its voxels are not one uncompressed block of
/// header.voxelType values, or the data file is shorter than the volume.
std::optional<RawVoxelLayout> findRawVoxelLayout(const std::string& path,
  const VolumeHeader& header);

} // namespace vtouch

#endif

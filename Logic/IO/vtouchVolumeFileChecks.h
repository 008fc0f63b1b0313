// Truncation checks that ITK IO does not make itself: MetaImage and NIfTI readers (ITK 5.2) print
// "data not read completely" and return success on a short file, and GDCM fills a short slice
// silently. Each check throws VolumeIOError when the voxel data cannot be complete. Internal to
// VesselTouchIO.
#ifndef vtouchVolumeFileChecks_h
#define vtouchVolumeFileChecks_h

#include <cstddef>
#include <string>

namespace vtouch
{

/// .nii: the file holds vox_offset + nvox * bitpix / 8 bytes. .nii.gz: the gzip trailer (ISIZE,
/// the uncompressed size modulo 2^32) matches that size. Other NIfTI forms are not checked.
void checkNiftiComplete(const std::string& path);

/// .mha: the bytes after the "ElementDataFile = LOCAL" line; .mhd: the size of the one data file
/// it names. Compressed data is not checked (zlib reports its own errors).
void checkMetaImageComplete(const std::string& path, std::size_t rawBytes);

/// A DICOM file is at least as long as its meta header and data set announce (one full GDCM
/// parse of the file).
void checkDicomSliceComplete(const std::string& path);

} // namespace vtouch

#endif

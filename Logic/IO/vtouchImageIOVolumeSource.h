// A VolumeSource over one ITK ImageIO (NIfTI, NRRD, MetaImage, a DICOM multi-frame file): the IO
// reads straight into the caller's buffer. A part of an uncompressed file is read from its raw
// layout (only that part's bytes); a part of a compressed file is decoded whole by ITK and cut out.
// Internal to VesselTouchIO.
#ifndef vtouchImageIOVolumeSource_h
#define vtouchImageIOVolumeSource_h

#include "vtouchRawVoxelLayout.h"
#include "vtouchVolumeIO.h"

#include <itkImageIOBase.h>

namespace vtouch
{

/// The voxel type of an ITK component type; throws VolumeIOError for unsupported ones.
VoxelType voxelTypeFromITK(itk::IOComponentEnum component, const std::string& path);

/// Checks that `io` (after ReadImageInformation) describes one scalar 3D volume (a 4D image with a
/// single time point counts as 3D) and fills `header` from it. Throws VolumeIOError otherwise.
void headerFromImageIO(const itk::ImageIOBase& io, const std::string& path, VolumeHeader& header);

class ImageIOVolumeSource : public VolumeSource
{
public:
  /// `io` must not have read the header yet; `format` names the file format in messages.
  ImageIOVolumeSource(itk::ImageIOBase::Pointer io, const std::string& path, const char* format);
  bool readExtent(const VoxelExtent& extent,
    void* buffer,
    std::size_t bytes,
    const VolumeProgress& progress) override;
  bool readsExtentsAlone() const override { return this->Layout.has_value(); }

private:
  /// The whole volume through ITK (compressed or otherwise non-raw files).
  bool readWholeWithITK(void* buffer, const VolumeProgress& progress);

  itk::ImageIOBase::Pointer IO;
  std::string Path;
  std::optional<RawVoxelLayout> Layout;
};

} // namespace vtouch

#endif

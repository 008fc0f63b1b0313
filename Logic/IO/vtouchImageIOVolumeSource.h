// A VolumeSource over one ITK ImageIO (NIfTI, NRRD, MetaImage, a DICOM multi-frame file): the IO
// reads straight into the caller's buffer. Internal to VesselTouchIO.
#ifndef vtouchImageIOVolumeSource_h
#define vtouchImageIOVolumeSource_h

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
  bool read(void* buffer, std::size_t bytes, const VolumeProgress& progress) override;

private:
  itk::ImageIOBase::Pointer IO;
  std::string Path;
};

} // namespace vtouch

#endif

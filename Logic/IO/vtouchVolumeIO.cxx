#include "vtouchVolumeIO.h"

#include "vtouchDicomSeries.h"
#include "vtouchHeaderText.h"
#include "vtouchImageIOVolumeSource.h"

#include <itkMetaImageIO.h>
#include <itkNiftiImageIO.h>
#include <itkNrrdImageIO.h>

#include <algorithm>
#include <cctype>
#include <filesystem>

namespace vtouch
{

std::size_t voxelSize(VoxelType type)
{
  switch (type)
  {
    case VoxelType::Int8:
    case VoxelType::UInt8:
      return 1;
    case VoxelType::Int16:
    case VoxelType::UInt16:
      return 2;
    case VoxelType::Int32:
    case VoxelType::UInt32:
    case VoxelType::Float32:
      return 4;
    case VoxelType::Float64:
      return 8;
  }
  return 0;
}

const char* toString(VoxelType type)
{
  switch (type)
  {
    case VoxelType::Int8:
      return "int8";
    case VoxelType::UInt8:
      return "uint8";
    case VoxelType::Int16:
      return "int16";
    case VoxelType::UInt16:
      return "uint16";
    case VoxelType::Int32:
      return "int32";
    case VoxelType::UInt32:
      return "uint32";
    case VoxelType::Float32:
      return "float32";
    case VoxelType::Float64:
      return "float64";
  }
  return "unknown";
}

std::size_t VolumeGeometry::voxelCount() const
{
  return this->dimensions[0] * this->dimensions[1] * this->dimensions[2];
}

std::array<double, 3> VolumeGeometry::worldPosition(double i, double j, double k) const
{
  const double index[3] = {
    i * this->spacing_mm[0], j * this->spacing_mm[1], k * this->spacing_mm[2]
  };
  std::array<double, 3> world = this->origin_mm;
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 3; ++c)
    {
      world[r] += this->direction[3 * r + c] * index[c];
    }
  }
  return world;
}

VolumeGeometry VolumeGeometry::inFrame(WorldFrame frame) const
{
  VolumeGeometry g = *this;
  if (frame == WorldFrame::RAS)
  {
    // RAS = diag(-1, -1, 1) * LPS, applied to points (origin) and to directions (rows of D).
    for (int r = 0; r < 2; ++r)
    {
      g.origin_mm[r] = -g.origin_mm[r];
      for (int c = 0; c < 3; ++c)
      {
        g.direction[3 * r + c] = -g.direction[3 * r + c];
      }
    }
  }
  return g;
}

std::size_t VolumeHeader::byteCount() const
{
  return this->geometry.voxelCount() * voxelSize(this->voxelType);
}

VoxelExtent VoxelExtent::whole(const std::array<std::size_t, 3>& dimensions)
{
  VoxelExtent extent;
  for (int a = 0; a < 3; ++a)
  {
    extent.last[a] = dimensions[a] > 0 ? dimensions[a] - 1 : 0;
  }
  return extent;
}

std::array<std::size_t, 3> VoxelExtent::size() const
{
  std::array<std::size_t, 3> n{ { 0, 0, 0 } };
  for (int a = 0; a < 3; ++a)
  {
    n[a] = this->last[a] >= this->first[a] ? this->last[a] - this->first[a] + 1 : 0;
  }
  return n;
}

std::size_t VoxelExtent::voxelCount() const
{
  const std::array<std::size_t, 3> n = this->size();
  return n[0] * n[1] * n[2];
}

bool VoxelExtent::isWithin(const std::array<std::size_t, 3>& dimensions) const
{
  for (int a = 0; a < 3; ++a)
  {
    if (this->first[a] > this->last[a] || this->last[a] >= dimensions[a])
    {
      return false;
    }
  }
  return true;
}

bool VolumeSource::read(void* buffer, std::size_t bytes, const VolumeProgress& progress)
{
  return this->readExtent(
    VoxelExtent::whole(this->Header.geometry.dimensions), buffer, bytes, progress);
}

void VolumeSource::checkExtentRequest(const VoxelExtent& extent,
  const void* buffer,
  std::size_t bytes) const
{
  const std::array<std::size_t, 3>& dims = this->Header.geometry.dimensions;
  if (!extent.isWithin(dims))
  {
    throw VolumeIOError("the requested voxel extent [" + std::to_string(extent.first[0]) + ".." +
                        std::to_string(extent.last[0]) + ", " + std::to_string(extent.first[1]) +
                        ".." + std::to_string(extent.last[1]) + ", " +
                        std::to_string(extent.first[2]) + ".." + std::to_string(extent.last[2]) +
                        "] is not inside the " + std::to_string(dims[0]) + " x " +
                        std::to_string(dims[1]) + " x " + std::to_string(dims[2]) + " volume");
  }
  if (!buffer || bytes < extent.voxelCount() * voxelSize(this->Header.voxelType))
  {
    throw VolumeIOError("internal error: the voxel buffer is too small");
  }
}

namespace
{
enum class FileKind
{
  NIfTI,
  NRRD,
  MetaImage,
  Other
};

FileKind kindFromName(const std::string& path)
{
  const std::string name = lowerCase(std::filesystem::path(path).filename().string());
  for (const char* ext : { ".nii", ".nii.gz", ".hdr", ".img", ".img.gz" })
  {
    if (endsWith(name, ext))
    {
      return FileKind::NIfTI;
    }
  }
  if (endsWith(name, ".nrrd") || endsWith(name, ".nhdr"))
  {
    return FileKind::NRRD;
  }
  if (endsWith(name, ".mha") || endsWith(name, ".mhd"))
  {
    return FileKind::MetaImage;
  }
  return FileKind::Other;
}

// The IOs are created directly, not through itk::ImageIOFactory: no factory registration is
// needed, and the format is decided by the extension, never by whichever factory answers first.
itk::ImageIOBase::Pointer imageIOFor(FileKind kind)
{
  switch (kind)
  {
    case FileKind::NIfTI:
      return itk::NiftiImageIO::New().GetPointer();
    case FileKind::NRRD:
      return itk::NrrdImageIO::New().GetPointer();
    case FileKind::MetaImage:
      return itk::MetaImageIO::New().GetPointer();
    case FileKind::Other:
      break;
  }
  return nullptr;
}

const char* formatName(FileKind kind)
{
  switch (kind)
  {
    case FileKind::NIfTI:
      return "NIfTI";
    case FileKind::NRRD:
      return "NRRD";
    case FileKind::MetaImage:
      return "MetaImage";
    case FileKind::Other:
      break;
  }
  return "DICOM";
}
} // namespace

std::unique_ptr<VolumeSource> openVolume(const std::string& path, const VolumeOpenOptions& options)
{
  namespace fs = std::filesystem;
  std::error_code ec;
  if (path.empty())
  {
    throw VolumeIOError("no file name given");
  }
  if (!fs::exists(path, ec))
  {
    throw VolumeIOError("'" + path + "' does not exist");
  }
  if (fs::is_directory(path, ec))
  {
    return openDicomSeries(path, options);
  }
  const FileKind kind = kindFromName(path);
  if (kind == FileKind::Other)
  {
    if (!isDicomFile(path))
    {
      throw VolumeIOError(
        "'" + path + "' is neither a DICOM file nor a .nii/.nii.gz/.nrrd/.nhdr/.mha/.mhd volume");
    }
    return openDicomSeries(path, options);
  }
  return std::make_unique<ImageIOVolumeSource>(imageIOFor(kind), path, formatName(kind));
}

bool canReadVolume(const std::string& path)
{
  namespace fs = std::filesystem;
  std::error_code ec;
  if (path.empty() || !fs::exists(path, ec))
  {
    return false;
  }
  if (fs::is_directory(path, ec))
  {
    // Look at a few entries only: the reader factory calls this while the user browses.
    int looked = 0;
    for (fs::directory_iterator it(path, ec), end; !ec && it != end && looked < 32;
         it.increment(ec))
    {
      if (it->is_regular_file(ec))
      {
        ++looked;
        if (isDicomFile(it->path().string()))
        {
          return true;
        }
      }
    }
    return false;
  }
  const FileKind kind = kindFromName(path);
  return kind != FileKind::Other || isDicomFile(path);
}

} // namespace vtouch

#include "vtouchVolumeIO.h"

#include "vtouchDicomSeries.h"
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

namespace
{
enum class FileKind
{
  NIfTI,
  NRRD,
  MetaImage,
  Other
};

std::string lowerCase(std::string text)
{
  std::transform(text.begin(),
    text.end(),
    text.begin(),
    [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text;
}

bool endsWith(const std::string& text, const std::string& suffix)
{
  return text.size() >= suffix.size() &&
         text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0;
}

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

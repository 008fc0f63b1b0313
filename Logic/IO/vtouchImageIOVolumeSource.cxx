#include "vtouchImageIOVolumeSource.h"

#include "vtouchRawExtentRead.h"
#include "vtouchVolumeFileChecks.h"

#include <itkImageIORegion.h>

#include <sstream>
#include <vector>

namespace vtouch
{

VoxelType voxelTypeFromITK(itk::IOComponentEnum component, const std::string& path)
{
  using C = itk::IOComponentEnum;
  switch (component)
  {
    case C::CHAR:
      return VoxelType::Int8;
    case C::UCHAR:
      return VoxelType::UInt8;
    case C::SHORT:
      return VoxelType::Int16;
    case C::USHORT:
      return VoxelType::UInt16;
    case C::INT:
      return VoxelType::Int32;
    case C::UINT:
      return VoxelType::UInt32;
    case C::FLOAT:
      return VoxelType::Float32;
    case C::DOUBLE:
      return VoxelType::Float64;
    default:
      break;
  }
  throw VolumeIOError("'" + path + "' has an unsupported pixel type (" +
                      itk::ImageIOBase::GetComponentTypeAsString(component) +
                      "); supported: signed/unsigned 8, 16 and 32-bit integers, float and double");
}

void headerFromImageIO(const itk::ImageIOBase& io, const std::string& path, VolumeHeader& header)
{
  const unsigned int n = io.GetNumberOfDimensions();
  if (n < 3)
  {
    throw VolumeIOError(
      "'" + path + "' is a " + std::to_string(n) + "D image; VesselTouch needs a 3D volume");
  }
  if (n > 4 || (n == 4 && io.GetDimensions(3) > 1))
  {
    std::ostringstream msg;
    msg << "'" << path << "' is a " << n << "D image (";
    for (unsigned int a = 0; a < n; ++a)
    {
      msg << (a ? " x " : "") << io.GetDimensions(a);
    }
    msg << "); VesselTouch reads 3D volumes only: extract one time point first";
    throw VolumeIOError(msg.str());
  }
  if (io.GetNumberOfComponents() != 1)
  {
    throw VolumeIOError("'" + path + "' has " + std::to_string(io.GetNumberOfComponents()) +
                        " components per voxel (" +
                        itk::ImageIOBase::GetPixelTypeAsString(io.GetPixelType()) +
                        "); VesselTouch needs one scalar per voxel");
  }
  header.voxelType = voxelTypeFromITK(io.GetComponentType(), path);
  VolumeGeometry& g = header.geometry;
  for (unsigned int a = 0; a < 3; ++a)
  {
    g.dimensions[a] = io.GetDimensions(a);
    g.spacing_mm[a] = io.GetSpacing(a);
    g.origin_mm[a] = io.GetOrigin(a);
    const std::vector<double> axis = io.GetDirection(a); // world direction of index axis a
    for (unsigned int r = 0; r < 3; ++r)
    {
      g.direction[3 * r + a] = r < axis.size() ? axis[r] : (r == a ? 1.0 : 0.0);
    }
  }
  for (unsigned int a = 0; a < 3; ++a)
  {
    if (g.dimensions[a] < 2)
    {
      throw VolumeIOError("'" + path + "' is a single slice (" + std::to_string(g.dimensions[0]) +
                          " x " + std::to_string(g.dimensions[1]) + " x " +
                          std::to_string(g.dimensions[2]) +
                          "): a 2D image; VesselTouch needs a 3D volume");
    }
    if (!(g.spacing_mm[a] > 0.0))
    {
      throw VolumeIOError("'" + path + "' has a non-positive voxel spacing");
    }
  }
}

ImageIOVolumeSource::ImageIOVolumeSource(itk::ImageIOBase::Pointer io,
  const std::string& path,
  const char* format)
  : IO(std::move(io))
  , Path(path)
{
  this->Header.format = format;
  if (!this->IO->CanReadFile(path.c_str()))
  {
    throw VolumeIOError(
      "'" + path + "' is not a readable " + format + " file (missing, or a corrupt header)");
  }
  this->IO->SetFileName(path);
  try
  {
    this->IO->ReadImageInformation();
  }
  catch (const itk::ExceptionObject& e)
  {
    throw VolumeIOError("cannot read the " + std::string(format) + " header of '" + path +
                        "': " + e.GetDescription());
  }
  headerFromImageIO(*this->IO, path, this->Header);
  const std::string name(format);
  if (name == "NIfTI")
  {
    checkNiftiComplete(path);
  }
  else if (name == "MetaImage")
  {
    checkMetaImageComplete(path, this->Header.byteCount());
  }
  if (name != "DICOM multi-frame")
  {
    this->Layout = findRawVoxelLayout(path, this->Header);
  }
}

bool ImageIOVolumeSource::readExtent(const VoxelExtent& extent,
  void* buffer,
  std::size_t bytes,
  const VolumeProgress& progress)
{
  this->checkExtentRequest(extent, buffer, bytes);
  const VolumeGeometry& g = this->Header.geometry;
  const std::size_t voxelBytes = voxelSize(this->Header.voxelType);
  if (this->Layout)
  {
    return readRawExtent(
      *this->Layout, g.dimensions, voxelBytes, extent, buffer, progress, this->LastRead);
  }
  this->LastRead = VolumeReadStatistics();
  this->LastRead.filesRead = 1;
  this->LastRead.bytesRead = this->Header.byteCount();
  if (extent.voxelCount() == g.voxelCount())
  {
    return this->readWholeWithITK(buffer, progress);
  }
  // A compressed file has no random access: decode it whole, keep the part.
  std::vector<char> whole(this->Header.byteCount());
  if (!this->readWholeWithITK(whole.data(), progress))
  {
    return false;
  }
  copyExtent(whole.data(), g.dimensions, voxelBytes, extent, buffer);
  return true;
}

bool ImageIOVolumeSource::readWholeWithITK(void* buffer, const VolumeProgress& progress)
{
  if (progress && !progress(0.0))
  {
    return false;
  }
  const unsigned int n = this->IO->GetNumberOfDimensions();
  itk::ImageIORegion region(n);
  for (unsigned int a = 0; a < n; ++a)
  {
    region.SetIndex(a, 0);
    region.SetSize(a, this->IO->GetDimensions(a));
  }
  this->IO->SetIORegion(region);
  try
  {
    this->IO->Read(buffer);
  }
  catch (const itk::ExceptionObject& e)
  {
    throw VolumeIOError("cannot read the voxels of '" + this->Path +
                        "' (truncated or corrupt file?): " + e.GetDescription());
  }
  return progress ? progress(1.0) : true;
}

} // namespace vtouch

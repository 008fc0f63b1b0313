#include "vtouchTestVolumes.h"

#include <itkGDCMImageIO.h>
#include <itkImage.h>
#include <itkImageFileWriter.h>
#include <itkImageRegionIteratorWithIndex.h>
#include <itkImageSeriesWriter.h>
#include <itkMetaDataObject.h>
#include <itkMetaImageIO.h>
#include <itkNiftiImageIO.h>
#include <itkNrrdImageIO.h>
#include <itkVector.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <sstream>
#include <stdexcept>

namespace vtouch
{
namespace test
{
namespace
{
bool endsWith(const std::string& s, const std::string& suffix)
{
  return s.size() >= suffix.size() &&
         s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

itk::ImageIOBase::Pointer ioFor(const std::string& path)
{
  if (endsWith(path, ".nrrd") || endsWith(path, ".nhdr"))
  {
    return itk::NrrdImageIO::New().GetPointer();
  }
  if (endsWith(path, ".nii") || endsWith(path, ".nii.gz"))
  {
    return itk::NiftiImageIO::New().GetPointer();
  }
  if (endsWith(path, ".mha") || endsWith(path, ".mhd"))
  {
    return itk::MetaImageIO::New().GetPointer();
  }
  throw std::invalid_argument("no test writer for " + path);
}

template<class TImage>
void writeImage(const std::string& path, TImage* image)
{
  auto writer = itk::ImageFileWriter<TImage>::New();
  writer->SetImageIO(ioFor(path));
  writer->SetFileName(path);
  writer->SetInput(image);
  writer->Update();
}

template<class TPixel>
typename itk::Image<TPixel, 3>::Pointer makeImage(const TestGeometry& g)
{
  using ImageType = itk::Image<TPixel, 3>;
  auto image = ImageType::New();
  typename ImageType::RegionType region;
  typename ImageType::DirectionType direction;
  typename ImageType::SpacingType spacing;
  typename ImageType::PointType origin;
  for (unsigned a = 0; a < 3; ++a)
  {
    region.SetSize(a, g.size[a]);
    spacing[a] = g.spacing_mm[a];
    origin[a] = g.origin_LPS_mm[a];
    for (unsigned c = 0; c < 3; ++c)
    {
      direction(a, c) = g.direction[3 * a + c];
    }
  }
  image->SetRegions(region);
  image->SetSpacing(spacing);
  image->SetOrigin(origin);
  image->SetDirection(direction);
  image->Allocate();
  itk::ImageRegionIteratorWithIndex<ImageType> it(image, region);
  for (; !it.IsAtEnd(); ++it)
  {
    const auto idx = it.GetIndex();
    int v = testVoxelValue(idx[0], idx[1], idx[2]);
    if (std::is_unsigned<TPixel>::value)
    {
      v += 50; // keep it >= 0
    }
    it.Set(static_cast<TPixel>(v));
  }
  return image;
}

template<class TPixel>
void writeTyped(const std::string& path, const TestGeometry& g)
{
  auto image = makeImage<TPixel>(g);
  writeImage(path, image.GetPointer());
}

std::string decimalString(double v)
{
  std::ostringstream s;
  s.precision(10);
  s << v;
  return s.str();
}
} // namespace

TestGeometry obliqueGeometry()
{
  TestGeometry g;
  const double a = 30.0 * M_PI / 180.0;
  const double b = 20.0 * M_PI / 180.0;
  // Rx(b) * Rz(a)
  const double rz[9] = { std::cos(a), -std::sin(a), 0, std::sin(a), std::cos(a), 0, 0, 0, 1 };
  const double rx[9] = { 1, 0, 0, 0, std::cos(b), -std::sin(b), 0, std::sin(b), std::cos(b) };
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 3; ++c)
    {
      double sum = 0.0;
      for (int m = 0; m < 3; ++m)
      {
        sum += rx[3 * r + m] * rz[3 * m + c];
      }
      g.direction[3 * r + c] = sum;
    }
  }
  return g;
}

void writeVolume(const std::string& path, const TestGeometry& g, const std::string& pixel)
{
  if (pixel == "int8")
    writeTyped<std::int8_t>(path, g);
  else if (pixel == "uint8")
    writeTyped<std::uint8_t>(path, g);
  else if (pixel == "int16")
    writeTyped<std::int16_t>(path, g);
  else if (pixel == "uint16")
    writeTyped<std::uint16_t>(path, g);
  else if (pixel == "int32")
    writeTyped<std::int32_t>(path, g);
  else if (pixel == "uint32")
    writeTyped<std::uint32_t>(path, g);
  else if (pixel == "float")
    writeTyped<float>(path, g);
  else if (pixel == "double")
    writeTyped<double>(path, g);
  else if (pixel == "int64")
    writeTyped<std::int64_t>(path, g);
  else
    throw std::invalid_argument("unknown pixel type " + pixel);
}

std::vector<std::string> writeDicomSeries(const std::string& directory,
  const TestGeometry& g,
  const std::string& seriesUID,
  int skipSlice,
  const std::string& filePrefix,
  const std::string& fileSuffix)
{
  using Image3 = itk::Image<std::int16_t, 3>;
  using Image2 = itk::Image<std::int16_t, 2>;
  std::filesystem::create_directories(directory);
  auto image = makeImage<std::int16_t>(g);
  auto io = itk::GDCMImageIO::New();
  io->KeepOriginalUIDOn();

  const unsigned n = g.size[2];
  std::vector<std::string> names(n);
  std::vector<itk::MetaDataDictionary> dictionaries(n);
  std::ostringstream iop;
  iop.precision(10);
  iop << g.direction[0] << "\\" << g.direction[3] << "\\" << g.direction[6] << "\\"
      << g.direction[1] << "\\" << g.direction[4] << "\\" << g.direction[7];
  for (unsigned k = 0; k < n; ++k)
  {
    std::ostringstream name;
    name << directory << "/" << filePrefix;
    name.width(4);
    name.fill('0');
    name << (n - 1 - k) << fileSuffix;
    names[k] = name.str();
    // Voxel (0, 0, k) of the volume: origin + k * spacing_z * third direction column.
    std::ostringstream ipp;
    ipp.precision(10);
    for (int r = 0; r < 3; ++r)
    {
      ipp << (r ? "\\" : "") << g.origin_LPS_mm[r] + k * g.spacing_mm[2] * g.direction[3 * r + 2];
    }
    itk::MetaDataDictionary& d = dictionaries[k];
    itk::EncapsulateMetaData<std::string>(d, "0008|0016", "1.2.840.10008.5.1.4.1.1.2");
    itk::EncapsulateMetaData<std::string>(d, "0008|0018", seriesUID + "." + std::to_string(k + 1));
    itk::EncapsulateMetaData<std::string>(d, "0008|0060", "CT");
    itk::EncapsulateMetaData<std::string>(d, "0028|0004", "MONOCHROME2");
    itk::EncapsulateMetaData<std::string>(d, "0020|000d", "1.2.826.0.1.3680043.2.1125.1");
    itk::EncapsulateMetaData<std::string>(d, "0020|000e", seriesUID);
    itk::EncapsulateMetaData<std::string>(d, "0020|0013", std::to_string(k + 1));
    itk::EncapsulateMetaData<std::string>(d, "0020|0032", ipp.str());
    itk::EncapsulateMetaData<std::string>(d, "0020|0037", iop.str());
    itk::EncapsulateMetaData<std::string>(
      d, "0028|0030", decimalString(g.spacing_mm[1]) + "\\" + decimalString(g.spacing_mm[0]));
    itk::EncapsulateMetaData<std::string>(d, "0018|0050", decimalString(g.spacing_mm[2]));
  }
  std::vector<itk::MetaDataDictionary*> pointers;
  for (auto& d : dictionaries)
  {
    pointers.push_back(&d);
  }
  auto writer = itk::ImageSeriesWriter<Image3, Image2>::New();
  writer->SetInput(image);
  writer->SetImageIO(io);
  writer->SetFileNames(names);
  writer->SetMetaDataDictionaryArray(&pointers);
  writer->Update();
  if (skipSlice >= 0 && skipSlice < static_cast<int>(n))
  {
    std::filesystem::remove(names[skipSlice]);
    names.erase(names.begin() + skipSlice);
  }
  return names;
}

void write2D(const std::string& path)
{
  using ImageType = itk::Image<std::int16_t, 2>;
  auto image = ImageType::New();
  ImageType::RegionType region;
  region.SetSize({ { 8, 7 } });
  image->SetRegions(region);
  image->Allocate(true);
  writeImage(path, image.GetPointer());
}

void write4D(const std::string& path)
{
  using ImageType = itk::Image<std::int16_t, 4>;
  auto image = ImageType::New();
  ImageType::RegionType region;
  region.SetSize({ { 4, 4, 3, 2 } });
  image->SetRegions(region);
  image->Allocate(true);
  writeImage(path, image.GetPointer());
}

void writeVector(const std::string& path)
{
  using ImageType = itk::Image<itk::Vector<float, 3>, 3>;
  auto image = ImageType::New();
  ImageType::RegionType region;
  region.SetSize({ { 4, 4, 3 } });
  image->SetRegions(region);
  image->Allocate();
  image->FillBuffer(itk::Vector<float, 3>(1.0f));
  writeImage(path, image.GetPointer());
}

} // namespace test
} // namespace vtouch

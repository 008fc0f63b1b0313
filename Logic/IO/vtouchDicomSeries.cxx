#include "vtouchDicomSeries.h"

#include "vtouchImageIOVolumeSource.h"
#include "vtouchRawExtentRead.h"
#include "vtouchVolumeFileChecks.h"

#include <itkGDCMImageIO.h>

#include <gdcmScanner.h>
#include <gdcmTag.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <numeric>
#include <sstream>

namespace vtouch
{
namespace
{
const gdcm::Tag SeriesInstanceUIDTag(0x0020, 0x000e);
const gdcm::Tag ImagePositionPatientTag(0x0020, 0x0032);
const gdcm::Tag ImageOrientationPatientTag(0x0020, 0x0037);
const gdcm::Tag NumberOfFramesTag(0x0028, 0x0008);

// Tolerances in mm (positions) and in direction cosines (orientations).
constexpr double SamePositionTolerance_mm = 0.01;
constexpr double OrientationTolerance = 1e-3;

std::string trimmed(const char* text)
{
  std::string s = text ? text : "";
  const auto notSpace = [](unsigned char c) { return !std::isspace(c) && c != '\0'; };
  s.erase(s.begin(), std::find_if(s.begin(), s.end(), notSpace));
  s.erase(std::find_if(s.rbegin(), s.rend(), notSpace).base(), s.end());
  return s;
}

// "a\b\c" (DICOM decimal strings) -> numbers; an unparsable value ends the list.
std::vector<double> decimals(const char* text)
{
  std::vector<double> values;
  std::istringstream in(trimmed(text));
  std::string item;
  while (std::getline(in, item, '\\'))
  {
    char* end = nullptr;
    const double v = std::strtod(item.c_str(), &end);
    if (end == item.c_str())
    {
      break;
    }
    values.push_back(v);
  }
  return values;
}

double dot(const std::array<double, 3>& a, const std::array<double, 3>& b)
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

std::string fileName(const std::string& path)
{
  return std::filesystem::path(path).filename().string();
}

// The DICOM files of one folder (not recursive), grouped by Series Instance UID. gdcm::Scanner
// reads each header only up to the last tag asked for, never the pixel data: scanning a 400-slice
// series costs a few MB, where itk::GDCMSeriesFileNames (gdcm::SerieHelper) held every file,
// pixels included, in memory at once (one extra copy of the volume).
struct FolderScan
{
  gdcm::Scanner scanner;
  std::vector<std::string> uids; // in the order first met (file names sorted)
  std::map<std::string, std::vector<std::string>> files;
};

std::unique_ptr<FolderScan> scanFolder(const std::string& directory)
{
  std::vector<std::string> names;
  std::error_code ec;
  for (std::filesystem::directory_iterator it(directory, ec), end; !ec && it != end;
       it.increment(ec))
  {
    if (it->is_regular_file(ec))
    {
      names.push_back(it->path().string());
    }
  }
  if (ec)
  {
    throw VolumeIOError("cannot list the DICOM folder '" + directory + "': " + ec.message());
  }
  std::sort(names.begin(), names.end());
  auto scan = std::make_unique<FolderScan>();
  for (const gdcm::Tag& tag : { SeriesInstanceUIDTag,
         ImagePositionPatientTag,
         ImageOrientationPatientTag,
         NumberOfFramesTag })
  {
    scan->scanner.AddTag(tag);
  }
  if (!scan->scanner.Scan(names))
  {
    throw VolumeIOError("cannot scan the DICOM folder '" + directory + "'");
  }
  for (const std::string& name : names)
  {
    if (!scan->scanner.IsKey(name.c_str()))
    {
      continue; // not a DICOM file
    }
    const std::string uid = trimmed(scan->scanner.GetValue(name.c_str(), SeriesInstanceUIDTag));
    if (uid.empty())
    {
      continue;
    }
    std::vector<std::string>& files = scan->files[uid];
    if (files.empty())
    {
      scan->uids.push_back(uid);
    }
    files.push_back(name);
  }
  return scan;
}

std::vector<DicomSeriesSummary> summaries(const FolderScan& scan)
{
  std::vector<DicomSeriesSummary> list;
  for (const std::string& uid : scan.uids)
  {
    list.push_back({ uid, scan.files.at(uid).size() });
  }
  std::stable_sort(list.begin(),
    list.end(),
    [](const DicomSeriesSummary& a, const DicomSeriesSummary& b)
    { return a.fileCount > b.fileCount; });
  return list;
}

itk::GDCMImageIO::Pointer readSliceHeader(const std::string& file)
{
  auto io = itk::GDCMImageIO::New();
  io->SetFileName(file);
  try
  {
    io->ReadImageInformation();
  }
  catch (const itk::ExceptionObject& e)
  {
    throw VolumeIOError("cannot read the DICOM file '" + file + "': " + e.GetDescription());
  }
  return io;
}

struct Slice
{
  std::string file;
  std::array<double, 3> position_mm;
  double along_mm; // position along the slice normal
};

/// Reads the slices of one series straight into the caller's buffer; a part of the volume opens
/// only the files of its slices. GDCM parses each file three times (ITK's header read, the length
/// check, ITK's pixel read): 400 CT slices take ~0.5 s.
class DicomSeriesSource : public VolumeSource
{
public:
  DicomSeriesSource(VolumeHeader header, std::vector<std::string> files)
    : Files(std::move(files))
  {
    this->Header = std::move(header);
  }

  bool readExtent(const VoxelExtent& extent,
    void* buffer,
    std::size_t bytes,
    const VolumeProgress& progress) override
  {
    this->checkExtentRequest(extent, buffer, bytes);
    this->LastRead = VolumeReadStatistics();
    const VolumeGeometry& g = this->Header.geometry;
    const std::size_t voxelBytes = voxelSize(this->Header.voxelType);
    const std::size_t sliceBytes = g.dimensions[0] * g.dimensions[1] * voxelBytes;
    const bool wholeSlices =
      extent.size()[0] == g.dimensions[0] && extent.size()[1] == g.dimensions[1];
    // Only the files of the extent's slices are opened; a slice is decoded whole (DICOM pixel data
    // may be compressed), into the buffer directly when the extent spans whole slices.
    std::vector<char> slice(wholeSlices ? 0 : sliceBytes);
    const std::array<std::size_t, 3> sliceDims{ { g.dimensions[0], g.dimensions[1], 1 } };
    VoxelExtent inSlice = extent;
    inSlice.first[2] = inSlice.last[2] = 0;
    char* out = static_cast<char*>(buffer);
    const std::size_t outSliceBytes = extent.size()[0] * extent.size()[1] * voxelBytes;
    const std::size_t count = extent.size()[2];
    for (std::size_t k = extent.first[2]; k <= extent.last[2]; ++k)
    {
      if (progress && !progress(static_cast<double>(k - extent.first[2]) / count))
      {
        return false;
      }
      char* target = wholeSlices ? out : slice.data();
      this->readSlice(this->Files[k], target);
      if (!wholeSlices)
      {
        copyExtent(slice.data(), sliceDims, voxelBytes, inSlice, out);
      }
      out += outSliceBytes;
      this->LastRead.filesRead += 1;
      this->LastRead.bytesRead += sliceBytes;
    }
    return progress ? progress(1.0) : true;
  }

  bool readsExtentsAlone() const override { return true; }
  bool readsPartialSlicesAlone() const override { return false; } // one file per slice

private:
  /// Reads one whole slice of the series into `target` (sliceBytes).
  void readSlice(const std::string& file, char* target) const
  {
    const VolumeGeometry& g = this->Header.geometry;
    itk::GDCMImageIO::Pointer io = readSliceHeader(file);
    // Checked before every read: GDCM writes a whole slice into the buffer.
    const bool sameSize = io->GetDimensions(0) == g.dimensions[0] &&
                          io->GetDimensions(1) == g.dimensions[1] &&
                          (io->GetNumberOfDimensions() < 3 || io->GetDimensions(2) == 1);
    if (!sameSize || io->GetNumberOfComponents() != 1 ||
        voxelTypeFromITK(io->GetComponentType(), file) != this->Header.voxelType)
    {
      throw VolumeIOError("the slice '" + file +
                          "' differs from the first slice of its series in size or pixel type");
    }
    checkDicomSliceComplete(file);
    try
    {
      io->Read(target);
    }
    catch (const itk::ExceptionObject& e)
    {
      throw VolumeIOError("cannot read the pixels of '" + file +
                          "' (truncated or corrupt file?): " + e.GetDescription());
    }
  }

  std::vector<std::string> Files; // ordered by position along the slice normal
};

std::string chooseSeries(const FolderScan& scan,
  const std::string& path,
  bool pathIsFile,
  const VolumeOpenOptions& options,
  std::vector<std::string>& warnings)
{
  const std::string directory =
    pathIsFile ? std::filesystem::path(path).parent_path().string() : path;
  const std::vector<DicomSeriesSummary> found = summaries(scan);
  if (found.empty())
  {
    throw VolumeIOError("no DICOM series found in '" + directory + "'");
  }
  std::ostringstream list;
  for (const DicomSeriesSummary& s : found)
  {
    list << "\n  " << s.seriesInstanceUID << " (" << s.fileCount << " files)";
  }
  std::string uid = options.seriesInstanceUID;
  if (uid.empty() && pathIsFile)
  {
    const auto same = [&path](const std::string& file)
    {
      std::error_code ec;
      return std::filesystem::equivalent(file, path, ec);
    };
    for (const auto& [seriesUID, files] : scan.files)
    {
      if (std::any_of(files.begin(), files.end(), same))
      {
        uid = seriesUID;
      }
    }
    if (uid.empty())
    {
      throw VolumeIOError("'" + path + "' is not a DICOM image with a Series Instance UID");
    }
  }
  if (uid.empty())
  {
    uid = found.front().seriesInstanceUID;
  }
  const auto chosen = std::find_if(found.begin(),
    found.end(),
    [&uid](const DicomSeriesSummary& s) { return s.seriesInstanceUID == uid; });
  if (chosen == found.end())
  {
    throw VolumeIOError(
      "the DICOM series '" + uid + "' is not in '" + directory + "'; series found:" + list.str());
  }
  if (found.size() > 1)
  {
    std::ostringstream msg;
    msg << "'" << directory << "' holds " << found.size() << " DICOM series:" << list.str()
        << "\nReading " << chosen->seriesInstanceUID << " (" << chosen->fileCount
        << " files); pick another with the SeriesInstanceUID property.";
    warnings.push_back(msg.str());
  }
  return uid;
}

// Orders the slices along the normal and checks that they form one regular stack; returns the
// slice spacing in mm.
double orderAndCheckStack(std::vector<Slice>& slices)
{
  std::stable_sort(slices.begin(),
    slices.end(),
    [](const Slice& a, const Slice& b) { return a.along_mm < b.along_mm; });
  std::vector<double> steps;
  for (std::size_t k = 1; k < slices.size(); ++k)
  {
    const double step = slices[k].along_mm - slices[k - 1].along_mm;
    if (step < SamePositionTolerance_mm)
    {
      throw VolumeIOError(
        "the DICOM files '" + fileName(slices[k - 1].file) + "' and '" + fileName(slices[k].file) +
        "' are slices at the same position: the series mixes several acquisitions (time points, "
        "echoes or phases); VesselTouch reads a single 3D stack");
    }
    steps.push_back(step);
  }
  std::vector<double> sorted = steps;
  std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
  const double spacing = sorted[sorted.size() / 2];
  const double tolerance = std::max(0.02 * spacing, SamePositionTolerance_mm);
  for (std::size_t k = 0; k < steps.size(); ++k)
  {
    if (std::abs(steps[k] - spacing) > tolerance)
    {
      std::ostringstream msg;
      msg << "the DICOM series is not a regular stack: between '" << fileName(slices[k].file)
          << "' and '" << fileName(slices[k + 1].file) << "' the slices are " << steps[k]
          << " mm apart where the spacing is " << spacing << " mm";
      const double ratio = steps[k] / spacing;
      if (ratio > 1.5)
      {
        msg << " (about " << std::lround(ratio) - 1 << " missing slice(s))";
      }
      msg << ". The series is not read: a gap must not be stitched over";
      throw VolumeIOError(msg.str());
    }
  }
  return spacing;
}

std::unique_ptr<VolumeSource> openSeriesFiles(const gdcm::Scanner& scanner,
  const std::vector<std::string>& files,
  VolumeHeader header)
{
  itk::GDCMImageIO::Pointer first = readSliceHeader(files.front());
  if (files.size() == 1)
  {
    const char* frames = scanner.GetValue(files.front().c_str(), NumberOfFramesTag);
    if (frames && std::atoi(frames) > 1)
    {
      return std::make_unique<ImageIOVolumeSource>(
        itk::GDCMImageIO::New().GetPointer(), files.front(), "DICOM multi-frame");
    }
    throw VolumeIOError("the DICOM series of '" + files.front() +
                        "' holds a single 2D slice; VesselTouch needs a 3D volume");
  }
  if (first->GetNumberOfComponents() != 1)
  {
    throw VolumeIOError("'" + files.front() + "' has " +
                        std::to_string(first->GetNumberOfComponents()) +
                        " components per pixel (colour); VesselTouch needs one scalar per voxel");
  }
  header.voxelType = voxelTypeFromITK(first->GetComponentType(), files.front());

  std::vector<double> orientation;
  std::vector<Slice> slices;
  for (const std::string& file : files)
  {
    const std::vector<double> ipp =
      decimals(scanner.GetValue(file.c_str(), ImagePositionPatientTag));
    const std::vector<double> iop =
      decimals(scanner.GetValue(file.c_str(), ImageOrientationPatientTag));
    if (ipp.size() != 3 || iop.size() != 6)
    {
      throw VolumeIOError(
        "the DICOM file '" + file +
        "' has no usable ImagePositionPatient / ImageOrientationPatient: its slice cannot be "
        "placed in space");
    }
    if (orientation.empty())
    {
      orientation = iop;
    }
    for (int c = 0; c < 6; ++c)
    {
      if (std::abs(iop[c] - orientation[c]) > OrientationTolerance)
      {
        throw VolumeIOError("the DICOM series mixes slice orientations ('" + fileName(file) +
                            "' differs from '" + fileName(files.front()) + "'): not one 3D stack");
      }
    }
    slices.push_back({ file, { { ipp[0], ipp[1], ipp[2] } }, 0.0 });
  }
  const std::array<double, 3> row{ { orientation[0], orientation[1], orientation[2] } };
  const std::array<double, 3> col{ { orientation[3], orientation[4], orientation[5] } };
  std::array<double, 3> normal{ { row[1] * col[2] - row[2] * col[1],
    row[2] * col[0] - row[0] * col[2],
    row[0] * col[1] - row[1] * col[0] } };
  const double length = std::sqrt(dot(normal, normal));
  if (length < 0.5)
  {
    throw VolumeIOError("the DICOM ImageOrientationPatient of '" + files.front() + "' is invalid");
  }
  for (double& v : normal)
  {
    v /= length;
  }
  for (Slice& s : slices)
  {
    s.along_mm = dot(s.position_mm, normal);
  }
  const double spacing = orderAndCheckStack(slices);

  // Gantry tilt: slice origins that drift across the normal. Shown unsheared (like ITK).
  std::array<double, 3> run;
  for (int r = 0; r < 3; ++r)
  {
    run[r] = slices.back().position_mm[r] - slices.front().position_mm[r];
  }
  const double alongRun = dot(run, normal);
  const double lateral = std::sqrt(std::max(0.0, dot(run, run) - alongRun * alongRun));
  if (lateral > 0.01 * std::abs(alongRun) + SamePositionTolerance_mm)
  {
    header.warnings.push_back(
      "the DICOM slices drift " + std::to_string(lateral) +
      " mm across the slice normal (gantry tilt?): the volume is shown without that shear");
  }

  VolumeGeometry& g = header.geometry;
  g.dimensions = { { first->GetDimensions(0), first->GetDimensions(1), slices.size() } };
  g.spacing_mm = { { first->GetSpacing(0), first->GetSpacing(1), spacing } };
  g.origin_mm = slices.front().position_mm;
  for (int r = 0; r < 3; ++r)
  {
    g.direction[3 * r + 0] = row[r];
    g.direction[3 * r + 1] = col[r];
    g.direction[3 * r + 2] = normal[r];
  }
  std::vector<std::string> ordered;
  for (const Slice& s : slices)
  {
    ordered.push_back(s.file);
  }
  return std::make_unique<DicomSeriesSource>(std::move(header), std::move(ordered));
}
} // namespace

bool isDicomFile(const std::string& path)
{
  auto io = itk::GDCMImageIO::New();
  return io->CanReadFile(path.c_str());
}

std::vector<DicomSeriesSummary> listDicomSeries(const std::string& directory)
{
  return summaries(*scanFolder(directory));
}

std::unique_ptr<VolumeSource> openDicomSeries(const std::string& path,
  const VolumeOpenOptions& options)
{
  std::error_code ec;
  const bool pathIsFile = !std::filesystem::is_directory(path, ec);
  const std::string directory =
    pathIsFile ? std::filesystem::path(path).parent_path().string() : path;
  const std::unique_ptr<FolderScan> scan = scanFolder(directory.empty() ? "." : directory);
  VolumeHeader header;
  header.format = "DICOM series";
  const std::string uid = chooseSeries(*scan, path, pathIsFile, options, header.warnings);
  return openSeriesFiles(scan->scanner, scan->files.at(uid), std::move(header));
}

} // namespace vtouch

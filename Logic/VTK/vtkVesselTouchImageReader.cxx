#include "vtkVesselTouchImageReader.h"

#include "vtouchExtentReuse.h"

#include "vtouchVolumeIO.h"
#include "vtouchVoxelValueRange.h"

#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkExtentTranslator.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationInformationVectorKey.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkSmartPointer.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkStringArray.h"

#include <sys/mman.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <sstream>

vtkStandardNewMacro(vtkVesselTouchImageReader);

namespace
{
int vtkTypeOf(vtouch::VoxelType type)
{
  switch (type)
  {
    case vtouch::VoxelType::Int8:
      return VTK_SIGNED_CHAR;
    case vtouch::VoxelType::UInt8:
      return VTK_UNSIGNED_CHAR;
    case vtouch::VoxelType::Int16:
      return VTK_SHORT;
    case vtouch::VoxelType::UInt16:
      return VTK_UNSIGNED_SHORT;
    case vtouch::VoxelType::Int32:
      return VTK_INT;
    case vtouch::VoxelType::UInt32:
      return VTK_UNSIGNED_INT;
    case vtouch::VoxelType::Float32:
      return VTK_FLOAT;
    case vtouch::VoxelType::Float64:
      return VTK_DOUBLE;
  }
  return VTK_VOID;
}

bool isDicomInput(const char* path)
{
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
  {
    return true;
  }
  const std::string ext = std::filesystem::path(path).extension().string();
  for (const char* volumeExt : { ".nii", ".gz", ".hdr", ".img", ".nrrd", ".nhdr", ".mha", ".mhd" })
  {
    if (ext == volumeExt)
    {
      return false;
    }
  }
  return true;
}
} // namespace

vtkVesselTouchImageReader::vtkVesselTouchImageReader()
{
  this->SetNumberOfInputPorts(0);
  this->SetNumberOfOutputPorts(1);
}

vtkVesselTouchImageReader::~vtkVesselTouchImageReader()
{
  this->SetFileName(nullptr);
  this->SetSeriesInstanceUID(nullptr);
}

int vtkVesselTouchImageReader::CanReadFile(const char* path)
{
  return path && vtouch::canReadVolume(path) ? 1 : 0;
}

vtkStringArray* vtkVesselTouchImageReader::GetSeriesInstanceUIDs()
{
  return this->SeriesUIDs;
}

vtkStringArray* vtkVesselTouchImageReader::GetSeriesSummaries()
{
  return this->SeriesLines;
}

void vtkVesselTouchImageReader::UpdateSeriesList()
{
  this->SeriesUIDs->Initialize();
  this->SeriesLines->Initialize();
  if (!this->FileName || !isDicomInput(this->FileName))
  {
    return;
  }
  std::error_code ec;
  std::string folder = this->FileName;
  if (!std::filesystem::is_directory(folder, ec))
  {
    folder = std::filesystem::path(folder).parent_path().string();
  }
  try
  {
    for (const vtouch::DicomSeriesSummary& s : vtouch::listDicomSeries(folder))
    {
      this->SeriesUIDs->InsertNextValue(s.seriesInstanceUID);
      this->SeriesLines->InsertNextValue(
        s.seriesInstanceUID + " (" + std::to_string(s.fileCount) + " files)");
    }
  }
  catch (const vtouch::VolumeIOError&)
  {
    // Open() reports the same problem.
  }
}

std::string vtkVesselTouchImageReader::Open()
{
  this->Source.reset();
  this->FileFormat.clear();
  if (!this->FileName || !*this->FileName)
  {
    return "no FileName set";
  }
  vtouch::VolumeOpenOptions options;
  if (this->SeriesInstanceUID)
  {
    options.seriesInstanceUID = this->SeriesInstanceUID;
  }
  try
  {
    this->Source = vtouch::openVolume(this->FileName, options);
  }
  catch (const vtouch::VolumeIOError& e)
  {
    return e.what();
  }
  catch (const std::exception& e)
  {
    return std::string("unexpected failure: ") + e.what();
  }
  const vtouch::VolumeHeader& header = this->Source->header();
  this->FileFormat = header.format + ", " + vtouch::toString(header.voxelType);
  for (const std::string& warning : header.warnings)
  {
    vtkWarningMacro("VesselTouch reader: " << warning);
  }
  return std::string();
}

int vtkVesselTouchImageReader::RequestInformation(vtkInformation*,
  vtkInformationVector**,
  vtkInformationVector* outputVector)
{
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  if (this->OpenTime <= this->GetMTime())
  {
    this->UpdateSeriesList();
    this->OpenError = this->Open();
    this->WarnedWholeDecode = false;
    this->OpenTime.Modified();
  }
  const std::string& error = this->OpenError;
  int extent[6] = { 0, -1, 0, -1, 0, -1 };
  if (!error.empty())
  {
    // No file name yet (a proxy created before its FileName is set) is not an error.
    if (this->FileName && *this->FileName)
    {
      vtkErrorMacro("VesselTouch reader: " << error << ". The output is empty.");
    }
    outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent, 6);
    return 1;
  }
  const vtouch::VolumeHeader& header = this->Source->header();
  const vtouch::VolumeGeometry g = header.geometry.inFrame(
    this->OutputFrame == RAS ? vtouch::WorldFrame::RAS : vtouch::WorldFrame::LPS);
  for (int a = 0; a < 3; ++a)
  {
    extent[2 * a + 1] = static_cast<int>(g.dimensions[a]) - 1;
  }
  outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent, 6);
  outInfo->Set(vtkDataObject::SPACING(), g.spacing_mm.data(), 3);
  outInfo->Set(vtkDataObject::ORIGIN(), g.origin_mm.data(), 3);
  outInfo->Set(vtkDataObject::DIRECTION(), g.direction.data(), 9);
  outInfo->Set(CAN_PRODUCE_SUB_EXTENT(), 1);
  vtkDataObject::SetPointDataActiveScalarInfo(outInfo, vtkTypeOf(header.voxelType), 1);
  return 1;
}

namespace
{
double secondsSince(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// Asks Linux to back the 2 MiB-aligned part of a large voxel buffer with transparent huge pages
/// before it is filled, when VESSELTOUCH_READER_HUGE_PAGES=1 is in the environment. Off by
/// default (issue 19 item 4, Docs/SCALING.md "Where the distributed filter's time goes"): with the
/// kernel's THP mode "madvise" it cuts the first touch of a fresh 512 MiB piece from 131 081 minor
/// page faults to 776 and the read 3-fold on this loaded VM, but one 4-rank run was slower with
/// it (the kernel compacting memory for huge pages, presumably): not measured on an idle machine.
void adviseHugePages(void* buffer, std::size_t bytes)
{
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  const char* setting = std::getenv("VESSELTOUCH_READER_HUGE_PAGES");
  if (!setting || std::string(setting) != "1")
  {
    return;
  }
  constexpr std::uintptr_t huge = 2u << 20;
  const auto first = (reinterpret_cast<std::uintptr_t>(buffer) + huge - 1) & ~(huge - 1);
  const auto last = (reinterpret_cast<std::uintptr_t>(buffer) + bytes) & ~(huge - 1);
  if (last > first)
  {
    madvise(reinterpret_cast<void*>(first), last - first, MADV_HUGEPAGE);
  }
#else
  (void)buffer;
  (void)bytes;
#endif
}

void addSeconds(vtkFieldData* fd, const char* name, double seconds)
{
  vtkNew<vtkDoubleArray> a;
  a->SetName(name);
  a->InsertNextValue(seconds);
  fd->AddArray(a);
}
} // namespace

int vtkVesselTouchImageReader::RequestData(vtkInformation*,
  vtkInformationVector**,
  vtkInformationVector* outputVector)
{
  const auto start = std::chrono::steady_clock::now();
  vtkImageData* output = vtkImageData::GetData(outputVector, 0);
  if (!output)
  {
    vtkErrorMacro("VesselTouch reader: missing output image.");
    return 0;
  }
  int previousExtent[6];
  vtkSmartPointer<vtkDataArray> previous = this->ReusablePiece(previousExtent);
  output->Initialize();
  // Held now by `previous` alone (the output let go of it: no view or filter keeps it), the old
  // voxels are released before the new read, so that the peak memory is the new piece's alone,
  // as without reuse. Held elsewhere too (a view's representation), they stay in memory anyway
  // and copying from them costs nothing. (Counted before the output let go, the references
  // the output's own structures hold made a piece look held elsewhere: rank 0 of a 2-rank
  // 1024 x 1024 x 512 run kept its 512 MiB piece through the whole volume's read.)
  if (previous && previous->GetReferenceCount() <= 1)
  {
    previous = nullptr;
  }
  this->LastPieceArray = nullptr;
  this->LastBytesRead = this->LastBytesReused = 0.0;
  this->LastFilesRead = 0;
  if (!this->Source)
  {
    return 1; // RequestInformation reported why
  }
  const vtouch::VolumeHeader& header = this->Source->header();
  const vtouch::VolumeGeometry g = header.geometry.inFrame(
    this->OutputFrame == RAS ? vtouch::WorldFrame::RAS : vtouch::WorldFrame::LPS);
  // The piece asked for (the whole volume in a serial pipeline), clipped to the volume.
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  int extent[6] = { 0,
    static_cast<int>(g.dimensions[0]) - 1,
    0,
    static_cast<int>(g.dimensions[1]) - 1,
    0,
    static_cast<int>(g.dimensions[2]) - 1 };
  if (outInfo->Has(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT()))
  {
    int asked[6];
    outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(), asked);
    for (int a = 0; a < 3; ++a)
    {
      extent[2 * a] = std::max(extent[2 * a], asked[2 * a]);
      extent[2 * a + 1] = std::min(extent[2 * a + 1], asked[2 * a + 1]);
    }
  }
  vtouch::VoxelExtent box;
  for (int a = 0; a < 3; ++a)
  {
    if (extent[2 * a] > extent[2 * a + 1])
    {
      return 1; // an empty piece (more ranks than slices): an empty output
    }
    box.first[a] = static_cast<std::size_t>(extent[2 * a]);
    box.last[a] = static_cast<std::size_t>(extent[2 * a + 1]);
  }
  if (!this->Source->readsExtentsAlone() && box.voxelCount() < g.voxelCount() &&
      !this->WarnedWholeDecode)
  {
    vtkWarningMacro(
      "VesselTouch reader: '"
      << this->FileName
      << "' is compressed: each piece of a parallel read decodes the whole file. Store it "
         "uncompressed (.nii, raw NRRD or MetaImage) so that each rank reads only its piece.");
    this->WarnedWholeDecode = true;
  }

  vtkSmartPointer<vtkDataArray> scalars;
  scalars.TakeReference(vtkDataArray::CreateDataArray(vtkTypeOf(header.voxelType)));
  scalars->SetName("ImageScalars");
  scalars->SetNumberOfComponents(1);
  // The file is read straight into this array: no intermediate ITK image, no copy.
  const std::size_t bytes = box.voxelCount() * vtouch::voxelSize(header.voxelType);
  if (!scalars->Resize(static_cast<vtkIdType>(box.voxelCount())))
  {
    vtkErrorMacro("VesselTouch reader: cannot allocate " << bytes << " bytes for the volume.");
    return 1;
  }
  scalars->SetNumberOfTuples(static_cast<vtkIdType>(box.voxelCount()));
  adviseHugePages(scalars->GetVoidPointer(0), bytes);
  auto progress = [this](double fraction)
  {
    this->UpdateProgress(fraction);
    return !this->CheckAbort();
  };
  vtouch::VoxelExtent previousBox;
  for (int a = 0; a < 3 && previous; ++a)
  {
    previousBox.first[a] = static_cast<std::size_t>(previousExtent[2 * a]);
    previousBox.last[a] = static_cast<std::size_t>(previousExtent[2 * a + 1]);
  }
  // Project rule: the copy is for a piece grown by its ghost margin (the old piece covers most
  // of the new one). A request more than twice the old piece (the whole volume on the first
  // rank) reads anew: there the old piece was measured to outlive the read, 2324 instead of
  // 1875 MiB at the peak of a 2-rank 1024 x 1024 x 512 extraction, for a saving of at most half
  // the read.
  if (previous)
  {
    const std::optional<vtouch::VoxelExtent> shared = vtouch::intersectExtents(box, previousBox);
    if (!shared || 2 * shared->voxelCount() <= box.voxelCount())
    {
      previous = nullptr;
    }
  }
  try
  {
    vtouch::ExtentReuseStatistics read;
    const bool done = vtouch::readExtentReusing(*this->Source, box, scalars->GetVoidPointer(0),
      bytes, previous ? previous->GetVoidPointer(0) : nullptr, previousBox, progress, read);
    previous = nullptr; // the old piece goes as soon as it was copied
    this->LastBytesRead = static_cast<double>(read.read.bytesRead);
    this->LastBytesReused = static_cast<double>(read.bytesReused);
    this->LastFilesRead = static_cast<int>(read.read.filesRead);
    if (!done)
    {
      return 1; // aborted by the user: an empty output, no error
    }
  }
  catch (const vtouch::VolumeIOError& e)
  {
    vtkErrorMacro("VesselTouch reader: " << e.what() << ". The output is empty.");
    return 1;
  }
  const auto rangeStart = std::chrono::steady_clock::now();
  CacheValueRange(scalars, header.voxelType);
  const double rangeSeconds = secondsSince(rangeStart);
  output->SetExtent(extent);
  output->SetSpacing(g.spacing_mm.data());
  output->SetOrigin(g.origin_mm.data());
  output->SetDirectionMatrix(g.direction.data());
  output->GetPointData()->SetScalars(scalars);
  this->MarkGhostLayers(outInfo, output);
  this->AddReadStatistics(output);
  this->RememberPiece(output);
  // Where a piece's time goes (issue 19 item 4): the whole RequestData and its value range.
  addSeconds(output->GetFieldData(), "ReaderValueRangeSeconds", rangeSeconds);
  addSeconds(output->GetFieldData(), "ReaderSeconds", secondsSince(start));
  return 1;
}

vtkDataArray* vtkVesselTouchImageReader::ReusablePiece(int extent[6]) const
{
  vtkDataArray* scalars = this->LastPieceArray;
  if (!scalars || !this->Source || !this->Source->readsExtentsAlone() ||
      scalars->GetMTime() != this->LastPieceArrayTime ||
      this->OpenTime.GetMTime() != this->LastPieceOpenTime)
  {
    return nullptr; // gone, another file, a compressed one (each box would decode the whole
                    // file), or voxels changed since
  }
  std::copy(this->LastPieceExtent, this->LastPieceExtent + 6, extent);
  return scalars;
}

void vtkVesselTouchImageReader::RememberPiece(vtkImageData* output)
{
  vtkDataArray* scalars = output->GetPointData()->GetScalars();
  this->LastPieceArray = scalars;
  this->LastPieceArrayTime = scalars ? scalars->GetMTime() : 0;
  this->LastPieceOpenTime = this->OpenTime.GetMTime();
  output->GetExtent(this->LastPieceExtent);
}

void vtkVesselTouchImageReader::MarkGhostLayers(vtkInformation* outInfo, vtkImageData* output)
{
  // Downstream filters that ask for ghost levels (a distributed filter coding its piece with a
  // margin) get the executive's piece extent grown by those levels; the layers that belong to a
  // neighbour are marked in vtkGhostType so they are not counted twice.
  const int ghostLevels =
    outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_GHOST_LEVELS());
  const int pieces = outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES());
  if (ghostLevels <= 0 || pieces <= 1)
  {
    return;
  }
  int whole[6];
  outInfo->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), whole);
  int owned[6];
  vtkNew<vtkExtentTranslator> translator;
  translator->PieceToExtentThreadSafe(
    outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER()),
    pieces,
    0,
    whole,
    owned,
    vtkExtentTranslator::BLOCK_MODE,
    0);
  output->GenerateGhostArray(owned);
}

void vtkVesselTouchImageReader::CacheValueRange(vtkDataArray* scalars, vtouch::VoxelType type)
{
  // VTK keeps an array's range per component in its information (PER_COMPONENT for GetRange,
  // PER_FINITE_COMPONENT for GetFiniteRange), valid while the array is not modified after it:
  // ParaView's data information and colour maps then read it instead of scanning the voxels with
  // VTK's slow generic loop (vtouchVoxelValueRange.h says how slow).
  const vtouch::VoxelValueRange r = vtouch::computeVoxelValueRange(
    scalars->GetVoidPointer(0), type, static_cast<std::size_t>(scalars->GetNumberOfTuples()));
  const auto cache = [scalars](vtkInformationInformationVectorKey* key, double lo, double hi)
  {
    vtkNew<vtkInformationVector> perComponent;
    perComponent->SetNumberOfInformationObjects(1);
    const double range[2] = { lo, hi };
    perComponent->GetInformationObject(0)->Set(vtkDataArray::COMPONENT_RANGE(), range, 2);
    scalars->GetInformation()->Set(key, perComponent);
  };
  if (!r.empty())
  {
    cache(vtkAbstractArray::PER_COMPONENT(), r.min, r.max);
  }
  if (!r.finiteEmpty())
  {
    cache(vtkAbstractArray::PER_FINITE_COMPONENT(), r.finiteMin, r.finiteMax);
  }
}

void vtkVesselTouchImageReader::AddReadStatistics(vtkImageData* output)
{
  // What this piece cost, where a parallel pipeline's rank can report it (field data travels with
  // the piece; information properties would only show the first rank's).
  vtkNew<vtkDoubleArray> bytes;
  bytes->SetName("ReaderVoxelBytesRead");
  bytes->InsertNextValue(this->GetLastReadBytes());
  vtkNew<vtkDoubleArray> reused;
  reused->SetName("ReaderVoxelBytesReused");
  reused->InsertNextValue(this->GetLastReusedBytes());
  output->GetFieldData()->AddArray(reused);
  vtkNew<vtkIntArray> files;
  files->SetName("ReaderFilesRead");
  files->InsertNextValue(this->GetLastReadFiles());
  vtkNew<vtkIntArray> alone;
  alone->SetName("ReaderReadsPiecesAlone");
  alone->InsertNextValue(this->GetReadsPiecesAlone());
  output->GetFieldData()->AddArray(bytes);
  output->GetFieldData()->AddArray(files);
  output->GetFieldData()->AddArray(alone);
}

int vtkVesselTouchImageReader::GetReadsPiecesAlone()
{
  return this->Source && this->Source->readsExtentsAlone() ? 1 : 0;
}

double vtkVesselTouchImageReader::GetLastReadBytes()
{
  return this->LastBytesRead;
}

double vtkVesselTouchImageReader::GetLastReusedBytes()
{
  return this->LastBytesReused;
}

int vtkVesselTouchImageReader::GetLastReadFiles()
{
  return this->LastFilesRead;
}

void vtkVesselTouchImageReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << (this->FileName ? this->FileName : "(none)") << "\n"
     << indent
     << "SeriesInstanceUID: " << (this->SeriesInstanceUID ? this->SeriesInstanceUID : "(largest)")
     << "\n"
     << indent << "OutputFrame: " << (this->OutputFrame == RAS ? "RAS" : "LPS") << "\n"
     << indent << "FileFormat: " << this->FileFormat << "\n";
}

#include "vtouchDistributedCenterline.h"

#include "vtouchSkeletonClipper.h"
#include "vtouchSkeletonFragmentCodec.h"
#include "vtouchSkeletonOverlapResolver.h"

#include "vtkDoubleArray.h"
#include "vtkExtentTranslator.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkIntArray.h"
#include "vtkMatrix3x3.h"
#include "vtkMultiProcessController.h"
#include "vtkNew.h"
#include "vtkPointData.h"

#include <sys/resource.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <sstream>

namespace vtouch
{

vtkMultiProcessController* DistributedCenterline::controllerFor(int piece, int pieces)
{
  vtkMultiProcessController* c = vtkMultiProcessController::GetGlobalController();
  if (pieces <= 1 || !c || c->GetNumberOfProcesses() != pieces || c->GetLocalProcessId() != piece)
  {
    return nullptr;
  }
  return c;
}

std::vector<VoxelExtent6> DistributedCenterline::pieceExtents(const VoxelExtent6& whole, int pieces)
{
  std::vector<VoxelExtent6> extents;
  vtkNew<vtkExtentTranslator> translator;
  for (int r = 0; r < pieces; ++r)
  {
    int wholeCopy[6];
    std::copy(whole.begin(), whole.end(), wholeCopy);
    int piece[6];
    translator->PieceToExtentThreadSafe(
      r, pieces, 0, wholeCopy, piece, vtkExtentTranslator::BLOCK_MODE, 0);
    VoxelExtent6 e;
    std::copy(piece, piece + 6, e.begin());
    extents.push_back(e);
  }
  return extents;
}

double DistributedCenterline::peakResidentKiB()
{
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss); // Linux: KiB
}

namespace
{
constexpr int kReportValues = 12;

std::array<double, kReportValues> encodeReport(const PieceReport& r)
{
  return { static_cast<double>(r.inputExtent[0]),
    static_cast<double>(r.inputExtent[1]),
    static_cast<double>(r.inputExtent[2]),
    static_cast<double>(r.inputExtent[3]),
    static_cast<double>(r.inputExtent[4]),
    static_cast<double>(r.inputExtent[5]),
    r.readerBytes,
    r.peakResident_kiB,
    r.fragments,
    r.rangeLower,
    r.rangeUpper,
    r.extractSeconds };
}

PieceReport decodeReport(const double* d)
{
  PieceReport r;
  for (std::size_t i = 0; i < 6; ++i)
  {
    r.inputExtent[i] = static_cast<int>(d[i]);
  }
  r.readerBytes = d[6];
  r.peakResident_kiB = d[7];
  r.fragments = d[8];
  r.rangeLower = d[9];
  r.rangeUpper = d[10];
  r.extractSeconds = d[11];
  return r;
}
} // namespace

bool DistributedCenterline::gatherAndStitch(vtkMultiProcessController* controller,
  const QSkeleton& own,
  const IndexFrame& frame,
  const VoxelExtent6& whole,
  PieceReport report,
  double joinTolerance_mm,
  Result& result)
{
  using Clock = std::chrono::steady_clock;
  const auto since = [](Clock::time_point t0)
  { return std::chrono::duration<double>(Clock::now() - t0).count(); };
  const Clock::time_point gatherStart = Clock::now();
  const int ranks = controller->GetNumberOfProcesses();
  const int rank = controller->GetLocalProcessId();
  const PieceOwnership ownership(pieceExtents(whole, ranks), whole);
  // The owned points and the overlap band beyond the shared faces (kOverlapBandVoxels).
  const std::vector<SkeletonFragment> fragments =
    SkeletonClipper(ownership, frame, rank, kOverlapBandVoxels).clip(own);
  const std::vector<double> sent = SkeletonFragmentCodec::encode(fragments);
  report.fragments = static_cast<double>(fragments.size());
  report.peakResident_kiB = peakResidentKiB();
  // Fixed-size reports and the lengths first, then the fragments (GatherV).
  const std::array<double, kReportValues> mine = encodeReport(report);
  std::vector<double> reports(static_cast<std::size_t>(kReportValues * ranks));
  controller->Gather(mine.data(), reports.data(), kReportValues, 0);
  const vtkIdType length = static_cast<vtkIdType>(sent.size());
  std::vector<vtkIdType> lengths(static_cast<std::size_t>(ranks), 0);
  controller->Gather(&length, lengths.data(), 1, 0);
  std::vector<vtkIdType> offsets(static_cast<std::size_t>(ranks), 0);
  vtkIdType total = 0;
  for (int r = 0; r < ranks; ++r)
  {
    offsets[static_cast<std::size_t>(r)] = total;
    total += lengths[static_cast<std::size_t>(r)];
  }
  std::vector<double> received(static_cast<std::size_t>(rank == 0 ? total : 0) + 1);
  controller->GatherV(sent.data(), received.data(), length, lengths.data(), offsets.data(), 0);
  if (rank != 0)
  {
    return false;
  }
  result.gatherSeconds = since(gatherStart);
  const Clock::time_point stitchStart = Clock::now();
  std::vector<SkeletonFragment> all;
  for (int r = 0; r < ranks; ++r)
  {
    result.pieces.push_back(decodeReport(reports.data() + kReportValues * r));
    std::string error;
    if (!SkeletonFragmentCodec::decode(received.data() + offsets[static_cast<std::size_t>(r)],
          static_cast<std::size_t>(lengths[static_cast<std::size_t>(r)]),
          all,
          error))
    {
      std::ostringstream text;
      text << "the skeleton fragments of rank " << r << " are unreadable (" << error << ")";
      result.error = text.str();
    }
  }
  SkeletonStitcher stitcher;
  stitcher.joinTolerance_mm = joinTolerance_mm;
  stitcher.ownership = ownership;
  stitcher.frame = frame;
  const double voxel_mm = *std::max_element(frame.spacing_mm.begin(), frame.spacing_mm.end());
  stitcher.copyReach_mm = kCopyReachVoxels * voxel_mm;
  stitcher.coverageReach_mm = kCopyReachVoxels * voxel_mm;
  stitcher.coincidentPoint_mm = kCoincidentPointVoxels * voxel_mm;
  result.skeleton = stitcher.stitch(all, result.stitch);
  result.stitchSeconds = since(stitchStart);
  return true;
}

IndexFrame DistributedCenterline::indexFrame(vtkImageData* image)
{
  IndexFrame frame;
  image->GetOrigin(frame.origin_mm.data());
  image->GetSpacing(frame.spacing_mm.data());
  if (vtkMatrix3x3* m = image->GetDirectionMatrix())
  {
    for (int e = 0; e < 9; ++e)
    {
      frame.direction[static_cast<std::size_t>(e)] = m->GetData()[e];
    }
  }
  return frame;
}

vtkSmartPointer<vtkImageData> DistributedCenterline::pieceFromIndexZero(vtkImageData* piece)
{
  int extent[6];
  piece->GetExtent(extent);
  auto local = vtkSmartPointer<vtkImageData>::New();
  local->SetDimensions(
    extent[1] - extent[0] + 1, extent[3] - extent[2] + 1, extent[5] - extent[4] + 1);
  local->SetSpacing(piece->GetSpacing());
  local->SetDirectionMatrix(piece->GetDirectionMatrix());
  double first[3];
  piece->TransformIndexToPhysicalPoint(extent[0], extent[2], extent[4], first);
  local->SetOrigin(first);
  local->GetPointData()->ShallowCopy(piece->GetPointData());
  local->GetFieldData()->ShallowCopy(piece->GetFieldData());
  return local;
}

namespace
{
void addIntValue(vtkFieldData* fd, const char* name, int value)
{
  vtkNew<vtkIntArray> a;
  a->SetName(name);
  a->InsertNextValue(value);
  fd->AddArray(a);
}
} // namespace

bool DistributedCenterline::addReports(vtkFieldData* fd,
  const Result& result,
  int ghostMarginVoxels,
  const double rangeUsed[2])
{
  addIntValue(fd, "DistributedPieces", static_cast<int>(result.pieces.size()));
  addIntValue(fd, "GhostMarginVoxels", ghostMarginVoxels);
  addIntValue(fd, "StitchCutEndsJoined", result.stitch.cutEndsJoined);
  addIntValue(fd, "StitchCutEndsUnmatched", result.stitch.cutEndsUnmatched);
  addIntValue(fd, "StitchAttachmentsUnresolved", result.stitch.attachmentsUnresolved);
  addIntValue(fd, "StitchLoopsClosed", result.stitch.loopsClosed);
  addIntValue(fd, "StitchBifurcationsWithoutBranch", result.stitch.bifurcationsWithoutBranch);
  addIntValue(fd, "StitchDuplicatesRemoved", result.stitch.duplicatesRemoved);
  addIntValue(fd, "StitchBandStubsDropped", result.stitch.bandStubsDropped);
  addIntValue(fd, "StitchPointsDropped", result.stitch.pointsDropped);
  addIntValue(fd, "StitchStrayPointsDropped", result.stitch.strayPointsDropped);
  vtkNew<vtkIntArray> extents;
  extents->SetName("PieceInputExtents");
  extents->SetNumberOfComponents(6);
  vtkNew<vtkDoubleArray> bytes;
  bytes->SetName("PieceReaderVoxelBytesRead");
  vtkNew<vtkDoubleArray> peak;
  peak->SetName("PiecePeakResidentKiB");
  vtkNew<vtkIntArray> fragments;
  fragments->SetName("PieceFragments");
  vtkNew<vtkDoubleArray> extractSeconds;
  extractSeconds->SetName("PieceExtractSeconds");
  // With AutomaticIntensityRange each rank estimates the range on its own piece: the same for a
  // binary mask (its midpoint), not always for a raw volume.
  bool rangesDiffer = false;
  for (const PieceReport& r : result.pieces)
  {
    double e[6];
    std::copy(r.inputExtent.begin(), r.inputExtent.end(), e);
    extents->InsertNextTuple(e);
    bytes->InsertNextValue(r.readerBytes);
    peak->InsertNextValue(r.peakResident_kiB);
    fragments->InsertNextValue(static_cast<int>(r.fragments));
    extractSeconds->InsertNextValue(r.extractSeconds);
    const double scale = std::max({ 1.0, std::abs(r.rangeLower), std::abs(r.rangeUpper) });
    if (r.fragments > 0.0 && (std::abs(r.rangeLower - rangeUsed[0]) > 1e-6 * scale ||
                               std::abs(r.rangeUpper - rangeUsed[1]) > 1e-6 * scale))
    {
      rangesDiffer = true;
    }
  }
  fd->AddArray(extents);
  fd->AddArray(bytes);
  fd->AddArray(peak);
  fd->AddArray(fragments);
  fd->AddArray(extractSeconds);
  for (const auto& [name, seconds] :
    { std::make_pair("DistributedGatherSeconds", result.gatherSeconds),
      std::make_pair("DistributedStitchSeconds", result.stitchSeconds) })
  {
    vtkNew<vtkDoubleArray> a;
    a->SetName(name);
    a->InsertNextValue(seconds);
    fd->AddArray(a);
  }
  addIntValue(fd, "PieceIntensityRangesDiffer", rangesDiffer ? 1 : 0);
  return rangesDiffer;
}

} // namespace vtouch

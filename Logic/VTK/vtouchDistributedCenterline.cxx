#include "vtouchDistributedCenterline.h"

#include "vtouchRankTimeline.h"
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
#include <functional>
#include <iterator>
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
// The report's values as they travel: the input extent, then these fields in this order.
constexpr double PieceReport::*kReportFields[] = { &PieceReport::readerBytes,
  &PieceReport::peakResident_kiB,
  &PieceReport::fragments,
  &PieceReport::rangeLower,
  &PieceReport::rangeUpper,
  &PieceReport::extractSeconds,
  &PieceReport::requestLast_Epoch_s,
  &PieceReport::dataEntry_Epoch_s,
  &PieceReport::extractStart_Epoch_s,
  &PieceReport::gatherEntry_Epoch_s,
  &PieceReport::maskSeconds,
  &PieceReport::codeSeconds,
  &PieceReport::readerSeconds,
  &PieceReport::readerValueRangeSeconds };
constexpr int kReportValues = 6 + static_cast<int>(std::size(kReportFields));

std::array<double, kReportValues> encodeReport(const PieceReport& r)
{
  std::array<double, kReportValues> values{};
  for (std::size_t i = 0; i < 6; ++i)
  {
    values[i] = static_cast<double>(r.inputExtent[i]);
  }
  for (std::size_t f = 0; f < std::size(kReportFields); ++f)
  {
    values[6 + f] = r.*kReportFields[f];
  }
  return values;
}

PieceReport decodeReport(const double* d)
{
  PieceReport r;
  for (std::size_t i = 0; i < 6; ++i)
  {
    r.inputExtent[i] = static_cast<int>(d[i]);
  }
  for (std::size_t f = 0; f < std::size(kReportFields); ++f)
  {
    r.*kReportFields[f] = d[6 + f];
  }
  return r;
}
} // namespace

bool DistributedCenterline::gatherAndStitch(vtkMultiProcessController* controller,
  const QSkeleton& own,
  const IndexFrame& frame,
  const VoxelExtent6& whole,
  PieceReport report,
  double joinTolerance_mm,
  Result& result,
  const ProgressCallback& stitchProgress)
{
  using Clock = std::chrono::steady_clock;
  const auto since = [](Clock::time_point t0)
  { return std::chrono::duration<double>(Clock::now() - t0).count(); };
  const Clock::time_point gatherStart = Clock::now();
  report.gatherEntry_Epoch_s = epochSeconds();
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
  stitcher.progress = stitchProgress;
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

PieceInWhole DistributedCenterline::pieceInWhole(vtkImageData* piece)
{
  PieceInWhole frame;
  int extent[6];
  piece->GetExtent(extent);
  for (std::size_t a = 0; a < 3; ++a)
  {
    frame.first_Whole[a] = extent[2 * a];
  }
  piece->GetOrigin(frame.wholeOrigin_World_mm.data());
  return frame;
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

/// `to - from`, 0 when a stamp was not taken (a rank without a piece).
double between(double from_Epoch_s, double to_Epoch_s)
{
  return from_Epoch_s > 0.0 && to_Epoch_s > 0.0 ? to_Epoch_s - from_Epoch_s : 0.0;
}

/// Where each rank's time went (issue 19, item 4): one value per rank in each array.
void addBreakdown(vtkFieldData* fd, const std::vector<PieceReport>& pieces)
{
  double lastGather_Epoch_s = 0.0;
  for (const PieceReport& r : pieces)
  {
    lastGather_Epoch_s = std::max(lastGather_Epoch_s, r.gatherEntry_Epoch_s);
  }
  using Value = std::function<double(const PieceReport&)>;
  const std::pair<const char*, Value> columns[] = {
    { "PieceUpstreamSeconds",
      [](const PieceReport& r) { return between(r.requestLast_Epoch_s, r.dataEntry_Epoch_s); } },
    { "PieceReaderSeconds", [](const PieceReport& r) { return r.readerSeconds; } },
    { "PieceReaderValueRangeSeconds",
      [](const PieceReport& r) { return r.readerValueRangeSeconds; } },
    { "PieceBeforeExtractSeconds",
      [](const PieceReport& r) { return between(r.dataEntry_Epoch_s, r.extractStart_Epoch_s); } },
    { "PieceMaskSeconds", [](const PieceReport& r) { return r.maskSeconds; } },
    { "PieceCodeSeconds", [](const PieceReport& r) { return r.codeSeconds; } },
    { "PieceAfterExtractSeconds",
      [](const PieceReport& r)
      {
        return r.extractStart_Epoch_s > 0.0
                 ? between(r.extractStart_Epoch_s + r.extractSeconds, r.gatherEntry_Epoch_s)
                 : 0.0;
      } },
    { "PieceGatherWaitSeconds",
      [lastGather_Epoch_s](const PieceReport& r)
      { return between(r.gatherEntry_Epoch_s, lastGather_Epoch_s); } },
    // Stamps, not durations (no "Seconds" suffix): the client compares them with its own clock.
    { "PieceRequestEpoch", [](const PieceReport& r) { return r.requestLast_Epoch_s; } },
    { "PieceRequestDataEntryEpoch", [](const PieceReport& r) { return r.dataEntry_Epoch_s; } },
    { "PieceGatherEntryEpoch", [](const PieceReport& r) { return r.gatherEntry_Epoch_s; } },
  };
  for (const auto& [name, value] : columns)
  {
    vtkNew<vtkDoubleArray> a;
    a->SetName(name);
    for (const PieceReport& r : pieces)
    {
      a->InsertNextValue(value(r));
    }
    fd->AddArray(a);
  }
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
  addBreakdown(fd, result.pieces);
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

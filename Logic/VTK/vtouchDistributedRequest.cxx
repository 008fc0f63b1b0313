#include "vtouchDistributedRequest.h"

#include "vtouchCandidateRegionRunner.h"
#include "vtouchControllerCollectives.h"
#include "vtouchDistributedCenterline.h"
#include "vtouchPolyDataToQSkeleton.h"

#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMultiProcessController.h"
#include "vtkNew.h"
#include "vtkPolyData.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include <algorithm>
#include <chrono>

namespace vtouch
{

namespace
{
/// The first value of the field-data array `name`, or `otherwise` when there is none.
double firstValue(vtkFieldData* fd, const char* name, double otherwise)
{
  vtkDataArray* a = fd ? fd->GetArray(name) : nullptr;
  return a && a->GetNumberOfTuples() > 0 ? a->GetComponent(0, 0) : otherwise;
}
} // namespace

void DistributedRequest::requestGrownPiece(vtkInformation* in,
  int piece,
  int pieces,
  int ghostMarginVoxels,
  int extent[6])
{
  // This rank's piece grown by the ghost margin on its shared faces (vtouch::GhostMarginRule).
  VoxelExtent6 whole;
  std::copy(extent, extent + 6, whole.begin());
  const VoxelExtent6 grown =
    grownExtent(DistributedCenterline::pieceExtents(whole, pieces)[static_cast<std::size_t>(piece)],
      whole,
      ghostMarginVoxels);
  std::copy(grown.begin(), grown.end(), extent);
  // As one piece of that extent: a reader that splits by piece number (ParaView's XML
  // readers split their own way) would intersect its split with the extent.
  in->Set(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER(), 0);
  in->Set(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES(), 1);
  in->Set(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_GHOST_LEVELS(), 0);
}

DistributedRequest::Outcome DistributedRequest::run(vtkInformationVector** inputVector,
  vtkPolyData* output,
  const Hooks& hooks)
{
  Outcome outcome;
  vtkImageData* input = vtkImageData::GetData(inputVector[0]);
  vtkMultiProcessController* controller = DistributedCenterline::controllerFor(
    vtkMultiProcessController::GetGlobalController()->GetLocalProcessId(),
    vtkMultiProcessController::GetGlobalController()->GetNumberOfProcesses());
  // This piece's own run; its errors (a piece without vessels is normal) wait for the stitch.
  vtkNew<vtkPolyData> own;
  QSkeleton skeleton;
  PieceReport report;
  IndexFrame frame;
  VoxelExtent6 whole{ 0, -1, 0, -1, 0, -1 };
  double largestSpacing = 1.0;
  std::string pieceMessage;
  report.requestLast_Epoch_s = hooks.timeline.lastRequest_Epoch_s;
  report.dataEntry_Epoch_s = hooks.timeline.dataEntry_Epoch_s;
  if (vtkInformation* in = inputVector[0]->GetInformationObject(0))
  {
    in->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), whole.data());
  }
  if (hooks.beforePiece)
  {
    hooks.beforePiece(input, whole); // collective: every rank, with or without a piece
  }
  if (input)
  {
    report.extractStart_Epoch_s = epochSeconds();
    const auto extractStart = std::chrono::steady_clock::now();
    hooks.extractPiece(DistributedCenterline::pieceFromIndexZero(input),
      DistributedCenterline::pieceInWhole(input),
      own);
    report.extractSeconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - extractStart).count();
    // Two of the coder's sequential stages (vtouch::VoxelCodingSkeletonFilter): the threshold
    // mask of the grown piece, and the coding itself.
    report.maskSeconds = firstValue(own->GetFieldData(), "CoderMaskSeconds", 0.0);
    report.codeSeconds = firstValue(own->GetFieldData(), "CoderCoderAllSeconds", 0.0);
    if (hooks.afterExtract)
    {
      hooks.afterExtract(); // collective
    }
    hooks.lastRun(outcome.rangeUsed, pieceMessage);
    std::string error;
    if (own->GetNumberOfLines() > 0 && !PolyDataToQSkeleton().convert(own, skeleton, error))
    {
      pieceMessage = "VesselCenterline: this piece's skeleton is unreadable: " + error;
      skeleton = QSkeleton{};
    }
    if (hooks.afterPiece)
    {
      hooks.afterPiece(input, own, skeleton);
    }
    report.rangeLower = outcome.rangeUsed[0];
    report.rangeUpper = outcome.rangeUsed[1];
    frame = DistributedCenterline::indexFrame(input);
    largestSpacing = std::max({ frame.spacing_mm[0], frame.spacing_mm[1], frame.spacing_mm[2] });
    input->GetExtent(report.inputExtent.data());
    vtkFieldData* read = input->GetFieldData();
    report.readerBytes = firstValue(read, "ReaderVoxelBytesRead", report.readerBytes);
    report.readerSeconds = firstValue(read, "ReaderSeconds", report.readerSeconds);
    report.readerValueRangeSeconds =
      firstValue(read, "ReaderValueRangeSeconds", report.readerValueRangeSeconds);
    if (report.readerSeconds >= 0.0 && input->GetUpdateTime() <= hooks.timeline.lastRequest_MTime)
    {
      // The reader did not run for this request (the piece it held was the one asked for): its
      // field data tells of an earlier run.
      report.readerSeconds = report.readerValueRangeSeconds = 0.0;
    }
  }
  else if (hooks.afterExtract)
  {
    hooks.afterExtract(); // collective: a rank without a piece joins too
  }
  // Collective: every rank gets here once per run, whatever its piece gave. First a cancel
  // point of its own (one word per rank): the first rank may have stopped its own stages for a
  // cancel the others have not heard of yet; every rank leaves here together, before the gather.
  {
    ControllerCollectives exchanges(controller);
    CancellableCollectives(exchanges, hooks.cancelRequested).agree();
  }
  DistributedCenterline::Result result;
  output->Initialize();
  // The first rank's stitch has check points of its own (hooks.stitchProgress, h18q): a cancel
  // there stops it on the first rank alone, after the gathers.
  bool firstRank = false;
  bool stitchCancelled = false;
  try
  {
    firstRank = DistributedCenterline::gatherAndStitch(controller,
      skeleton,
      frame,
      whole,
      report,
      2.0 * largestSpacing,
      result,
      hooks.stitchProgress);
  }
  catch (const Cancelled&)
  {
    firstRank = stitchCancelled = true;
  }
  // Collective: a cancel point after the stitch (one word per rank, h18q), where a stitch stopped
  // for a cancel meets the others and every rank throws together. The other ranks wait here for
  // the first rank's stitch (they would wait for it in ParaView's next collective, or in the
  // refinement's rounds, anyway): a rank that left before would keep this run as completed while
  // the first rank cancelled it, and the ranks' kept outputs (vtkVesselTouchCenterlineFilter's
  // project rule) would no longer be the same run's.
  {
    ControllerCollectives exchanges(controller);
    CancellableCollectives(exchanges,
      [&] { return stitchCancelled || (hooks.cancelRequested && hooks.cancelRequested()); })
      .agree();
  }
  if (!firstRank)
  {
    if (hooks.afterStitchCollective)
    {
      hooks.afterStitchCollective(input, whole, nullptr, nullptr); // serves the first rank
    }
    outcome.message = pieceMessage;
    return outcome; // not the first rank: an empty piece of the output
  }
  outcome.firstRank = true;
  if (!result.skeleton.empty() && hooks.afterStitch)
  {
    hooks.afterStitch(result.skeleton, frame);
  }
  std::string stitchedError;
  if (hooks.afterStitchCollective)
  {
    stitchedError = hooks.afterStitchCollective(
      input, whole, result.skeleton.empty() ? nullptr : &result.skeleton, output->GetFieldData());
  }
  if (!result.skeleton.empty() && hooks.beforeFill)
  {
    hooks.beforeFill(result.skeleton);
  }
  if (!result.skeleton.empty())
  {
    // (An empty skeleton's zero-tuple topology arrays would make the client lose every field
    // array on the way, the message with them.)
    hooks.fill(result.skeleton, output);
  }
  vtkFieldData* fd = output->GetFieldData();
  // The first rank's run data (range, factor, stage times, ...), then the stitch's.
  vtkFieldData* ownFd = own->GetFieldData();
  for (int i = 0; i < ownFd->GetNumberOfArrays(); ++i)
  {
    vtkAbstractArray* a = ownFd->GetAbstractArray(i);
    if (a && a->GetName() && !fd->GetAbstractArray(a->GetName()))
    {
      fd->AddArray(a);
    }
  }
  std::string message;
  if (result.skeleton.empty())
  {
    message = pieceMessage.empty()
                ? std::string("VesselCenterline: no piece of the volume gave a skeleton.")
                : pieceMessage;
  }
  if (!result.error.empty())
  {
    message = "VesselCenterline: " + result.error;
  }
  if (!stitchedError.empty() && message.empty())
  {
    message = "VesselCenterline (distributed): " + stitchedError;
  }
  outcome.message = message;
  addRangeFieldData(
    fd, outcome.rangeUsed[0], outcome.rangeUsed[1], hooks.automaticIntensityRange, message);
  const bool rangesDiffer = DistributedCenterline::addReports(
    fd, result, hooks.ghostMarginVoxels(frame.spacing_mm.data()), outcome.rangeUsed);
  if (rangesDiffer)
  {
    outcome.warnings.push_back(
      "VesselCenterline (distributed): the ranks estimated different intensity "
      "ranges on their pieces; set AutomaticIntensityRange off and the thresholds "
      "for one range everywhere.");
  }
  for (const std::string& note : result.stitch.notes)
  {
    outcome.warnings.push_back("VesselCenterline (distributed): " + note);
  }
  // The first rank leaves RequestData now (the last rank to: it stitched); the client's wall
  // time after this stamp is the executive's end of the pass and ParaView's data information.
  vtkNew<vtkDoubleArray> exitStamp;
  exitStamp->SetName("DistributedRequestDataExitEpoch");
  exitStamp->InsertNextValue(epochSeconds());
  fd->AddArray(exitStamp);
  return outcome;
}

} // namespace vtouch

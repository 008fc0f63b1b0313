#include "vtouchDistributedRequest.h"

#include "vtouchCandidateRegionRunner.h"
#include "vtouchDistributedCenterline.h"
#include "vtouchPolyDataToQSkeleton.h"

#include "vtkDataArray.h"
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
    const auto extractStart = std::chrono::steady_clock::now();
    hooks.extractPiece(DistributedCenterline::pieceFromIndexZero(input), own);
    report.extractSeconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - extractStart).count();
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
    if (vtkDataArray* bytes = input->GetFieldData()->GetArray("ReaderVoxelBytesRead"))
    {
      report.readerBytes = bytes->GetComponent(0, 0);
    }
  }
  else if (hooks.afterExtract)
  {
    hooks.afterExtract(); // collective: a rank without a piece joins too
  }
  // Collective: every rank gets here once per run, whatever its piece gave.
  DistributedCenterline::Result result;
  output->Initialize();
  if (!DistributedCenterline::gatherAndStitch(
        controller, skeleton, frame, whole, report, 2.0 * largestSpacing, result))
  {
    outcome.message = pieceMessage;
    return outcome; // not the first rank: an empty piece of the output
  }
  outcome.firstRank = true;
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
  return outcome;
}

} // namespace vtouch

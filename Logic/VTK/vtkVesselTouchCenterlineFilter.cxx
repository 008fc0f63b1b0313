#include "vtkVesselTouchCenterlineFilter.h"

#include "vtouchCandidateRegionRunner.h"
#include "vtouchDistributedCenterline.h"
#include "vtouchDistributedRequest.h"
#include "vtouchDistributedRawRegion.h"
#include "vtouchDistributedShading.h"
#include "vtouchDistributedGlobalField.h"
#include "vtouchDistributedWholePathRefinement.h"
#include "vtouchControllerCollectives.h"
#include "vtouchRemoteCancelListener.h"
#include "vtouchPolyDataToQSkeleton.h"
#include "vtouchProgressThrottle.h"
#include "vtouchQSkeletonToPolyData.h"
#include "vtouchRangeForeground.h"
#include "vtouchRawSkeletonRefinement.h"
#include "vtouchSeedComponentSplit.h"
#include "vtouchShadingCorrection.h"
#include "vtouchBranchEntry.h"
#include "vtouchSkeletonPathSmoothing.h"
#include "vtouchSteadyClock.h"
#include "vtouchVolumeSkeletonizer.h"

#include "vtkCellArray.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkMatrix3x3.h"
#include "vtkMultiProcessController.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkStringArray.h"
#include "vtkUnsignedCharArray.h"

#include <itkCommand.h>
#include <itkImportImageFilter.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <memory>
#include <new>
#include <sstream>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkVesselTouchCenterlineFilter);

namespace
{
/// The piece's run's share of a distributed run's progress, the first rank's stitch taking the
/// rest up to 95 % (h18q). Project rule: the long runs the cancel is for spend most of their time
/// in the stitch (the 128^3 raw phantom on 2 ranks: 21-74 s of 26-85 s), short ones in the
/// pieces; half and half shows both moving.
constexpr double kPieceProgressShare = 0.5;
} // namespace

vtkVesselTouchCenterlineFilter::vtkVesselTouchCenterlineFilter()
{
  this->SetInputArrayToProcess(
    0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, vtkDataSetAttributes::SCALARS);
}

vtkVesselTouchCenterlineFilter::~vtkVesselTouchCenterlineFilter() = default;

int vtkVesselTouchCenterlineFilter::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  return 1;
}

namespace
{
/// The piece of the output this process is asked for (0 built in and on rank 0).
int requestedPiece(vtkInformationVector* outputVector)
{
  vtkInformation* info = outputVector->GetInformationObject(0);
  return info && info->Has(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER())
           ? info->Get(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER())
           : 0;
}

/// The number of pieces the output is asked in (1 built in).
int requestedPieces(vtkInformationVector* outputVector)
{
  vtkInformation* info = outputVector->GetInformationObject(0);
  return info && info->Has(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES())
           ? info->Get(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES())
           : 1;
}
} // namespace

int vtkVesselTouchCenterlineFilter::RequestUpdateExtent(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkInformation* in = inputVector[0]->GetInformationObject(0);
  if (!in || !in->Has(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()))
  {
    return 1;
  }
  int extent[6];
  in->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent);
  const int piece = requestedPiece(outputVector), pieces = requestedPieces(outputVector);
  if (this->Distributed(piece, pieces))
  {
    this->DistributedTimeline.markRequest();
    double spacing[3] = { 1.0, 1.0, 1.0 };
    if (in->Has(vtkDataObject::SPACING()))
    {
      in->Get(vtkDataObject::SPACING(), spacing);
    }
    vtouch::DistributedRequest::requestGrownPiece(
      in, piece, pieces, this->GetGhostMarginVoxels(spacing), extent);
  }
  else if (piece > 0)
  {
    const int none[6] = { 0, -1, 0, -1, 0, -1 };
    std::copy(none, none + 6, extent);
  }
  else
  {
    // The whole volume as one piece: readers that split by piece number read it all.
    in->Set(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER(), 0);
    in->Set(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES(), 1);
  }
  in->Set(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(), extent, 6);
  in->Set(vtkStreamingDemandDrivenPipeline::EXACT_EXTENT(), 1);
  return 1;
}

int vtkVesselTouchCenterlineFilter::RequestData(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  // The client's Cancel on a pvserver (issue 19 item 1, issue 16 item 6): the first rank's
  // socket is open for this run only, closed however the run ends.
  struct RemoteCancelScope
  {
    vtkVesselTouchCenterlineFilter* filter;
    ~RemoteCancelScope() { this->filter->CloseRemoteCancel(); }
  } scope{ this };
  // Project rule (Docs/CLIENT-SERVER.md, "Cancel on a pvserver"): the output of the last run that
  // completed is kept (a shallow copy: the executive empties the output before each run), and
  // after a cancelled run a run with that run's key (its parameters, restored by the panel after
  // a remote cancel) returns it at once. Each rank keeps its own (its piece's).
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  const std::string key = this->RequestKey(inputVector);
  if (output && this->LastRunCancelled && this->CompletedOutput && !key.empty() &&
      key == this->CompletedRunKey)
  {
    this->RestoreOutput(this->CompletedOutput, output);
    this->LastRunKey = key;
    this->LastRunCancelled = false;
    this->LastRunPrecomputed = true;
    this->UpdateProgress(1.0);
    return 1;
  }
  this->OpenRemoteCancel();
  const int result = this->ExecuteRequest(inputVector, outputVector);
  if (!this->LastRunCancelled && output)
  {
    this->CompletedOutput = vtkSmartPointer<vtkPolyData>::New();
    this->CompletedOutput->ShallowCopy(output);
    this->CompletedRunKey = key;
  }
  return result;
}

std::string vtkVesselTouchCenterlineFilter::RequestKey(vtkInformationVector** inputVector)
{
  vtkImageData* input = vtkImageData::GetData(inputVector[0]);
  if (!input)
  {
    return std::string();
  }
  vtkDataArray* scalars = this->GetInputArrayToProcess(0, inputVector);
  if (!scalars)
  {
    scalars = input->GetPointData()->GetScalars();
  }
  return scalars ? this->RunKey(input, scalars) : std::string();
}

void vtkVesselTouchCenterlineFilter::OpenRemoteCancel()
{
  this->RemoteCancel.reset();
  this->RemoteCancelPort = 0;
  vtkMultiProcessController* global = vtkMultiProcessController::GetGlobalController();
  const bool firstRank = !global || global->GetLocalProcessId() == 0;
  if (this->RemoteCancelToken.empty())
  {
    return;
  }
  this->RemoteCancel = std::make_unique<vtouch::RemoteCancelListener>(this->RemoteCancelToken);
  if (!this->RemoteCancel->listening())
  {
    vtkWarningMacro(<< "VesselCenterline: this run cannot be cancelled from the client"
                    << (firstRank ? "" : " before this rank's next exchange") << " ("
                    << this->RemoteCancel->error() << ").");
    this->RemoteCancel.reset();
    return;
  }
  this->RemoteCancelPort = this->RemoteCancel->port();
  if (!firstRank)
  {
    return; // told by the first rank's socket (ShareRemoteCancelPorts)
  }
  // ParaView sends the first rank's progress, with its text, to the client during the update
  // (vtkPVProgressHandler): the client reads the port there (vesseltouch.remote_cancel). Every
  // progress report of the run carries it, so a report ParaView skips loses nothing.
  const std::string text =
    "VesselCenterline: cancel port " + std::to_string(this->RemoteCancelPort);
  this->SetProgressText(text.c_str());
  this->UpdateProgress(0.0);
}

void vtkVesselTouchCenterlineFilter::ShareRemoteCancelPorts()
{
  vtkMultiProcessController* global = vtkMultiProcessController::GetGlobalController();
  vtouch::ControllerCollectives c(vtouch::DistributedCenterline::controllerFor(
    global->GetLocalProcessId(), global->GetNumberOfProcesses()));
  // Each rank's port (0: none) and host name, as numbers.
  std::vector<double> mine{ static_cast<double>(this->RemoteCancelPort) };
  for (const char ch : vtouch::RemoteCancelListener::hostName())
  {
    mine.push_back(static_cast<double>(static_cast<unsigned char>(ch)));
  }
  const std::vector<std::vector<double>> all = c.allGather(mine);
  if (c.rank() != 0 || !this->RemoteCancel)
  {
    return;
  }
  std::vector<std::pair<std::string, int>> peers;
  for (std::size_t r = 1; r < all.size(); ++r)
  {
    if (all[r].empty() || all[r][0] <= 0.0)
    {
      continue;
    }
    std::string host;
    for (std::size_t i = 1; i < all[r].size(); ++i)
    {
      host.push_back(static_cast<char>(static_cast<unsigned char>(all[r][i])));
    }
    peers.emplace_back(host, static_cast<int>(all[r][0]));
  }
  this->RemoteCancel->forwardTo(std::move(peers));
}

void vtkVesselTouchCenterlineFilter::CloseRemoteCancel()
{
  if (this->RemoteCancel)
  {
    this->RemoteCancel.reset(); // joins its thread, closes the socket
    this->SetProgressText(nullptr);
  }
}

int vtkVesselTouchCenterlineFilter::ExecuteRequest(vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkImageData* input = vtkImageData::GetData(inputVector[0]);
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  if (this->Distributed(requestedPiece(outputVector), requestedPieces(outputVector)))
  {
    this->DistributedTimeline.markDataEntry();
    return this->RequestDistributed(inputVector, output);
  }
  if (output && requestedPiece(outputVector) > 0)
  {
    output->Initialize(); // the first piece codes the whole volume (RequestUpdateExtent)
    return 1;
  }
  int extent[6] = { 0, -1, 0, -1, 0, -1 };
  if (input)
  {
    input->GetExtent(extent);
  }
  if (extent[0] == 0 && extent[2] == 0 && extent[4] == 0)
  {
    return this->ExtractVolume(inputVector, input, output);
  }
  // A volume whose extent does not start at 0 (ParaView's Extract Subset, a reader's VOI): every
  // stage indexes the voxels from the first one, so it gets the same voxels from index 0, and
  // the coder the frame that places them where they are, as a distributed rank's piece does.
  // Before, the positions came out shifted by the extent's start times the spacing.
  const vtouch::PieceInWhole frame = vtouch::DistributedCenterline::pieceInWhole(input);
  return this->ExtractVolume(
    inputVector, vtouch::DistributedCenterline::pieceFromIndexZero(input), output, &frame);
}

void vtkVesselTouchCenterlineFilter::Complain(const std::string& message)
{
  if (!this->QuietErrors)
  {
    vtkErrorMacro(<< message);
  }
}

int vtkVesselTouchCenterlineFilter::ExtractVolume(vtkInformationVector** inputVector,
  vtkImageData* input,
  vtkPolyData* output,
  const vtouch::PieceInWhole* pieceInWhole)
{
  this->DownsampleFactorUsed = 0;
  this->LastRunKey.clear();
  this->LastRunPrecomputed = false;
  this->LastRunCancelled = false;
  if (!input || !output)
  {
    this->Complain("VesselCenterline needs a vtkImageData input.");
    return 1;
  }
  output->Initialize();
  this->ExtractionMessage.clear();
  this->IntensityRangeUsed[0] = this->LowerThreshold;
  this->IntensityRangeUsed[1] = this->UpperThreshold;
  const auto fail = [this, output](const std::string& message)
  {
    output->Initialize();
    this->ExtractionMessage = message;
    vtouch::addRangeFieldData(output->GetFieldData(),
      this->IntensityRangeUsed[0],
      this->IntensityRangeUsed[1],
      this->AutomaticIntensityRange,
      message);
  };
  int dims[3];
  input->GetDimensions(dims);
  if (dims[0] < 2 || dims[1] < 2 || dims[2] < 2)
  {
    std::ostringstream text;
    text << "VesselCenterline needs a 3D volume; the input is " << dims[0] << " x " << dims[1]
         << " x " << dims[2] << ".";
    fail(text.str());
    this->Complain(this->ExtractionMessage);
    return 1;
  }
  vtkDataArray* scalars = this->GetInputArrayToProcess(0, inputVector);
  if (!scalars)
  {
    scalars = input->GetPointData()->GetScalars(); // no array selected: the active scalars
  }
  if (scalars && this->DistributedShadedScalars &&
      this->DistributedShadedScalars->GetNumberOfTuples() == scalars->GetNumberOfTuples())
  {
    scalars = this->DistributedShadedScalars; // the ranks' shading correction of this piece
  }
  if (!scalars)
  {
    fail("The input has no point scalars to threshold.");
    this->Complain(this->ExtractionMessage);
    return 1;
  }
  if (scalars->GetNumberOfComponents() != 1)
  {
    fail("The input scalars have " + std::to_string(scalars->GetNumberOfComponents()) +
         " components; VesselCenterline needs one.");
    this->Complain(this->ExtractionMessage);
    return 1;
  }
  if (this->DownsampleFactor < 0)
  {
    this->Complain("DownsampleFactor must be 0 (automatic) or a factor >= 1, got " +
                   std::to_string(this->DownsampleFactor) + ".");
    return 1;
  }
  this->LastRunKey = this->RunKey(input, scalars);
  if (this->UsePrecomputed(this->LastRunKey, output))
  {
    return 1; // a background run of this input and these parameters computed it
  }
  const auto cancelled = [this, &fail]()
  {
    fail(vtouch::cancelledMessage());
    this->LastRunCancelled = true;
    return 1;
  };
  // Progress: the candidate region (raw path) is the first half, the coder the rest but the
  // pruning's last 5 %; every report is a check point of the cancel flag.
  const double coderBegin = this->AutomaticIntensityRange ? 0.5 : 0.0;
  // The raw-angiogram path: the range, the seed's network, tubes only.
  double lower = this->LowerThreshold, upper = this->UpperThreshold;
  double background = 0.0, backgroundNoise = 0.0; // the range estimator's B and S (automatic)
  double seed[3] = { this->SeedPoint[0], this->SeedPoint[1], this->SeedPoint[2] };
  std::shared_ptr<const vtouch::SparseVesselMask> mask;
  std::vector<std::pair<std::string, double>> candidateSeconds;
  bool codeFromSeed = true;
  // The volume's smooth shading, corrected before the range (issue 16; vtouch::ShadingField):
  // every stage after it (range, region, sections, tips) reads the corrected scalars. A
  // distributed run corrected its piece with the ranks' common field before (RequestDistributed).
  vtouch::ShadingCorrection shading;
  double shadingSeconds = -1.0; // CandidateShadingSeconds (this run's fit and correction)
  if (this->AutomaticIntensityRange && this->CorrectShading && !this->DistributedRegion)
  {
    const double start = vtouch::steadyNow_s();
    shading = vtouch::correctShading(input, scalars, this->UseSeedPoint, this->SeedPoint);
    if (shading.scalars)
    {
      scalars = shading.scalars;
    }
    shadingSeconds = vtouch::steadyNow_s() - start;
  }
  if (this->AutomaticIntensityRange)
  {
    vtouch::CandidateRegionRequest request;
    request.automatic = true;
    request.useSeed = this->UseSeedPoint;
    std::copy(this->SeedPoint, this->SeedPoint + 3, request.seed_World_mm);
    request.progress = [this, coderBegin](double fraction)
    {
      this->UpdateProgress(coderBegin * fraction);
      return !this->CancelRequested();
    };
    vtouch::CandidateRegionOutcome region;
    try
    {
      // Distributed raw modes: the region the ranks computed together (the hook).
      region = this->DistributedRegion ? *this->DistributedRegion
                                       : vtouch::runCandidateRegion(input, scalars, request);
    }
    catch (const vtouch::Cancelled&)
    {
      return cancelled();
    }
    catch (const std::exception& e) // ITK exceptions are std::exceptions too
    {
      fail(std::string("VesselCenterline: ") + e.what());
      this->Complain(this->ExtractionMessage);
      return 1;
    }
    candidateSeconds = region.stageSeconds;
    if (shadingSeconds >= 0.0)
    {
      candidateSeconds.insert(candidateSeconds.begin(), { "shading", shadingSeconds });
    }
    this->IntensityRangeUsed[0] = lower = region.lower;
    this->IntensityRangeUsed[1] = upper = region.upper;
    background = region.background;
    backgroundNoise = region.backgroundNoise;
    if (!region.ok)
    {
      fail(region.message);
      this->Complain(region.message);
      return 1;
    }
    if (!region.binary)
    {
      mask = region.mask;
      // Distributed: only the seed's rank codes from the seed; the others from their own roots.
      codeFromSeed = region.seedIndex[0] >= 0;
      if (this->UseSeedPoint && codeFromSeed)
      {
        // The seed voxel the region grew from (world), for the coder's root.
        double origin[3], spacing[3];
        input->GetOrigin(origin);
        input->GetSpacing(spacing);
        vtkMatrix3x3* m = input->GetDirectionMatrix();
        for (int r = 0; r < 3; ++r)
        {
          seed[r] = origin[r];
          for (int c = 0; c < 3; ++c)
          {
            const double d = m ? m->GetElement(r, c) : (r == c ? 1.0 : 0.0);
            seed[r] += d * static_cast<double>(region.seedIndex[c]) * spacing[c];
          }
        }
      }
    }
  }
  // Distributed with the global SS field (seeded, or the unseeded mask's automatic roots): the
  // coder codes with it instead of propagating from a root of its own.
  vtouch::DistributedGlobalField* global = this->DistributedField;
  const vtouch::CoderSettings s{ lower,
    upper,
    this->UseSeedPoint && codeFromSeed && !global,
    { seed[0], seed[1], seed[2] },
    this->DistributedRegion
      ? vtouch::DistributedRawRegion::componentSizeVoxels(
          this->MinimumComponentSize, this->GetGhostMarginVoxels(input->GetSpacing()))
      : this->MinimumComponentSize,
    this->MinimumBranchLength,
    this->DeferPathSmoothing ? vtouch::kPositionsKeptWindow_mm : this->SmoothingWindow,
    this->UseVesselness,
    this->VesselnessSigmaMinimum,
    this->VesselnessSigmaMaximum,
    this->VesselnessNumberOfScales,
    this->VesselnessThreshold,
    this->DownsampleFactor,
    mask,
    [this, coderBegin](double fraction)
    {
      this->UpdateProgress(coderBegin + (0.95 - coderBegin) * fraction);
      return !this->CancelRequested();
    },
    global ? [global](vtouch::SparseVesselMask& m) { return global->code(m); }
           : std::function<std::vector<float>(vtouch::SparseVesselMask&)>(),
    global ? [global](const vtouch::skeleton::SkeletonTracer& t) { return global->faceTips(t); }
           : std::function<std::vector<std::int64_t>(const vtouch::skeleton::SkeletonTracer&)>(),
    // A piece's positions in the whole volume's frame, the single run's (PieceInWhole).
    pieceInWhole ? std::optional<vtouch::PieceInWhole>(*pieceInWhole) : std::nullopt };
  try
  {
    vtouch::CoderRun coded = vtouch::skeletonizeVolume(input, scalars, s);
    vtouch::QSkeleton& skeleton = coded.skeleton;
    const int factorUsed = coded.factorUsed;
    const std::vector<std::pair<std::string, double>>& coderSeconds = coded.stageSeconds;
    if (this->CancelRequested())
    {
      return cancelled();
    }
    if (mask && !this->DeferRawRefinement)
    {
      // Raw-angiogram path only (issue 16): stretches where clutter touches a vessel are
      // re-traced on the tube's own sections or cut, then paths whose cross-sections are not
      // tube-like go; binary masks and the override are untouched. (Distributed with the global
      // field the first rank runs it on the whole stitched paths instead, RequestDistributed.)
      vtouch::SectionGeometry geometry;
      input->GetOrigin(geometry.origin_mm.data());
      input->GetSpacing(geometry.spacing_mm.data());
      if (vtkMatrix3x3* m = input->GetDirectionMatrix())
      {
        for (int r = 0; r < 3; ++r)
        {
          for (int c = 0; c < 3; ++c)
          {
            geometry.direction[static_cast<std::size_t>(3 * r + c)] = m->GetElement(r, c);
          }
        }
      }
      // Sections of the volume in the range (not of the candidate region: the neck cut keeps
      // a plate's rims, which are bars of their own; the plate around them shows in the image).
      const vtouch::SectionForeground inRange =
        vtouch::rangeForeground(scalars, { dims[0], dims[1], dims[2] }, lower, upper);
      // Free ends turned onto one dim noise voxel (the intensities, the range's B and S).
      const vtouch::TurnedDimTipTrimmer::Evidence tips{ vtouch::volumeIntensity(
                                                          scalars, { dims[0], dims[1], dims[2] }),
        lower,
        background,
        backgroundNoise };
      const vtouch::RawSkeletonRefinement refined = vtouch::RawSkeletonRefinement::apply(
        skeleton, inRange, geometry, this->SmoothingWindow, &tips);
      candidateSeconds.emplace_back("tubeTrack", refined.trackSeconds);
      candidateSeconds.emplace_back("tubePrune", refined.pruneSeconds);
      vtkNew<vtkIntArray> retraced;
      retraced->SetName("ContactStretchesRetraced");
      retraced->InsertNextValue(refined.tracked.stretchesTracked);
      output->GetFieldData()->AddArray(retraced);
      vtkNew<vtkIntArray> cut;
      cut->SetName("ClutterStretchesCut");
      cut->InsertNextValue(refined.tracked.stretchesCut);
      output->GetFieldData()->AddArray(cut);
      vtkNew<vtkIntArray> removed;
      removed->SetName("NonTubularPathsRemoved");
      removed->InsertNextValue(refined.pruned.pathsRemoved);
      output->GetFieldData()->AddArray(removed);
    }
    if (!this->DeferBranchEntries)
    {
      this->PlaceBranchEntries(skeleton);
    }
    vtouch::qSkeletonToPolyData(skeleton, output);
    // Which scale the default (automatic) DownsampleFactor chose: 1 = full resolution.
    vtkNew<vtkIntArray> used;
    used->SetName("DownsampleFactorUsed");
    used->InsertNextValue(factorUsed);
    output->GetFieldData()->AddArray(used);
    this->DownsampleFactorUsed = factorUsed;
    vtouch::addRangeFieldData(
      output->GetFieldData(), lower, upper, this->AutomaticIntensityRange, std::string());
    if (this->AutomaticIntensityRange)
    {
      vtouch::addShadingFieldData(output->GetFieldData(), shading);
    }
    vtouch::addStageSeconds(output->GetFieldData(), candidateSeconds);
    vtouch::addStageSeconds(output->GetFieldData(), coderSeconds, "Coder");
    this->UpdateProgress(1.0);
  }
  catch (const itk::ProcessAborted&)
  {
    return cancelled(); // the cancel flag or AbortExecute stopped the coder
  }
  catch (const vtouch::Cancelled&)
  {
    // The ranks agreed to cancel in an exchange of the coder's hooks (the global field's
    // rounds, CancellableCollectives): this rank goes on to the run's next cancel point like a
    // rank that stopped for its own cancel, so no rank waits for it (issue 19 item 1).
    return cancelled();
  }
  catch (const itk::ExceptionObject& e)
  {
    fail(std::string("VesselCenterline: ") + e.GetDescription());
    this->Complain(this->ExtractionMessage);
  }
  catch (const std::bad_alloc&)
  {
    fail("VesselCenterline: not enough memory for this volume.");
    this->Complain(this->ExtractionMessage);
  }
  return 1;
}

bool vtkVesselTouchCenterlineFilter::DistributesExactly() const
{
  // The modes RequestDistributed codes with the global SS field (globalSeedCode, globalRootCode):
  // a seed, a thresholded / binary mask without one, or the raw mode without a seed (its range
  // and region computed across the ranks, h19x), at full resolution. Vesselness is left out: its
  // Hessian on a piece is the whole volume's only as far as the margin reaches.
  return this->DownsampleFactor <= 1 && !this->UseVesselness;
}

bool vtkVesselTouchCenterlineFilter::Distributed(int piece, int pieces) const
{
  const bool wanted =
    this->DistributedExtraction == DistributedExtractionOn ||
    (this->DistributedExtraction == DistributedExtractionAutomatic && this->DistributesExactly());
  return wanted && vtouch::DistributedCenterline::controllerFor(piece, pieces) != nullptr;
}

int vtkVesselTouchCenterlineFilter::GetGhostMarginVoxels(const double spacing[3]) const
{
  const double largestSpacing = std::max({ spacing[0], spacing[1], spacing[2] });
  vtouch::GhostMarginRule rule;
  // Automatic: 10 voxels, the thickest vessel the project's phantoms and CTA volumes hold at
  // their resolution (project rule; set LargestVesselRadius for thicker ones).
  rule.largestRadius_mm =
    this->LargestVesselRadius > 0.0 ? this->LargestVesselRadius : 10.0 * largestSpacing;
  rule.minimumBranchLength = this->MinimumBranchLength;
  rule.useVesselness = this->UseVesselness;
  rule.vesselnessSigmaMaximum_mm = this->VesselnessSigmaMaximum;
  const int margin = rule.voxels({ spacing[0], spacing[1], spacing[2] });
  // The raw seeded mode: the seed's rank estimates the range on the seed's neighbourhood.
  return this->AutomaticIntensityRange && this->UseSeedPoint
           ? std::max(margin, vtouch::DistributedRawRegion::minimumMarginVoxels())
           : margin;
}

int vtkVesselTouchCenterlineFilter::RequestDistributed(vtkInformationVector** inputVector,
  vtkPolyData* output)
{
  vtouch::DistributedRequest::Hooks hooks;
  // Progress of a distributed run (h18q): the piece's run (its own 0-100 %) is the first
  // kPieceProgressShare, the first rank's stitch the rest up to 95 %, so the reports never go
  // back when the stitch starts (VTK's shift and scale, around the piece's run only).
  hooks.extractPiece = [this, inputVector](vtkImageData* piece,
                         const vtouch::PieceInWhole& frame,
                         vtkPolyData* pieceOutput)
  {
    struct ProgressScope
    {
      vtkVesselTouchCenterlineFilter* filter;
      ~ProgressScope() { this->filter->SetProgressShiftScale(0.0, 1.0); }
    } scope{ this };
    this->SetProgressShiftScale(0.0, kPieceProgressShare);
    this->QuietErrors = true;
    this->ExtractVolume(inputVector, piece, pieceOutput, &frame);
    this->QuietErrors = false;
  };
  hooks.lastRun = [this](double range[2], std::string& message)
  {
    range[0] = this->IntensityRangeUsed[0];
    range[1] = this->IntensityRangeUsed[1];
    message = this->ExtractionMessage;
  };
  hooks.fill = vtouch::qSkeletonToPolyData;
  hooks.ghostMarginVoxels = [this](const double spacing[3])
  { return this->GetGhostMarginVoxels(spacing); };
  hooks.automaticIntensityRange = this->AutomaticIntensityRange;
  hooks.timeline = this->DistributedTimeline.take();
  // A cancel (the first rank's remote cancel, AbortExecute) at every exchange of the ranks,
  // taken by every rank at the same one (vtouch::CancellableCollectives, issue 19 item 1).
  // On the first rank with a cancel socket, each exchange also reports the progress again: the
  // ranks' rounds report none of their own, and ParaView sends the first rank's progress (with
  // the port in its text) at most once a second and only when reported, so without it the
  // client would learn the port only when the coder first reports (seconds to minutes later).
  const vtouch::CancellableCollectives::CancelCheck cancelRequested = [this]
  {
    if (this->RemoteCancel)
    {
      // The same value again (UpdateProgress applies the shift and scale of the piece's run).
      this->UpdateProgress(
        (this->GetProgress() - this->GetProgressShift()) / this->GetProgressScale());
    }
    return this->CancelRequested();
  };
  hooks.cancelRequested = cancelRequested;
  // The first rank's stitch (h18q): the 128^3 raw phantom's long runs on 2 ranks spent 21-74 s
  // of their 26-85 s there, reporting nothing before, so the client (Python's RemoteCancel, the
  // panel's Cancel) heard nothing until the run's end. Its check points read the cancel flag
  // and report through a throttle (a few reports a second, never going back), from this thread.
  vtouch::ProgressThrottle stitchReports([this](double fraction)
    { this->UpdateProgress(kPieceProgressShare + (0.95 - kPieceProgressShare) * fraction); });
  hooks.stitchProgress = [this, &stitchReports](double fraction)
  {
    if (this->RemoteCancel && stitchReports.highest() == 0.0 && fraction == 0.0)
    {
      // The stage in the text ParaView carries to the client (its progress bar shows it; the
      // port stays first: RemoteCancel and the panel find it anywhere in the text).
      const std::string text =
        "VesselCenterline: cancel port " + std::to_string(this->RemoteCancelPort) + " (stitching)";
      this->SetProgressText(text.c_str());
    }
    stitchReports.offer(fraction, vtouch::steadyNow_s());
    return !this->CancelRequested();
  };
  if (!this->RemoteCancelToken.empty())
  {
    this->ShareRemoteCancelPorts(); // collective: the token is on every rank's filter
  }
  // The global SS field (issue 19 item 2): every rank codes its piece with the single run's SS
  // field, computed across the ranks (vtouch::DistributedGlobalField, the coder's hook), instead
  // of from roots of its own: from the seed in the seeded modes, from the single run's automatic
  // roots without a seed (a thresholded or binary mask, or the raw mode: its region is computed
  // across the ranks and each rank takes its held voxels' owners' decisions, so every rank's
  // mask is its piece of one whole mask, DistributedRootChoice's precondition). At full
  // resolution (project rule: a coarse block grid starts at each piece's first voxel, not on one
  // grid of the whole volume): an explicit DownsampleFactor > 1 keeps each rank's own roots.
  const bool fullResolution = this->DownsampleFactor <= 1;
  const bool globalSeedCode = this->UseSeedPoint && fullResolution;
  const bool globalRootCode = !this->UseSeedPoint && fullResolution;
  std::unique_ptr<vtouch::DistributedGlobalField> field;
  const auto controller = []
  {
    return vtouch::DistributedCenterline::controllerFor(
      vtkMultiProcessController::GetGlobalController()->GetLocalProcessId(),
      vtkMultiProcessController::GetGlobalController()->GetNumberOfProcesses());
  };
  // The automatic roots' field (globalRootCode), collective. The coder's own settings: its
  // MinimumComponentSize in input voxels (the field is coded at full resolution), and the
  // cluster width it leaves at its default (0: the largest spacing; VoxelCodingSkeletonFilter's
  // ClusterWidth, never set here).
  const auto rootField = [&](vtkImageData* input, const vtouch::VoxelExtent6& whole)
  {
    vtouch::DistributedRootChoice::Parameters parameters;
    parameters.minimumComponentSize =
      static_cast<std::uint64_t>(std::max(1, this->MinimumComponentSize));
    parameters.clusterWidth_mm = 0.0;
    field = vtouch::DistributedGlobalField::automaticRoot(
      controller(), input, whole, parameters, cancelRequested);
    this->DistributedField = field.get();
  };
  // The raw modes (automatic range): the range and the region with the other ranks (collective),
  // then the piece's own run codes that region (the hook in ExtractVolume). Seeded without the
  // global SS code, the seed's rank adds the parts of the network that reach the seed only
  // outside its piece. Without a seed the range is the whole volume's (fromVolume's sample
  // across the ranks) and the region every kept voxel in it (h19x).
  vtouch::CandidateRegionOutcome region, rest;
  vtouch::DistributedRawRegion::Report regionReport;
  vtouch::ShadingCorrection shading;
  const bool raw = this->AutomaticIntensityRange;
  if (raw)
  {
    hooks.beforePiece = [&](vtkImageData* input, const vtouch::VoxelExtent6& whole)
    {
      vtouch::CandidateRegionRequest request;
      request.useSeed = this->UseSeedPoint;
      std::copy(this->SeedPoint, this->SeedPoint + 3, request.seed_World_mm);
      vtkDataArray* scalars = input ? this->GetInputArrayToProcess(0, inputVector) : nullptr;
      scalars = scalars || !input ? scalars : input->GetPointData()->GetScalars();
      if (this->CorrectShading)
      {
        // The single run's shading correction, its field fitted to the ranks' common sample
        // (collective); every later stage of this rank reads the corrected piece.
        shading = vtouch::DistributedShading::run(
          controller(), input, scalars, whole, this->UseSeedPoint, this->SeedPoint);
        this->DistributedShadedScalars = shading.scalars;
        scalars = shading.scalars ? shading.scalars.Get() : scalars;
      }
      region = vtouch::DistributedRawRegion::run(
        controller(), input, scalars, whole, request, regionReport, cancelRequested);
      this->DistributedRegion = &region;
      if (!this->UseSeedPoint)
      {
        if (globalRootCode)
        {
          rootField(input, whole); // the single run's automatic roots on the common region
        }
        return;
      }
      if (!globalSeedCode)
      {
        rest = vtouch::DistributedRawRegion::splitSeedComponent(region);
        return;
      }
      // The whole region is coded with the global field (no split): the region's seed voxel,
      // known on the seed's rank; the region is exact on the evaluable box only.
      std::array<std::int64_t, 3> seed_Whole{ -1, -1, -1 };
      const bool here = input && region.ok && region.seedIndex[0] >= 0;
      if (here)
      {
        int e[6];
        input->GetExtent(e);
        for (std::size_t a = 0; a < 3; ++a)
        {
          seed_Whole[a] = region.seedIndex[a] + e[2 * a] - whole[2 * a];
        }
      }
      field = vtouch::DistributedGlobalField::seeded(
        controller(), input, whole, here, seed_Whole, true, cancelRequested);
      this->DistributedField = field.get();
    };
  }
  else if (globalSeedCode)
  {
    hooks.beforePiece = [&](vtkImageData* input, const vtouch::VoxelExtent6& whole)
    {
      const std::array<std::int64_t, 3> seed_Whole =
        input ? vtouch::DistributedGlobalField::seedVoxel_Whole(input, this->SeedPoint, whole)
              : std::array<std::int64_t, 3>{ -1, -1, -1 };
      field = vtouch::DistributedGlobalField::seeded(
        controller(), input, whole, input != nullptr, seed_Whole, false, cancelRequested);
      this->DistributedField = field.get();
    };
  }
  else if (globalRootCode)
  {
    hooks.beforePiece = rootField;
  }
  if (globalSeedCode || globalRootCode)
  {
    hooks.afterExtract = [&]
    {
      this->DistributedField = nullptr;
      if (field)
      {
        field->finish(); // collective: a rank whose run stopped before its coder joins here
      }
    };
  }
  if (raw || globalSeedCode || globalRootCode)
  {
    hooks.afterPiece = [&](vtkImageData* input, vtkPolyData* own, vtouch::QSkeleton& skeleton)
    {
      this->DistributedRegion = nullptr;
      if (raw)
      {
        vtouch::DistributedRawRegion::addReport(own->GetFieldData(), regionReport);
      }
      if (field)
      {
        field->addReport(own->GetFieldData());
      }
      if (rest.ok)
      {
        this->AddRestOfRegion(inputVector, input, rest, skeleton);
      }
    };
  }
  // The whole paths smoothed on the first rank (issue 19 item 2): the smoothing windows scale
  // with a path's median radius, and a rank sees only its part of a path that crosses pieces
  // (the 256^3 scaling tree: 4 points 0.16 voxel off at a bend with each rank's own windows).
  // In the modes coded with the global field, whose ranks' centres are the single run's.
  this->DeferPathSmoothing = globalSeedCode || globalRootCode;
  // The raw modes coded with the global field: the raw path's refinement (tube tracker, tube
  // likeness pruning, turned dim tips) then runs once on the whole stitched, smoothed skeleton
  // on the first rank, as in the single run, the volume read from pages its owners send (h19r:
  // each rank's run on its own smoothed part of a path made the whole-path decisions and the
  // re-traced stretches' windows differ). An explicit DownsampleFactor > 1 keeps each rank's
  // own roots, smoothing and refinement (a departure, Docs/CLIENT-SERVER.md).
  this->DeferRawRefinement = raw && this->DeferPathSmoothing;
  struct DeferReset
  {
    vtkVesselTouchCenterlineFilter* filter;
    ~DeferReset()
    {
      this->filter->DeferPathSmoothing = this->filter->DeferRawRefinement = false;
      this->filter->DistributedShadedScalars = nullptr;
      this->filter->DeferBranchEntries = false;
    }
  } deferReset{ this };
  if (this->DeferPathSmoothing)
  {
    hooks.afterStitch = [this](vtouch::QSkeleton& stitched, const vtouch::IndexFrame& frame)
    {
      vtouch::smoothSkeletonPaths(stitched,
        *std::max_element(frame.spacing_mm.begin(), frame.spacing_mm.end()),
        this->SmoothingWindow);
    };
  }
  if (this->DeferRawRefinement)
  {
    hooks.afterStitchCollective = [&](vtkImageData* input,
                                    const vtouch::VoxelExtent6& whole,
                                    vtouch::QSkeleton* stitched,
                                    vtkFieldData* report)
    {
      // The single run's arguments (ExtractVolume): the SmoothingWindow, and the range with its
      // B and S, which the ranks computed together (the same numbers on every rank, checked).
      vtouch::DistributedRawRefinement::Settings settings;
      settings.smoothingWindow_mm = this->SmoothingWindow;
      settings.lower = region.lower;
      settings.upper = region.upper;
      settings.background = region.background;
      settings.backgroundNoise = region.backgroundNoise;
      vtkDataArray* scalars = input ? this->GetInputArrayToProcess(0, inputVector) : nullptr;
      scalars = scalars || !input ? scalars : input->GetPointData()->GetScalars();
      scalars = this->DistributedShadedScalars ? this->DistributedShadedScalars.Get() : scalars;
      // A two-valued volume without a seed is a mask the single run does not refine.
      return vtouch::DistributedWholePathRefinement::run(controller(),
        input,
        scalars,
        whole,
        region.binary ? nullptr : stitched,
        settings,
        report,
        cancelRequested);
    };
  }
  // The single run's last step on the whole network: each branch's entry into its parent.
  this->DeferBranchEntries = true;
  hooks.beforeFill = [this](vtouch::QSkeleton& stitched) { this->PlaceBranchEntries(stitched); };
  vtouch::DistributedRequest::Outcome outcome;
  try
  {
    outcome = vtouch::DistributedRequest::run(inputVector, output, hooks);
  }
  catch (const vtouch::Cancelled&)
  {
    // Every rank threw at the same exchange (CancellableCollectives): an empty output and
    // "Cancelled." on every rank, as a cancelled single run.
    this->DistributedRegion = nullptr;
    this->DistributedField = nullptr;
    this->QuietErrors = false; // a piece's run may have been left by the exception
    output->Initialize();
    this->ExtractionMessage = vtouch::cancelledMessage();
    this->LastRunCancelled = true;
    vtouch::addRangeFieldData(output->GetFieldData(),
      this->IntensityRangeUsed[0],
      this->IntensityRangeUsed[1],
      this->AutomaticIntensityRange,
      this->ExtractionMessage);
    return 1;
  }
  this->DistributedRegion = nullptr;
  this->DistributedField = nullptr;
  this->ExtractionMessage = outcome.message;
  if (!outcome.firstRank)
  {
    return 1; // not the first rank: an empty piece of the output
  }
  if (raw && this->CorrectShading && outcome.message.empty())
  {
    vtouch::addShadingFieldData(output->GetFieldData(), shading); // the single run's arrays
  }
  for (const std::string& warning : outcome.warnings)
  {
    vtkWarningMacro(<< warning);
  }
  if (!outcome.message.empty())
  {
    vtkErrorMacro(<< outcome.message);
  }
  return 1;
}

void vtkVesselTouchCenterlineFilter::AddRestOfRegion(vtkInformationVector** inputVector,
  vtkImageData* input,
  const vtouch::CandidateRegionOutcome& rest,
  vtouch::QSkeleton& skeleton)
{
  const std::string message = this->ExtractionMessage;
  vtkNew<vtkPolyData> other;
  this->QuietErrors = true;
  this->DistributedRegion = &rest;
  const vtouch::PieceInWhole frame = vtouch::DistributedCenterline::pieceInWhole(input);
  this->ExtractVolume(
    inputVector, vtouch::DistributedCenterline::pieceFromIndexZero(input), other, &frame);
  this->DistributedRegion = nullptr;
  this->QuietErrors = false;
  this->ExtractionMessage = message; // the seed's component's run speaks for the piece
  vtouch::QSkeleton more;
  std::string error;
  if (other->GetNumberOfLines() > 0 && vtouch::PolyDataToQSkeleton().convert(other, more, error))
  {
    skeleton = vtouch::SeedComponentSplit::appended(skeleton, more);
  }
}

void vtkVesselTouchCenterlineFilter::PlaceBranchEntries(vtouch::QSkeleton& skeleton) const
{
  // Not when the positions are kept as coded (a negative SmoothingWindow).
  if (this->SmoothingWindow >= 0.0)
  {
    vtouch::placeBranchEntries(skeleton);
  }
}

bool vtkVesselTouchCenterlineFilter::CancelRequested()
{
  return vtouch::cancelRequested(this->CancelFlag, this) ||
         (this->RemoteCancel && this->RemoteCancel->cancelled().load());
}

std::string vtkVesselTouchCenterlineFilter::RunKey(vtkImageData* input, vtkDataArray* scalars) const
{
  // What the output depends on: the voxels (the array itself and its modification time: a
  // shallow copy of the input shares both, a new or modified array changes them), the geometry
  // and every parameter, printed exactly.
  std::ostringstream key;
  key.precision(17);
  key << "scalars " << static_cast<const void*>(scalars) << " " << scalars->GetMTime() << " type "
      << scalars->GetDataType() << " n " << scalars->GetNumberOfTuples();
  int dims[3];
  input->GetDimensions(dims);
  const double* origin = input->GetOrigin();
  const double* spacing = input->GetSpacing();
  key << " dims " << dims[0] << " " << dims[1] << " " << dims[2] << " origin " << origin[0] << " "
      << origin[1] << " " << origin[2] << " spacing " << spacing[0] << " " << spacing[1] << " "
      << spacing[2] << " direction";
  vtkMatrix3x3* m = input->GetDirectionMatrix();
  for (int e = 0; e < 9; ++e)
  {
    key << " " << (m ? m->GetData()[e] : (e % 4 == 0 ? 1.0 : 0.0));
  }
  key << " automatic " << this->AutomaticIntensityRange << " shading " << this->CorrectShading
      << " range " << this->LowerThreshold << " " << this->UpperThreshold << " seed "
      << this->UseSeedPoint << " " << this->SeedPoint[0] << " " << this->SeedPoint[1] << " "
      << this->SeedPoint[2] << " component " << this->MinimumComponentSize << " branch "
      << this->MinimumBranchLength << " smoothing " << this->SmoothingWindow << " downsample "
      << this->DownsampleFactor << " vesselness " << this->UseVesselness << " "
      << this->VesselnessSigmaMinimum << " " << this->VesselnessSigmaMaximum << " "
      << this->VesselnessNumberOfScales << " " << this->VesselnessThreshold << " largest radius "
      << this->LargestVesselRadius << " distributed " << this->DistributedExtraction;
  return key.str();
}

bool vtkVesselTouchCenterlineFilter::UsePrecomputed(const std::string& key, vtkPolyData* output)
{
  // Consumed either way: a mismatch means the input or the parameters changed since.
  const vtkSmartPointer<vtkPolyData> precomputed = this->PrecomputedOutput;
  const std::string precomputedKey = this->PrecomputedKey;
  this->PrecomputedOutput = nullptr;
  this->PrecomputedKey.clear();
  if (!precomputed || key != precomputedKey)
  {
    return false;
  }
  this->RestoreOutput(precomputed, output);
  this->LastRunPrecomputed = true;
  this->UpdateProgress(1.0);
  return true;
}

void vtkVesselTouchCenterlineFilter::RestoreOutput(vtkPolyData* from, vtkPolyData* output)
{
  output->ShallowCopy(from);
  // The members the run would have set, from the field data it wrote.
  vtkFieldData* fd = output->GetFieldData();
  if (vtkDataArray* used = fd->GetArray("IntensityRangeUsed"))
  {
    this->IntensityRangeUsed[0] = used->GetComponent(0, 0);
    this->IntensityRangeUsed[1] = used->GetComponent(used->GetNumberOfTuples() > 1 ? 1 : 0, 0);
  }
  if (auto* message = vtkStringArray::SafeDownCast(fd->GetAbstractArray("ExtractionMessage")))
  {
    this->ExtractionMessage = message->GetNumberOfValues() > 0 ? message->GetValue(0) : "";
  }
  if (vtkDataArray* factor = fd->GetArray("DownsampleFactorUsed"))
  {
    this->DownsampleFactorUsed = static_cast<int>(factor->GetComponent(0, 0));
  }
}

void vtkVesselTouchCenterlineFilter::SetPrecomputedOutput(vtkPolyData* output, const char* runKey)
{
  this->PrecomputedOutput = output;
  this->PrecomputedKey = output && runKey ? runKey : "";
  this->Modified(); // the pipeline runs this filter again, which returns it
}

void vtkVesselTouchCenterlineFilter::CopyParameters(vtkVesselTouchCenterlineFilter* other)
{
  if (!other || other == this)
  {
    return;
  }
  this->AutomaticIntensityRange = other->AutomaticIntensityRange;
  this->CorrectShading = other->CorrectShading;
  this->LowerThreshold = other->LowerThreshold;
  this->UpperThreshold = other->UpperThreshold;
  std::copy(other->SeedPoint, other->SeedPoint + 3, this->SeedPoint);
  this->UseSeedPoint = other->UseSeedPoint;
  this->MinimumComponentSize = other->MinimumComponentSize;
  this->MinimumBranchLength = other->MinimumBranchLength;
  this->SmoothingWindow = other->SmoothingWindow;
  this->DownsampleFactor = other->DownsampleFactor;
  this->UseVesselness = other->UseVesselness;
  this->VesselnessSigmaMinimum = other->VesselnessSigmaMinimum;
  this->VesselnessSigmaMaximum = other->VesselnessSigmaMaximum;
  this->VesselnessNumberOfScales = other->VesselnessNumberOfScales;
  this->VesselnessThreshold = other->VesselnessThreshold;
  this->LargestVesselRadius = other->LargestVesselRadius;
  this->DistributedExtraction = other->DistributedExtraction;
  if (vtkInformation* array = other->GetInputArrayInformation(0))
  {
    this->GetInputArrayInformation(0)->Copy(array);
  }
  this->Modified();
}

void vtkVesselTouchCenterlineFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "AutomaticIntensityRange: " << this->AutomaticIntensityRange << "\n";
  os << indent << "CorrectShading: " << this->CorrectShading << "\n";
  os << indent << "LowerThreshold: " << this->LowerThreshold << "\n";
  os << indent << "UpperThreshold: " << this->UpperThreshold << "\n";
  os << indent << "UseSeedPoint: " << this->UseSeedPoint << "\n";
  os << indent << "SeedPoint: " << this->SeedPoint[0] << " " << this->SeedPoint[1] << " "
     << this->SeedPoint[2] << "\n";
  os << indent << "MinimumComponentSize: " << this->MinimumComponentSize << "\n";
  os << indent << "MinimumBranchLength: " << this->MinimumBranchLength << "\n";
  os << indent << "SmoothingWindow: " << this->SmoothingWindow << "\n";
  os << indent << "DownsampleFactor: " << this->DownsampleFactor << "\n";
  os << indent << "UseVesselness: " << this->UseVesselness << "\n";
  os << indent << "LargestVesselRadius: " << this->LargestVesselRadius << "\n";
  os << indent << "DistributedExtraction: " << this->DistributedExtraction << "\n";
}

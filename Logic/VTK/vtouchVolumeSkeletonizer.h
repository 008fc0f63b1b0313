// The voxel coder (the ITK VoxelCodingSkeletonFilter, Yi & Hayward section 3.1 / Zhou & Toga's
// voxel coding) run on a vtkImageData's scalars for VesselCenterline: the ITK image wraps the VTK
// scalars without a copy (float, unsigned char, short, unsigned short; other types through one
// float copy of the volume).
#pragma once

#include "vtouchPieceInWhole.h"
#include "vtouchProgress.h"
#include "vtouchQSkeleton.h"

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

class vtkDataArray;
class vtkImageData;

namespace vtouch
{
class SparseVesselMask;
namespace skeleton
{
class SkeletonTracer;
} // namespace skeleton

/// What VesselCenterline passes to the coder: its properties, resolved for this run.
struct CoderSettings
{
  double lower, upper;
  bool useSeed;
  double seed[3];
  int minimumComponentSize;
  double minimumBranchLength, smoothing;
  bool useVesselness;
  double sigmaMin, sigmaMax;
  int scales;
  double vesselnessThreshold;
  int downsampleFactor;
  /// The candidate region to code (raw-angiogram path) or null (threshold the input).
  std::shared_ptr<const SparseVesselMask> mask;
  /// The coder's fraction done; returns false to abort it.
  ProgressCallback progress;
  /// The distributed seeded modes' global SS code (VoxelCodingSkeletonFilter::SetGlobalSeedCode),
  /// or empty (the single run).
  std::function<std::vector<float>(SparseVesselMask&)> globalSeedCode;
  /// With it, the face tips' single-run answers (VoxelCodingSkeletonFilter::SetGlobalFaceTips),
  /// or empty.
  std::function<std::vector<std::int64_t>(const skeleton::SkeletonTracer&)> globalFaceTips;
  /// A distributed run's piece: where it lies in the whole volume (the coder then computes its
  /// positions in the whole volume's frame, VoxelCodingSkeletonFilter::SetPieceInWhole), or
  /// empty (the single run).
  std::optional<PieceInWhole> pieceInWhole;
};

/// What one run of the coder gives.
struct CoderRun
{
  QSkeleton skeleton;
  /// The downsampling factor the coder used (1 = full resolution).
  int factorUsed = 0;
  /// The filter's and the coder's stage times (mask, scale, the coder's stages, geometry).
  std::vector<std::pair<std::string, double>> stageSeconds;
};

/// Runs the coder on `scalars` (the point scalars of `image`, its geometry: origin, spacing,
/// direction). Throws itk::ExceptionObject (itk::ProcessAborted when `s.progress` aborts it).
CoderRun skeletonizeVolume(vtkImageData* image, vtkDataArray* scalars, const CoderSettings& s);
} // namespace vtouch

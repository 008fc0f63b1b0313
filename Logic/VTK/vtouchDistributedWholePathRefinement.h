// VesselCenterline's raw modes on a parallel pvserver, after the stitch (issue 19 item 2, h19r):
// the raw path's refinement (RawSkeletonRefinement) once on the whole stitched skeleton on the
// first rank, the volume read from pages its owners send (vtouch::DistributedRawRefinement over
// vtkMultiProcessController), and its report in the output's field data. Not a wrapped class:
// the filter's private helper (DistributedRequest::Hooks::afterStitchCollective).
#pragma once

#include "vtouchCancellableCollectives.h"
#include "vtouchDistributedCenterline.h" // for VoxelExtent6
#include "vtouchDistributedRawRefinement.h"

#include <string>

class vtkDataArray;
class vtkFieldData;
class vtkImageData;
class vtkMultiProcessController;

namespace vtouch
{

class DistributedWholePathRefinement
{
public:
  /// Collective: every rank calls it once per run, with or without an input. `piece`: the
  /// rank's input (its extent of the whole volume `whole`) and `scalars` its voxels (null: the
  /// rank holds no piece); `stitched`: the first rank's stitched skeleton (null elsewhere, or
  /// when there is nothing to refine), refined in place; `settings`: this rank's refinement
  /// arguments (the first rank's are used; every rank's range is compared with them).
  /// `report` (first rank): DistributedRefinement* arrays and the refinement's own
  /// (ContactStretchesRetraced, ClutterStretchesCut, NonTubularPathsRemoved). Returns an error
  /// ("" when none; the first rank's counts).
  static std::string run(vtkMultiProcessController* controller,
    vtkImageData* piece,
    vtkDataArray* scalars,
    const VoxelExtent6& whole,
    QSkeleton* stitched,
    const DistributedRawRefinement::Settings& settings,
    vtkFieldData* report,
    const CancellableCollectives::CancelCheck& cancelRequested);
};

} // namespace vtouch

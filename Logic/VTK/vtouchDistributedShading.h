// The raw modes' shading correction on a parallel pvserver (issue 16 item 1, issue 19 item 2):
// the single run's vtouch::ShadingField on every rank, so that each rank corrects its held piece
// as the single run corrects the whole volume. Not a wrapped class: the filter's private helper
// (vtkVesselTouchCenterlineFilter::RequestDistributed's raw hook).
//  - the sample: each rank sends the voxels of the single run's lattice (every
//    IntensityRangeEstimator::sampleStride-th voxel of the whole volume, in its linear order) that
//    its held piece holds; the ranks' pieces cover the volume, so the union (a voxel two pieces
//    hold counted once) is the single run's sample, and ShadingField::fit, which sorts it, gives
//    the single run's field on every rank;
//  - the reference: the seed's voxel of the whole volume, the same on every rank.
#pragma once

#include "vtouchPieceOwnership.h"
#include "vtouchShadingCorrection.h"

class vtkMultiProcessController;

namespace vtouch
{

class DistributedShading
{
public:
  /// Collective: every rank calls it, with or without an input. `input` is the rank's held piece
  /// (its extent in the whole volume's index space), `scalars` its array (one component), `whole`
  /// the whole extent. The result's scalars are the corrected piece (null when the field is not
  /// active, or on a rank without an input).
  static ShadingCorrection run(vtkMultiProcessController* controller,
    vtkImageData* input,
    vtkDataArray* scalars,
    const VoxelExtent6& whole,
    bool useSeed,
    const double seed_World_mm[3]);
};

} // namespace vtouch

// VesselCenterline on a parallel pvserver coded with the global SS field (issue 19 item 2): every
// rank codes its piece with the single run's SS field instead of from roots of its own. One class
// owns what both ways share (the ranks' collectives over vtkMultiProcessController, the layout,
// joining exactly once per run, the coder's hook, the report); the field comes either
//  - from the seed (the seeded modes: vtouch::SeededDistributedCoding), or
//  - from the single run's automatic roots (the unseeded thresholded or binary mask:
//    vtouch::AutomaticRootDistributedCoding over vtouch::DistributedRootChoice).
// Not a wrapped class: the filter's private helper (RequestDistributed builds it, ExtractVolume
// hands it to the coder, DistributedRequest::Hooks::afterExtract finishes it).
#pragma once

#include "vtouchDistributedCenterline.h" // for VoxelExtent6
#include "vtouchDistributedFaceTips.h"
#include "vtouchDistributedRootChoice.h"
#include "vtouchPieceLayout.h"
#include "vtouchCancellableCollectives.h"
#include "vtouchRankCollectives.h"
#include "vtouchSparseVesselMask.h"

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

class vtkFieldData;
class vtkImageData;
class vtkMultiProcessController;

namespace vtouch
{

class DistributedGlobalField
{
public:
  /// One way to compute the field (the seed's or the automatic roots'), on this rank.
  class Source
  {
  public:
    virtual ~Source() = default;
    /// Collective, once: the field on `mask` (SparseVesselMask::rank order), mm.
    virtual std::vector<float> code(SparseVesselMask& mask) = 0;
    /// Collective, once: takes part without a mask (the run stopped before its coder).
    virtual void join() = 0;
    virtual bool joined() const = 0;
    /// Its outputs as field arrays.
    virtual void addReport(vtkFieldData* fd) const = 0;
  };

  /// The seeded modes. Collective (one AllGather of the ranks' input extents: the layout), on
  /// every rank with or without an input. `hasSeed`: this rank knows the seed voxel `seed_Whole`
  /// (whole-volume index). `clearOuterLayer`: the raw seeded mode
  /// (SeededDistributedCoding::Settings). Reports SeedCodeRounds, SeedCodeVoxelsSent (this
  /// rank's) and SeedCodeRoot (whole index).
  static std::unique_ptr<DistributedGlobalField> seeded(vtkMultiProcessController* controller,
    vtkImageData* input,
    const VoxelExtent6& whole,
    bool hasSeed,
    const std::array<std::int64_t, 3>& seed_Whole,
    bool clearOuterLayer,
    const CancellableCollectives::CancelCheck& cancelRequested);
  /// The unseeded thresholded or binary mask. Collective as seeded(). `parameters`: the coder's
  /// MinimumComponentSize and cluster width. Reports RootChoiceRounds, RootChoicePropagations,
  /// RootChoiceComponents and RootChoiceRoots (whole index, every root voxel of every coded
  /// component).
  static std::unique_ptr<DistributedGlobalField> automaticRoot(
    vtkMultiProcessController* controller,
    vtkImageData* input,
    const VoxelExtent6& whole,
    const DistributedRootChoice::Parameters& parameters,
    const CancellableCollectives::CancelCheck& cancelRequested);
  ~DistributedGlobalField();

  /// The whole-volume voxel of a world point on `input` (which holds its extent of the whole).
  static std::array<std::int64_t, 3> seedVoxel_Whole(vtkImageData* input,
    const double seed_World_mm[3],
    const VoxelExtent6& whole);
  /// The ranks' pieces: what each holds (its input's extent, gathered), what each owns (the
  /// executive's split, half-open on shared faces). Collective. `usable`: this rank's `piece` is
  /// a piece (else its held box is empty).
  static PieceLayout gatherLayout(RankCollectives& c,
    vtkImageData* piece,
    bool usable,
    const VoxelExtent6& whole);

  /// The coder's hook (VoxelCodingSkeletonFilter::SetGlobalSeedCode): collective, once.
  std::vector<float> code(SparseVesselMask& mask);
  /// The coder's second hook (VoxelCodingSkeletonFilter::SetGlobalFaceTips; vtouch::
  /// DistributedFaceTips): collective, once, after code() gave the field.
  std::vector<std::int64_t> faceTips(const skeleton::SkeletonTracer& tracer);
  /// After the piece's run, on every rank: joins without a mask if the run stopped before its
  /// coder (its own message stands: the join's verdict is not reported on this rank), and joins
  /// the face tips' rounds when the field was given (on every rank alike) but this rank's coder
  /// did not reach them.
  void finish();
  void addReport(vtkFieldData* fd) const;

private:
  /// `cancelRequested`: this rank's cancel (every exchange a cancel point, issue 19 item 1).
  DistributedGlobalField(vtkMultiProcessController* controller,
    const CancellableCollectives::CancelCheck& cancelRequested);

  std::unique_ptr<RankCollectives> Exchanges;   ///< over the controller
  std::unique_ptr<RankCollectives> Collectives; ///< Exchanges, cancellable
  std::unique_ptr<Source> Field;
  std::unique_ptr<DistributedFaceTips> FaceTips;
  bool FieldGiven = false; ///< the field's rounds succeeded (the same verdict on every rank)
};

} // namespace vtouch

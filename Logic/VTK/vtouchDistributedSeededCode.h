// VesselCenterline's seeded modes on a parallel pvserver with the global SS code (issue 19 item 2):
// every rank codes its piece with the single run's SS field (vtouch::SeededDistributedCoding over
// vtkMultiProcessController), instead of from a root of its own. Not a wrapped class: the filter's
// private helper (the hook RequestDistributed sets and ExtractVolume hands to the coder).
#pragma once

#include "vtouchDistributedCenterline.h" // for VoxelExtent6
#include "vtouchRankCollectives.h"
#include "vtouchSeededDistributedCoding.h"

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

class vtkFieldData;
class vtkImageData;
class vtkMultiProcessController;

namespace vtouch
{

class DistributedSeededCode
{
public:
  /// Collective (one AllGather of the ranks' input extents: the layout), on every rank with or
  /// without an input. `hasSeed`: this rank knows the seed voxel `seed_Whole` (whole-volume
  /// index). `clearOuterLayer`: the raw seeded mode (SeededDistributedCoding::Settings).
  DistributedSeededCode(vtkMultiProcessController* controller,
    vtkImageData* input,
    const VoxelExtent6& whole,
    bool hasSeed,
    const std::array<std::int64_t, 3>& seed_Whole,
    bool clearOuterLayer);
  ~DistributedSeededCode();

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
  /// After the piece's run, on every rank: joins the rounds with an empty mask if the run
  /// stopped before its coder (its own message stands: the join's verdict is not reported).
  void finish();
  /// SeedCodeRounds (int), SeedCodeVoxelsSent (this rank's) and SeedCodeRoot (whole index) as
  /// field arrays.
  void addReport(vtkFieldData* fd) const;

private:
  std::unique_ptr<RankCollectives> Collectives;
  std::unique_ptr<SeededDistributedCoding> Coding;
};

} // namespace vtouch

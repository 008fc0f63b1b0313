// VesselCenterline's raw modes on a parallel pvserver (issue 19 item 2, issue 16 item 1), seeded
// and without a seed: the candidate region of the rank's held piece, computed with the other ranks
// (vtouch::DistributedCandidateRegion over vtkMultiProcessController), as the outcome the
// filter's one-process path takes from runCandidateRegion. Not a wrapped class: the filter's
// private helper (the hook in vtkVesselTouchCenterlineFilter::RequestDistributed).
#pragma once

#include "vtouchCancellableCollectives.h"
#include "vtouchCandidateRegionRunner.h"
#include "vtouchPieceOwnership.h"

class vtkMultiProcessController;

namespace vtouch
{

class DistributedRawRegion
{
public:
  /// What the rounds did, for the output's field data.
  struct Report
  {
    int growthRounds = 0;    ///< RegionGrowthRounds
    int componentRounds = 0; ///< RegionComponentRounds (the seed's component after the neck cut)
    double sentVoxels = 0.0; ///< RegionVoxelsSent: boundary voxels this rank reported
    bool seeded = true;      ///< false: the unseeded mode (the next array is written)
    /// RegionHeldVoxelsFromOwners (unseeded): held voxels whose decision the owner's changed.
    double heldVoxelsFromOwners = 0.0;
  };

  /// The ghost margin the raw seeded mode needs at least (voxels): the range estimate's seed
  /// neighbourhood on the seed's rank (DistributedCandidateRegion::rangeMarginVoxels) and one
  /// layer for the growth's evaluable box.
  static int minimumMarginVoxels();

  /// The coder's MinimumComponentSize on a piece (project rule): a component of the seed's
  /// network in a held piece that does not hold the seed reaches the piece from a shared face,
  /// so one that reaches an owned voxel crosses the whole ghost margin and has at least
  /// `marginVoxels` voxels: capping the size there keeps every owned part of the network (the
  /// single run codes the whole network from the seed, whatever the parts' sizes).
  static int componentSizeVoxels(int minimumComponentSize, int marginVoxels)
  {
    return minimumComponentSize < marginVoxels ? minimumComponentSize : marginVoxels;
  }
  /// RegionGrowthRounds, RegionComponentRounds (int) and RegionVoxelsSent (this rank's) as field
  /// arrays; without a seed also RegionHeldVoxelsFromOwners (this rank's).
  static void addReport(vtkFieldData* fd, const Report& report);

  /// On the seed's rank: leaves in `seeded` the seed's 26-connected component of its region
  /// (the coder codes it from the seed, as the single run does) and returns the rest (parts of
  /// the network that reach the seed only outside this piece; coded from roots of their own).
  /// The rest is not ok (nothing to code) when the seed's component is the whole region, or when
  /// `seeded` has no seed here.
  static CandidateRegionOutcome splitSeedComponent(CandidateRegionOutcome& seeded);

  /// Collective: every rank calls it once per run, whatever its input (null: an empty piece;
  /// every rank then gets the same message). `piece` is the rank's input (its extent in the
  /// whole volume's index), `whole` the whole extent, `request` the filter's (automatic; seeded or
  /// not, the same on every rank: without a seed the region is every kept voxel in the range).
  static CandidateRegionOutcome run(vtkMultiProcessController* controller,
    vtkImageData* piece,
    vtkDataArray* scalars,
    const VoxelExtent6& whole,
    const CandidateRegionRequest& request,
    Report& report,
    const CancellableCollectives::CancelCheck& cancelRequested);
};

} // namespace vtouch

// Private to Logic/Skeleton: stage 4 of vtouch::VoxelCoder, the tree of paths from the tips.
#pragma once

#include "vtouchSkeletonTracer.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace vtouch
{
namespace skeleton
{

/// Back-tracing from every tip (Zhou & Toga 1999; Yi & Hayward §3.1: "center-adjusted shortest
/// lines that connect the two ends of each branch"): each cluster without higher neighbours
/// (a local maximum of the SS code), farthest first, is traced down to the skeleton traced so far
/// or to the root. Traces shorter than a spur (VoxelCodingParameters::minimumBranchLength local
/// radii) are dropped; a branch that reaches its parent across a thick junction is joined along
/// its own axis.
///
/// Input: the tracer's codes and cluster graph of one component. Output: the component's tree of
/// paths in the tracer's draft.
class TraceStage
{
public:
  /// `onlyRootBandIsRoot`: a piece coded with the global SS field (VoxelCodingParameters::
  /// globalSs_mm) has local minima of SS where the vessels enter it, besides the root (band 0)
  /// when it holds it; a trace that ends at such an entry, on no path, stays a path of its own
  /// (its end is a cut end at the piece's face, for the stitch) instead of joining the first
  /// path at the root. A trace that reaches the root band joins the root-band cluster it reached
  /// (the field may hold several roots: the automatic roots across the ranks, one per
  /// component). Off (the single run): every trace ends at the root.
  ///
  /// `faceTipBands` (the global field on several ranks, VoxelCodingParameters::faceTipBands; per
  /// cluster, or null): the tips' rank keys (DistributedTipOrder: the band, then the place in the
  /// single run's order of the volume's tips, h17j). A true tip has its own; a face tip (a local
  /// maximum of SS only because the piece ends there) has the single run's tip's beyond the face;
  /// one with no tip beyond (DistributedFaceTips::kNoTipBeyond) is the side the single run
  /// reaches only by closing a loop: it is traced after every tip as LoopStage::closeLoops' side
  /// B is, attached where it touches (no spur test, no joinAlongBranchAxis). Tips tied in rank
  /// go by their own band, higher first (one chain's entries in the single run's order), then
  /// by cluster index; without answers the rank is the band, so the single run is unchanged.
  TraceStage(SkeletonTracer& tracer,
    double minimumBranchLength,
    bool onlyRootBandIsRoot = false,
    const std::vector<std::int64_t>* faceTipBands = nullptr);

  /// Traces the component's tips; returns the number of paths it emitted.
  std::size_t run();

private:
  /// Traces tip cluster `tip`; `asLoopSide`: attached where it touches, no spur test.
  void traceTip(std::uint32_t tip, bool asLoopSide, std::size_t firstPath, std::uint32_t root);

  /// A branch trace that reaches the skeleton across a thick junction touches it early, on the
  /// crotch side: the corner is cut. Extend the branch's own axis (its centres between `far` and
  /// `near` radii of the touch) to the parent path and attach there, dropping the trace voxels
  /// within `near` radii of the touch (appendSkeletonPoint bridges the gap with a straight voxel
  /// line).
  void joinAlongBranchAxis(Trace& t, double junctionRadius);

  SkeletonTracer& tracer;
  double minimumBranchLength; // in local radii
  bool onlyRootBandIsRoot;
  const std::vector<std::int64_t>* faceTipBands;
};

} // namespace skeleton
} // namespace vtouch

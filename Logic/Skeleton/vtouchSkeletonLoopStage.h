// Private to Logic/Skeleton: stage 5 of vtouch::VoxelCoder, loop closing.
#pragma once

#include "vtouchSkeletonTracer.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace vtouch
{
namespace skeleton
{

/// Loops (where two fronts of the SS propagation meet, the skeleton of a ring has a loop; Yi &
/// Hayward §3.1 ask for a "connected and complete network", and give no rule: the rules are the
/// project's, Docs/CENTERLINES.md). Back-tracing makes a tree; this stage closes its rings, in
/// three passes: closeLoops(), closeTracedLoops(), joinFacingEnds().
///
/// Input: the tracer's codes, cluster graph and the component's tree (paths from `firstPath`).
/// Output: loop-closing paths (attached at both ends) in the draft; RawSkeleton::loops counts them.
class LoopStage
{
public:
  /// `legsEndAtEntries`: a piece coded with the global SS field (VoxelCodingParameters::
  /// globalSs_mm) has local minima of SS where the vessels enter it (TraceStage's
  /// onlyRootBandIsRoot); where two fronts that entered it apart meet inside it (a ring longer
  /// than the piece), closeLoops()' second side descends to its entry on no path: it is kept as
  /// a path attached where the fronts met, its end a cut end at the face for the stitch, which
  /// closes the loop across the pieces. Off (the single run): a side that reaches no path is
  /// dropped.
  LoopStage(SkeletonTracer& tracer,
    double minimumBranchLength,
    std::size_t firstPath,
    bool legsEndAtEntries = false);

  /// The three passes, in order.
  void run();

  /// Where two fronts of the SS propagation meet, a cluster touches two or more lower clusters. A
  /// lower one not yet on the skeleton may be the other front: trace down from it (B) and, if the
  /// cluster itself is not on the skeleton, from the cluster too (A), and join the two traces into
  /// one path attached at both ends: a loop. A trace B that meets the skeleton as soon as touches
  /// count is one front split by noise, not a loop. With `legsEndAtEntries`, a trace B that ends
  /// at an entry of the piece (an SS minimum out of the root band) on no path is kept, attached
  /// at A only (RawSkeleton::loops does not count it: the loop closes in the stitch).
  void closeLoops();

  /// Where the two fronts of a ring met, a cluster touches the skeleton on both sides; when both
  /// sides were traced already (each from its own tip, e.g. strands of noise on the wall where the
  /// fronts met), closeLoops() finds no untraced side, and the ring stays open. A cluster whose
  /// skeleton neighbours are a step apart in the vessel but far apart along the skeleton closes
  /// the ring with a short path between them.
  void closeTracedLoops();

  /// Where the fronts of a ring met amid noise, the meeting zone can hold several SS maxima: each
  /// front is traced from a tip of its own (often a strand of noise on the wall), short of the
  /// other front, and no cluster touches both (closeTracedLoops() finds nothing). A free end's
  /// stem (where the vessel is, not the strand) that faces a point of the skeleton across a short
  /// gap of vessel (within four radii, within 60 degrees of its outward direction, the straight
  /// segment inside the mask) that the skeleton reaches only the long way round is joined to it
  /// by a short path, like a trace that touches the skeleton (EndStage::pruneStubEnds() then cuts
  /// the strand beyond the stem).
  void joinFacingEnds();

private:
  /// The vessel voxels of the cheapest way from `from` to `to` (both excluded, in that order)
  /// along the ridge of the BS code, searched within half their distance plus two `radius` of
  /// their midpoint; empty when there is none.
  std::vector<std::uint32_t> medialBridge(std::uint32_t from,
    std::uint32_t to,
    double radius) const;

  SkeletonTracer& tracer;
  double minimumBranchLength; // in local radii
  std::size_t firstPath;      // the component's first path
  bool legsEndAtEntries;      // the global-field mode (see the constructor)
};

} // namespace skeleton
} // namespace vtouch

// Joins the skeleton fragments of the pieces of a distributed volume into one Q-skeleton
// (issue 19, item 2). Plain C++, no MPI: the first rank runs it on what every rank sent.
#pragma once

#include "vtouchQSkeleton.h"
#include "vtouchSkeletonFragment.h"

#include <string>
#include <vector>

namespace vtouch
{

/// What stitching did; unmatched ends are reported, never fatal.
struct StitchReport
{
  int cutEndsJoined = 0;       ///< cut ends joined to the matching cut end (counted once per pair)
  int cutEndsUnmatched = 0;    ///< cut ends with no partner: they became free ends
  int attachmentsResolved = 0; ///< attached ends whose parent point was found
  int attachmentsUnresolved = 0; ///< attached ends with no point near: they became free ends
  int loopsClosed = 0;           ///< chains of fragments that closed on themselves
  /// Points a rank labelled Bifurcation with no junction within tolerance after stitching: a
  /// branch was lost (a vessel running along a piece face, whose points each rank placed on the
  /// other's side: Docs/CLIENT-SERVER.md).
  int bifurcationsWithoutBranch = 0;
  std::vector<std::string> notes; ///< one sentence per unmatched or unresolved end
};

/// - A cut end joins the nearest cut end within tolerance, first across pieces (preferring the
///   pair whose neighbour pieces name each other: the same face, edge or corner), then within one
///   piece (a path that wanders a fraction of a voxel across the face and back: the other piece
///   placed those points on this side).
/// - Fragments joined end to end become one path (a reversed fragment has its tangents negated).
///   A chain that closes on itself (a loop spanning pieces) is one path whose tail is attached to
///   its own point 0, as PolyDataToQSkeleton represents rings.
/// - An attached end joins the nearest point of the stitched skeleton to its parent point's
///   position (the parent may have been computed by another piece), not counting its own end.
/// Tolerance for a pair of ends: max(joinTolerance_mm, half the smaller radius there).
class SkeletonStitcher
{
public:
  /// Smallest reach of a join, mm (the filter sets two voxels of the largest spacing). Default 2.
  double joinTolerance_mm = 2.0;

  QSkeleton stitch(const std::vector<SkeletonFragment>& fragments, StitchReport& report) const;
};

} // namespace vtouch

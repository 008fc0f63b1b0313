// Joins the skeleton fragments of the pieces of a distributed volume into one Q-skeleton
// (issue 19, item 2). Plain C++, no MPI: the first rank runs it on what every rank sent.
#pragma once

#include "vtouchPieceOwnership.h"
#include "vtouchProgress.h"
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
  /// Points the pieces sent that were dropped as another piece's copy (the overlap band).
  int duplicatesRemoved = 0;
  /// Kept runs of the overlap band that stitched to nothing, dropped (vtouch::OverlapBandStubs:
  /// the owner of their points coded that stretch elsewhere or not at all).
  int bandStubsDropped = 0;
  /// Points some piece sent that end up farther than the coverage reach from the stitched
  /// skeleton: a stretch no piece kept. Zero by construction; counted so that it is never silent.
  int pointsDropped = 0;
  /// Points of chains that ended with fewer than two points after joining (a kept run of one
  /// point that neither a copy took back nor a cut end joined: SkeletonOverlapResolver's
  /// settleOnePointRuns): dropped, because a path needs two points. Those no kept point covers
  /// are also in pointsDropped; the others were copies of kept geometry.
  int strayPointsDropped = 0;
  std::vector<std::string> notes; ///< one sentence per unmatched or unresolved end
};

/// - With `ownership` set (the pieces sent their owned points and an overlap band beyond their
///   shared faces, SkeletonClipper): where two pieces' fragments overlap, one copy of each point
///   is kept (vtouch::SkeletonOverlapResolver: the piece owning the copies' midpoint), so a vessel
///   crossing a face is cut where it crosses and one lying along a face is kept once; the kept
///   runs end in cut ends.
/// - A run made only of band points whose cut end found no partner is dropped
///   (vtouch::OverlapBandStubs, StitchReport::bandStubsDropped).
/// - A cut end joins the nearest cut end within tolerance, preferring the run whose copy won the
///   next point (the overlap's own partner), then ends across pieces (preferring the pair whose
///   neighbour pieces name each other: the same face, edge or corner), then within one piece.
/// - Fragments joined end to end become one path (a reversed fragment has its tangents negated).
///   A chain that closes on itself (a loop spanning pieces) is one path whose tail is attached to
///   its own point 0, as PolyDataToQSkeleton represents rings.
/// - An attached end joins the nearest point of the stitched skeleton to its parent point's
///   position (the parent may have been computed, or kept, by another piece: a branch that hung
///   on a dropped copy hangs on the kept one), not counting its own end.
/// - Every point any piece sent is checked against the result: those farther than
///   `coverageReach_mm` from it are counted (StitchReport::pointsDropped) and named.
/// - Every stitched path has at least two points and the stitch adds no zero-length segment:
///   where two joined runs both kept a point it is kept once, and a chain of one point is dropped
///   (StitchReport::strayPointsDropped).
/// Tolerance for a pair of ends: max(joinTolerance_mm, half the smaller radius there).
class SkeletonStitcher
{
public:
  /// Smallest reach of a join, mm (the filter sets two voxels of the largest spacing). Default 2.
  double joinTolerance_mm = 2.0;
  /// The pieces' ownership and index frame; with no pieces (the default) the fragments are
  /// taken as they are (no overlap).
  PieceOwnership ownership;
  IndexFrame frame;
  /// Two pieces' points within this reach are copies (kCopyReachVoxels voxels). Default 1.5.
  double copyReach_mm = 1.5;
  /// A sent point farther than this from the stitched skeleton is a dropped point. Default 1.5.
  double coverageReach_mm = 1.5;
  /// Where two joined runs meet, end points closer than this are one (no zero-length segment;
  /// the coder's own consecutive points are left as they are); two pieces' points closer than
  /// this are copies whatever their directions (SkeletonOverlapResolver::coincidentPoint_mm).
  /// Default 1e-3 (the filter: kCoincidentPointVoxels voxels).
  double coincidentPoint_mm = 1e-3;
  /// The stitch's progress and cancel (issue 16 item 6, h18q): called with the fraction done at
  /// check points every few dozen points or paths of its long passes (the overlap, the
  /// attachments, the coverage check: the 128^3 raw phantom's long run spent 21-74 s here on the
  /// first rank of 2); returning false stops the stitch with vtouch::Cancelled. Empty by default
  /// (no reports, no cancel). Reads nothing the stitch decides on: the result is the same.
  ProgressCallback progress;

  /// Throws vtouch::Cancelled when `progress` asks to stop.
  QSkeleton stitch(const std::vector<SkeletonFragment>& fragments, StitchReport& report) const;
};

} // namespace vtouch

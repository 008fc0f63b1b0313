// Keeps one copy of every stretch of vessel that two pieces of a distributed volume both sent
// (issue 19, item 2): the pieces send their owned points and those in an overlap band beyond
// their shared faces, so a vessel near a face (across it, or along it) arrives twice.
// Plain C++; the stitcher (vtouchSkeletonStitcher) runs it before joining.
#pragma once

#include "vtouchPieceOwnership.h"
#include "vtouchProgress.h"
#include "vtouchSkeletonFragment.h"

#include <cstdint>
#include <vector>

namespace vtouch
{

/// Project rule: the overlap band, in voxels, that every piece sends beyond each face it shares
/// with another piece (vtouch::SkeletonClipper). A vessel lying along a face is computed by the two
/// pieces a fraction of a voxel apart, each possibly on the other's side (measured on the 512^3
/// tree with 4 ranks: within 1 voxel of the face z = 255, Docs/CLIENT-SERVER.md); with a band
/// both send it. The band must hold a copy's point (up to 1 voxel off the face) plus the copy
/// reach (1.5 voxels) and one point spacing (1 voxel) more, so that the pair of copies is seen
/// on both sides of where the winner changes: 1 + 1.5 + 1 = 3.5, rounded up to 4 voxels. It is
/// far inside the ghost margin (>= 10 voxels, GhostMarginRule), so the band's points are coded
/// with >= 6 voxels of context.
constexpr double kOverlapBandVoxels = 4.0;

/// Project rule: two pieces' points are copies of one vessel point when they lie within this
/// many voxels (of the largest spacing) and run alike (directions within ~35 degrees). Copies
/// coded with the ghost margin's context agree within a fraction of a voxel (0.000 voxel where
/// both see the vessel whole, ClientServer.DistributedExtraction); a path's points are about a
/// voxel apart, so the nearest copy is up to half a voxel along plus that offset; two distinct
/// vessels of radius >= 1 voxel that do not touch lie > 2 voxels apart.
constexpr double kCopyReachVoxels = 1.5;

/// Project rule: two consecutive points of a stitched path closer than this many voxels are one
/// point (two joined runs that both kept it: a zero-length segment has no direction). Far below
/// any point spacing the coder makes (about a voxel) and far above the round-off of the index
/// frame (1e-12).
constexpr double kCoincidentPointVoxels = 1e-3;

/// A kept run of one fragment. A run end that is not the fragment's own end is a Cut end
/// (neighbourPiece: the piece whose copy won the first dropped point) at the run's end point.
struct OverlapRun
{
  SkeletonFragment fragment;
  std::size_t source = 0; ///< the index of the fragment the run was taken from
  /// For a run end cut here: the source fragment whose copy won the next point, else -1.
  long headToward = -1;
  long tailToward = -1;
  /// For a run end cut here: the distance from the end point to the dropped point beyond, mm
  /// (the gap to the partner run is at most this, the partner's, and the copy reach).
  double headGap_mm = 0.0;
  double tailGap_mm = 0.0;
};

/// Which copy wins: a point p of piece r and its copy q of piece s are compared at their
/// midpoint m (the same for both: the decision is symmetric): the piece owning m wins; when m
/// belongs to neither (a corner), the lower piece. With copies of several pieces (an edge or a
/// corner) their centroid decides the same way (pairwise, all could lose). At a face the lower
/// piece's fragment decides (smoothed over 7 points) and the other takes the complement. A point is
/// dropped when any other piece's copy wins against it, so a point is dropped only where a copy
/// within the reach is kept or is itself dropped for a nearer winner: no stretch is lost by
/// construction (the stitcher counts any that would be: StitchReport::pointsDropped).
class SkeletonOverlapResolver
{
public:
  SkeletonOverlapResolver(const PieceOwnership& ownership, const IndexFrame& frame);
  /// Copy reach, mm (the stitcher sets kCopyReachVoxels voxels of the largest spacing).
  double copyReach_mm = 1.5;
  /// Smallest |cos| between two copies' directions (~35 degrees).
  double minimumCopyCosine = 0.82;
  /// Two pieces' points closer than this, mm, are one point of one vessel, a copy whatever the
  /// directions (the stitcher sets kCoincidentPointVoxels voxels). Project rule (h17c): both
  /// pieces coded the same centre; the direction test tells a vessel passing near from the
  /// vessel itself, but at a fragment's clipped end the direction is one-sided, and on a zigzag
  /// of the coder's centres it is far off the other piece's central difference at the same
  /// point (the real CTA seeded on 4 ranks: |cos| 0.714; the point, kept by neither piece,
  /// was lost). Not at an attached end: a branch's first point lies on its parent's point, and
  /// there the directions tell the two vessels apart. Default 1e-3.
  double coincidentPoint_mm = 1e-3;

  /// The kept runs of `fragments`; `duplicatesRemoved` counts the points dropped as copies.
  /// `progress`: check points every kPointPeriod points of the copy search (throws
  /// vtouch::Cancelled when its callback asks to stop); the default never reports.
  std::vector<OverlapRun> resolve(const std::vector<SkeletonFragment>& fragments,
    int& duplicatesRemoved,
    const ProgressSpan& progress = ProgressSpan()) const;

  /// Points of the copy search between two check points. Project rule (h18q): the search costs
  /// up to about 0.1 ms a point on the long-run scenes (the 128^3 raw phantom's 2-rank stitch),
  /// so a cancel waits a few milliseconds here, and a check point costs nothing beside it.
  static constexpr std::uint64_t kPointPeriod = 64;

private:
  /// Whether the point at `p` of piece `r` wins against its copy at `q` of piece `s`.
  bool wins(const Vec3& p, int r, const Vec3& q, int s) const;
  const PieceOwnership& ownership_;
  IndexFrame frame_;
};

} // namespace vtouch

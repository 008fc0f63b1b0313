// Finds the kept runs of the overlap band that stitch to nothing (issue 19, item 2): a stretch a
// piece sent only because it lies in its band beyond a shared face, whose copy the owner of
// those points did not code within the copy reach. Plain C++; the stitcher
// (vtouchSkeletonStitcher) drops them after matching the cut ends.
#pragma once

#include "vtouchPieceOwnership.h"
#include "vtouchSkeletonFragment.h"

#include <vector>

namespace vtouch
{

/// Project rule: the owner of a point is the piece that codes it (PieceOwnership); the band
/// beyond a face is sent only so that the stitcher can find the copies of what both pieces coded
/// (vtouch::SkeletonOverlapResolver). A kept run is a band stub when
/// - none of its points is owned by the piece that sent it (all lie in its band), and
/// - it has a cut end that found no partner (it leaves the band into the owner's box, where the
///   owner's skeleton has no cut end to meet it: the owner coded that stretch elsewhere, or not
///   at all), and no cut end that did.
/// Kept, it would hang a vessel end (and, attached, a bifurcation) the owner's skeleton does not
/// have. Measured on ClientServer.DistributedRawSeeded (2 ranks, split at z = 55): a branch
/// leaving its parent at a shallow angle 3.5 voxels below the face; the seed's rank (and the
/// single run) attach it where it leaves, the other rank (coding from roots of its own) 3.3 mm
/// farther along the parent, inside its band; its 3 band points run ~55 degrees off the owner's
/// copy (no copy within the direction test) and end at the band's edge unmatched: one vessel
/// end and one bifurcation more than the single run. Dropped, the owner's geometry is kept, as
/// everywhere else in its box. A stub farther than the coverage reach from the stitched skeleton
/// (the owner did not code the vessel there at all) is still counted as dropped points
/// (StitchReport::pointsDropped): never silent.
class OverlapBandStubs
{
public:
  OverlapBandStubs(const PieceOwnership& ownership, const IndexFrame& frame);

  /// stub[i] != 0 when runs[i] is a band stub; `partner[e]`: the end joined to end e (end e of
  /// run e / 2, the head when e is even), or -1, as the stitcher's cut-end matching gives it.
  std::vector<char> find(const std::vector<SkeletonFragment>& runs,
    const std::vector<long>& partner) const;

private:
  /// Whether every point of `run` is owned by a piece other than the one that sent it.
  bool onlyBandPoints(const SkeletonFragment& run) const;
  const PieceOwnership& ownership_;
  IndexFrame frame_;
};

} // namespace vtouch

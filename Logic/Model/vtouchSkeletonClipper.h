// Keeps of a piece's Q-skeleton only the points that piece owns (issue 19, item 2).
#pragma once

#include "vtouchPieceOwnership.h"
#include "vtouchSkeletonFragment.h"

#include <vector>

namespace vtouch
{

/// Splits every path of `skeleton` (coded on piece `piece`'s grown extent) into the maximal runs
/// of points that `ownership` gives to `piece` or that lie within `band_voxels` of its owned box
/// (the overlap band, kOverlapBandVoxels: a vessel near a face is sent by both pieces and the
/// stitcher keeps one copy). A run ends where its path ends (Free or, for a path end attached to
/// another path, Attached with the parent point's position) or where the path leaves the owned
/// extent and its band (Cut, with the piece beyond). Points farther out are dropped: other
/// pieces compute them, with their own ghost margin.
class SkeletonClipper
{
public:
  /// `band_voxels` 0: the owned points only.
  SkeletonClipper(const PieceOwnership& ownership,
    const IndexFrame& frame,
    int piece,
    double band_voxels = 0.0);
  std::vector<SkeletonFragment> clip(const QSkeleton& skeleton) const;

private:
  int ownerOf(const SkeletonPoint& p) const;
  /// Whether the piece sends `p`: owned, or within the band.
  bool sends(const SkeletonPoint& p) const;
  const PieceOwnership& ownership_;
  IndexFrame frame_;
  int piece_;
  double band_voxels_;
};

} // namespace vtouch

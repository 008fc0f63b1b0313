// Keeps of a piece's Q-skeleton only the points that piece owns (issue 19, item 2).
#pragma once

#include "vtouchPieceOwnership.h"
#include "vtouchSkeletonFragment.h"

#include <vector>

namespace vtouch
{

/// Splits every path of `skeleton` (coded on piece `piece`'s grown extent) into the maximal runs
/// of points that `ownership` gives to `piece`. A run ends where its path ends (Free or, for a
/// path end attached to another path, Attached with the parent point's position) or where the
/// path leaves the owned extent (Cut, with the piece beyond). Points owned by other pieces are
/// dropped: those pieces compute them, with their own ghost margin.
class SkeletonClipper
{
public:
  SkeletonClipper(const PieceOwnership& ownership, const IndexFrame& frame, int piece);
  std::vector<SkeletonFragment> clip(const QSkeleton& skeleton) const;

private:
  int ownerOf(const SkeletonPoint& p) const;
  const PieceOwnership& ownership_;
  IndexFrame frame_;
  int piece_;
};

} // namespace vtouch

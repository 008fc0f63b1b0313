// A piece of a Q-skeleton path kept by one piece of a distributed volume (issue 19, item 2).
// Plain C++: the clipper (vtouchSkeletonClipper) makes them, the stitcher
// (vtouchSkeletonStitcher) joins them, the codec sends them between ranks.
#pragma once

#include "vtouchQSkeleton.h"

#include <limits>
#include <vector>

namespace vtouch
{

/// How a fragment ends.
struct FragmentEnd
{
  enum class Kind : int
  {
    Free = 0,     ///< a vessel end (as in the single-process run)
    Attached = 1, ///< attached to another path's point: the junction's parent point is at
                  ///< `position_World_mm` (found again by position when stitching, because the
                  ///< parent point may be owned, and computed, by another piece)
    Cut = 2       ///< the path leaves the piece's owned extent here, into `neighbourPiece`
  };
  Kind kind = Kind::Free;
  /// Attached: the parent point. Cut: the midpoint between the last owned point and the first
  /// point beyond (both pieces compute nearly the same pair, so their cut ends meet there).
  Vec3 position_World_mm;
  int neighbourPiece = -1; ///< Cut: the piece owning the first point beyond, else -1
  /// Attached: the positions of the parent point's neighbours along its path in the coder's
  /// skeleton (the points before and after it; NaN where the parent point is the path's end).
  /// Consecutive voxels of one cluster share its centre and radius, so the parent point can
  /// tie bit for bit with a neighbour; its neighbours tell which of the tied points the coder
  /// hung the child on (SkeletonStitcher, nearestPoint's last tie rule).
  Vec3 parentBefore_World_mm{ kNoNeighbour, kNoNeighbour, kNoNeighbour };
  Vec3 parentAfter_World_mm{ kNoNeighbour, kNoNeighbour, kNoNeighbour };
  static constexpr double kNoNeighbour = std::numeric_limits<double>::quiet_NaN();
};

/// The owned run of points of one path in one piece, head -> tail as in that path.
struct SkeletonFragment
{
  int piece = -1;
  FragmentEnd head;
  FragmentEnd tail;
  std::vector<SkeletonPoint> points;
};

} // namespace vtouch

// The points of a stitched skeleton's paths by position, for the stitcher's attachments (h18s).
// Plain C++.
#pragma once

#include "vtouchQSkeleton.h"
#include "vtouchSegmentGrid.h"

#include <cstddef>
#include <utility>
#include <vector>

namespace vtouch
{

/// Finds the points of `s`'s paths near a position, in path then point order (the order of a
/// scan of every point, which decides the stitcher's exact ties: the first one found wins).
///
/// Why (h18s): attaching each end scanned every point of the stitched skeleton (about 10 % of
/// the 128^3 raw phantom's stitch after its grids were fixed). A point farther than the largest
/// distance the attachment accepts cannot win where one within it exists, so the points within
/// that distance, in scan order, give the same answer. Points moved after construction (an end
/// moved onto its parent point) are named with moved() and always handed over.
class SkeletonPointIndex
{
public:
  /// Indexes the points of `s` (which must outlive the index; its paths are read, never
  /// changed). `cell_mm`: the cells' side, a usual query reach (mm).
  SkeletonPointIndex(const QSkeleton& s, double cell_mm);
  /// Point `point` of path `path` (the index in s.paths) has moved since construction.
  void moved(std::size_t path, std::size_t point);
  /// (path index, point) of every point within `reach_mm` of `position_World_mm` and of every
  /// moved point, maybe with others, each once, in path then point order.
  const std::vector<std::pair<std::size_t, std::size_t>>& near(const Vec3& position_World_mm,
    double reach_mm) const;

private:
  SegmentGrid grid_;
  std::vector<std::pair<std::size_t, std::size_t>> pointOf_; ///< overall index -> (path, point)
  std::vector<std::size_t> firstOf_;                         ///< path -> its first overall index
  std::vector<std::size_t> moved_;
  mutable std::vector<std::size_t> ids_;
  mutable std::vector<std::pair<std::size_t, std::size_t>> out_;
};

} // namespace vtouch

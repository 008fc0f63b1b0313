// The overlap resolver's copy search over the points of skeleton fragments: the points whose
// segments pass near a position, in a fixed order (h18s). Plain C++.
#pragma once

#include "vtouchFragmentPointGrid.h"
#include "vtouchSegmentGrid.h"
#include "vtouchSkeletonFragment.h"

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace vtouch
{

/// Finds, for a position, the fragments' points one of whose segments (the one before the point
/// and the one after it, or the point itself at a fragment's last point: what the resolver's
/// copy search measures) passes within `reach_mm` of it, and hands them over in the order in
/// which a FragmentPointGrid of cells of `orderCell_mm`, holding every point in fragment then
/// point order, visits them (its 27 cells in order, then the points in order).
///
/// Why (h18s): the copy search keeps, per piece, the first of copies tied within kTie_mm, so the
/// order of its candidates decides results; and that grid's cells are the reach plus half the
/// longest segment (so that a point's two segments are found through either end), which one
/// long junction link makes huge. Here the candidates come from a SegmentGrid of cells of the
/// reach alone and are then put in that grid's order; the points that grid would visit and this
/// one drops have no segment within the reach, and the copy search skips those without effect.
/// So the copy search's results are unchanged, bit for bit (up to cells 2^21 apart, where that
/// grid's keys collide: volumes of a million voxels a side).
class FragmentSegmentGrid
{
public:
  FragmentSegmentGrid(const std::vector<SkeletonFragment>& fragments,
    double orderCell_mm,
    double reach_mm);
  /// Calls `f(item)` for the points described above, in that order.
  template<typename F>
  void visitNear(const Vec3& position_World_mm, F&& f) const;

private:
  /// The candidates near `p` in order (a buffer reused between queries: one thread only).
  const std::vector<FragmentPointGrid::Item>& near(const Vec3& p) const;
  long orderCellOf(double v) const;
  const std::vector<SkeletonFragment>& fragments_;
  double orderCell_mm_;
  double filter_mm_; ///< the reach and a rounding margin
  SegmentGrid segments_;
  /// Segment id -> (fragment, first point); segment s of fragment g runs from point s to point
  /// s + 1 (to itself at the last point).
  std::vector<FragmentPointGrid::Item> segmentStart_;
  /// The index of each fragment's first point among all points (fragment then point order).
  std::vector<std::uint64_t> firstPoint_;
  mutable std::vector<FragmentPointGrid::Item> buffer_;
  /// (rank, item): rank = the order cell's place (0-26) above the point's overall index.
  mutable std::vector<std::pair<std::uint64_t, FragmentPointGrid::Item>> ranked_;
};

template<typename F>
void FragmentSegmentGrid::visitNear(const Vec3& p, F&& f) const
{
  for (const FragmentPointGrid::Item& item : near(p))
  {
    f(item);
  }
}

} // namespace vtouch

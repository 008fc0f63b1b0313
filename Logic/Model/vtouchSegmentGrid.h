// A uniform grid over line segments for "which segments pass within a reach of this point"
// queries (h18s: the stitcher's coverage check). Plain C++.
#pragma once

#include "vtouchVector.h"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <unordered_map>
#include <vector>

namespace vtouch
{

/// Buckets segments by the cells they pass through, so that a query visits only the segments
/// near it, however long some of them are (a junction link may cross the volume).
///
/// Why not FragmentPointGrid (h18s): bucketing a segment by its two ends needs cells of the
/// reach plus half the longest segment, and one long junction link made every cell hold most of
/// the skeleton (the coverage check of the 128^3 raw phantom on 2 ranks: 13.6 s of a 20.8 s
/// stitch). Here a segment is sampled along its length every half cell and recorded in each
/// sample's cell, so the cell size depends on the reach alone.
///
/// Guarantee: every segment with a point within `reach_mm` of a position is visited by visitNear:
/// any point of a segment lies within a quarter cell of a sample, so the cells overlapping the
/// box of half side `reach_mm` + a quarter cell around the position hold it. Segments farther
/// away may be visited too, and a segment may be visited more than once (the caller measures the
/// distance).
class SegmentGrid
{
public:
  /// `reach_mm`: the largest query distance the caller needs (>= 0). `cell_mm`: the cells' side
  /// (mm); 0 (the default) means the reach (h18s: a query then visits cells holding about
  /// (3.5 reach)^3, a fifth of 27 cells of twice the reach); never below 1e-9.
  explicit SegmentGrid(double reach_mm, double cell_mm = 0.0);
  /// Records segment `index` from `a_World_mm` to `b_World_mm` (a point when they are equal).
  void add(const Vec3& a_World_mm, const Vec3& b_World_mm, std::size_t index);
  /// Calls `f(index)` for the segments recorded in the cells overlapping the box above around
  /// `position_World_mm` (every segment within the reach among them), in the order of the cells
  /// (x outermost, each ascending) then of add().
  template<typename F>
  void visitNear(const Vec3& position_World_mm, F&& f) const
  {
    visitWithin(position_World_mm, reach_mm_, f);
  }
  /// As visitNear, for another reach (>= 0; a larger one visits more cells).
  template<typename F>
  void visitWithin(const Vec3& position_World_mm, double reach_mm, F&& f) const;
  double cellSize_mm() const { return cell_mm_; }

private:
  std::int64_t key(long i, long j, long k) const;
  long cellOf(double v) const;
  const std::vector<std::size_t>* cell(long i, long j, long k) const;
  double cell_mm_;
  double reach_mm_;
  std::unordered_map<std::int64_t, std::vector<std::size_t>> cells_;
};

template<typename F>
void SegmentGrid::visitWithin(const Vec3& p, double reach_mm, F&& f) const
{
  const double h = std::max(reach_mm, 0.0) + 0.25 * cell_mm_;
  const long i1 = cellOf(p.x + h), j1 = cellOf(p.y + h), k1 = cellOf(p.z + h);
  for (long i = cellOf(p.x - h); i <= i1; ++i)
  {
    for (long j = cellOf(p.y - h); j <= j1; ++j)
    {
      for (long k = cellOf(p.z - h); k <= k1; ++k)
      {
        if (const std::vector<std::size_t>* items = cell(i, j, k))
        {
          for (const std::size_t index : *items)
          {
            f(index);
          }
        }
      }
    }
  }
}

} // namespace vtouch

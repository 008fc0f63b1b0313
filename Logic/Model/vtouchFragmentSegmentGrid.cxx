#include "vtouchFragmentSegmentGrid.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace vtouch
{

namespace
{
/// Project rule (h18s): a segment is a candidate within the reach plus this (mm), so that the
/// rounding of this distance against the copy search's own never drops one it keeps (a candidate
/// too many changes nothing: the search measures it again).
constexpr double kFilterMargin_mm = 1e-6;
} // namespace

FragmentSegmentGrid::FragmentSegmentGrid(const std::vector<SkeletonFragment>& fragments,
  double orderCell_mm,
  double reach_mm)
  : fragments_(fragments)
  , orderCell_mm_(std::max(orderCell_mm, 1e-9)) // FragmentPointGrid's cells, to the bit
  , filter_mm_(reach_mm + kFilterMargin_mm)
  , segments_(reach_mm)
{
  std::uint64_t total = 0;
  for (std::size_t g = 0; g < fragments.size(); ++g)
  {
    firstPoint_.push_back(total);
    total += fragments[g].points.size();
    const std::vector<SkeletonPoint>& points = fragments[g].points;
    for (std::size_t s = 0; s < points.size(); ++s)
    {
      const std::size_t b = std::min(s + 1, points.size() - 1);
      segments_.add(points[s].position_World_mm, points[b].position_World_mm, segmentStart_.size());
      segmentStart_.push_back({ g, s });
    }
  }
}

long FragmentSegmentGrid::orderCellOf(double v) const
{
  return static_cast<long>(std::floor(v / orderCell_mm_));
}

const std::vector<FragmentPointGrid::Item>& FragmentSegmentGrid::near(const Vec3& p) const
{
  // The points measuring a near segment: its first point and, unless it is the fragment's last
  // point itself, the next one (whose segment before it is this one).
  buffer_.clear();
  segments_.visitNear(p,
    [&](std::size_t id)
    {
      const FragmentPointGrid::Item& start = segmentStart_[id];
      const std::vector<SkeletonPoint>& points = fragments_[start.fragment].points;
      const Vec3& a = points[start.point].position_World_mm;
      const Vec3 ab = points[std::min(start.point + 1, points.size() - 1)].position_World_mm - a;
      const double length2 = ab.dot(ab);
      const double t = length2 > 0.0 ? std::clamp((p - a).dot(ab) / length2, 0.0, 1.0) : 0.0;
      if ((a + ab * t - p).norm() > filter_mm_)
      {
        return; // beyond the reach (h18s: most of the cells' segments; the sort is then short)
      }
      buffer_.push_back(start);
      if (start.point + 1 < fragments_[start.fragment].points.size())
      {
        buffer_.push_back({ start.fragment, start.point + 1 });
      }
    });
  // Keep those in the 27 order cells around p's, ranked by their cell's place in
  // FragmentPointGrid::visitNear's loops, then fragment, then point (its order within a cell).
  const long ci = orderCellOf(p.x), cj = orderCellOf(p.y), ck = orderCellOf(p.z);
  // One integer a candidate (h18s: sorting tuples was 8 % of the 128^3 run's samples); the
  // points' overall index runs in fragment then point order, below 2^58 points.
  constexpr int kCellShift = 58;
  ranked_.clear();
  for (const FragmentPointGrid::Item& item : buffer_)
  {
    const Vec3& q = fragments_[item.fragment].points[item.point].position_World_mm;
    const long di = orderCellOf(q.x) - ci, dj = orderCellOf(q.y) - cj, dk = orderCellOf(q.z) - ck;
    if (std::labs(di) > 1 || std::labs(dj) > 1 || std::labs(dk) > 1)
    {
      continue; // never visited by the order grid
    }
    const auto cell = static_cast<std::uint64_t>((di + 1) * 9 + (dj + 1) * 3 + (dk + 1));
    ranked_.emplace_back((cell << kCellShift) | (firstPoint_[item.fragment] + item.point), item);
  }
  const auto byRank = [](const auto& a, const auto& b) { return a.first < b.first; };
  std::sort(ranked_.begin(), ranked_.end(), byRank);
  buffer_.clear();
  for (std::size_t r = 0; r < ranked_.size(); ++r)
  {
    if (r == 0 || ranked_[r].first != ranked_[r - 1].first)
    {
      buffer_.push_back(ranked_[r].second);
    }
  }
  return buffer_;
}

} // namespace vtouch

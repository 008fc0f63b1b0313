#include "vtouchFragmentSegmentGrid.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <tuple>

namespace vtouch
{

FragmentSegmentGrid::FragmentSegmentGrid(const std::vector<SkeletonFragment>& fragments,
  double orderCell_mm,
  double reach_mm)
  : fragments_(fragments)
  , orderCell_mm_(std::max(orderCell_mm, 1e-9)) // FragmentPointGrid's cells, to the bit
  , segments_(reach_mm)
{
  for (std::size_t g = 0; g < fragments.size(); ++g)
  {
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
      buffer_.push_back(start);
      if (start.point + 1 < fragments_[start.fragment].points.size())
      {
        buffer_.push_back({ start.fragment, start.point + 1 });
      }
    });
  // Keep those in the 27 order cells around p's, ranked by their cell's place in
  // FragmentPointGrid::visitNear's loops, then fragment, then point (its order within a cell).
  const long ci = orderCellOf(p.x), cj = orderCellOf(p.y), ck = orderCellOf(p.z);
  using Ranked = std::tuple<int, std::size_t, std::size_t>;
  std::vector<Ranked> ranked;
  ranked.reserve(buffer_.size());
  for (const FragmentPointGrid::Item& item : buffer_)
  {
    const Vec3& q = fragments_[item.fragment].points[item.point].position_World_mm;
    const long di = orderCellOf(q.x) - ci, dj = orderCellOf(q.y) - cj, dk = orderCellOf(q.z) - ck;
    if (std::labs(di) > 1 || std::labs(dj) > 1 || std::labs(dk) > 1)
    {
      continue; // never visited by the order grid
    }
    const int cell = static_cast<int>((di + 1) * 9 + (dj + 1) * 3 + (dk + 1));
    ranked.emplace_back(cell, item.fragment, item.point);
  }
  std::sort(ranked.begin(), ranked.end());
  ranked.erase(std::unique(ranked.begin(), ranked.end()), ranked.end());
  buffer_.clear();
  for (const auto& [cell, fragment, point] : ranked)
  {
    buffer_.push_back({ fragment, point });
  }
  return buffer_;
}

} // namespace vtouch

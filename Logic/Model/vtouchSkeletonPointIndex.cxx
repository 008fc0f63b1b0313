#include "vtouchSkeletonPointIndex.h"

#include <algorithm>

namespace vtouch
{

SkeletonPointIndex::SkeletonPointIndex(const QSkeleton& s, double cell_mm)
  : grid_(cell_mm)
{
  for (std::size_t k = 0; k < s.paths.size(); ++k)
  {
    firstOf_.push_back(pointOf_.size());
    const std::vector<SkeletonPoint>& points = s.paths[k].points;
    for (std::size_t i = 0; i < points.size(); ++i)
    {
      grid_.add(points[i].position_World_mm, points[i].position_World_mm, pointOf_.size());
      pointOf_.emplace_back(k, i);
    }
  }
}

void SkeletonPointIndex::moved(std::size_t path, std::size_t point)
{
  moved_.push_back(firstOf_[path] + point);
}

const std::vector<std::pair<std::size_t, std::size_t>>& SkeletonPointIndex::near(const Vec3& p,
  double reach_mm) const
{
  // The overall index runs in path then point order: sorting it gives the scan's order.
  ids_.assign(moved_.begin(), moved_.end());
  grid_.visitWithin(p, reach_mm, [&](std::size_t id) { ids_.push_back(id); });
  std::sort(ids_.begin(), ids_.end());
  ids_.erase(std::unique(ids_.begin(), ids_.end()), ids_.end());
  out_.clear();
  for (const std::size_t id : ids_)
  {
    out_.push_back(pointOf_[id]);
  }
  return out_;
}

} // namespace vtouch

#include "vtouchSegmentGrid.h"

#include <algorithm>
#include <cmath>

namespace vtouch
{

SegmentGrid::SegmentGrid(double reach_mm, double cell_mm)
  : cell_mm_(std::max(cell_mm > 0.0 ? cell_mm : reach_mm, 1e-9))
  , reach_mm_(std::max(reach_mm, 0.0))
{
}

long SegmentGrid::cellOf(double v) const
{
  return static_cast<long>(std::floor(v / cell_mm_));
}

std::int64_t SegmentGrid::key(long i, long j, long k) const
{
  // As FragmentPointGrid's: 21 bits a coordinate; a collision (cells 2^21 apart) only adds
  // candidates the caller rejects by distance.
  const auto bits = [](long v) { return static_cast<std::int64_t>(v & 0x1FFFFF); };
  return (bits(i) << 42) | (bits(j) << 21) | bits(k);
}

const std::vector<std::size_t>* SegmentGrid::cell(long i, long j, long k) const
{
  const auto it = cells_.find(key(i, j, k));
  return it == cells_.end() ? nullptr : &it->second;
}

void SegmentGrid::add(const Vec3& a, const Vec3& b, std::size_t index)
{
  // Samples at most half a cell apart, both ends included: every point of the segment is within
  // a quarter cell of one (the guarantee in the header).
  const double length = (b - a).norm();
  const auto steps = static_cast<std::size_t>(std::ceil(length / (0.5 * cell_mm_)));
  std::int64_t last = 0;
  for (std::size_t s = 0; s <= steps; ++s)
  {
    const double t = steps == 0 ? 0.0 : static_cast<double>(s) / static_cast<double>(steps);
    const Vec3 q = s == steps ? b : a + (b - a) * t;
    const std::int64_t c = key(cellOf(q.x), cellOf(q.y), cellOf(q.z));
    if (s > 0 && c == last)
    {
      continue; // consecutive samples in one cell: recorded once
    }
    std::vector<std::size_t>& items = cells_[c];
    if (items.empty() || items.back() != index)
    {
      items.push_back(index);
    }
    last = c;
  }
}

} // namespace vtouch

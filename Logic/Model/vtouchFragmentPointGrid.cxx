#include "vtouchFragmentPointGrid.h"

#include <algorithm>
#include <cmath>

namespace vtouch
{

FragmentPointGrid::FragmentPointGrid(double cell_mm)
  : cell_mm_(std::max(cell_mm, 1e-9))
{
}

long FragmentPointGrid::cellOf(double v) const
{
  return static_cast<long>(std::floor(v / cell_mm_));
}

std::int64_t FragmentPointGrid::key(long i, long j, long k) const
{
  // 21 bits a coordinate: cells up to +-1e6 apart (a volume of 1e6 voxels a side at 1 cell a
  // voxel) never collide; beyond, a collision only adds candidates the caller rejects by distance.
  const auto bits = [](long v) { return static_cast<std::int64_t>(v & 0x1FFFFF); };
  return (bits(i) << 42) | (bits(j) << 21) | bits(k);
}

void FragmentPointGrid::add(const Vec3& p, Item item)
{
  cells_[key(cellOf(p.x), cellOf(p.y), cellOf(p.z))].push_back(item);
}

void FragmentPointGrid::visitNear(const Vec3& p, const std::function<void(const Item&)>& f) const
{
  const long ci = cellOf(p.x), cj = cellOf(p.y), ck = cellOf(p.z);
  for (long i = ci - 1; i <= ci + 1; ++i)
  {
    for (long j = cj - 1; j <= cj + 1; ++j)
    {
      for (long k = ck - 1; k <= ck + 1; ++k)
      {
        const auto it = cells_.find(key(i, j, k));
        if (it == cells_.end())
        {
          continue;
        }
        for (const Item& item : it->second)
        {
          f(item);
        }
      }
    }
  }
}

} // namespace vtouch

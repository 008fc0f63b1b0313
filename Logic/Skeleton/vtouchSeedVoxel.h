// The seed's voxel (the single run's rule, shared by the distributed seeded coding): a click may
// land a voxel off the vessel, so the root is the vessel voxel of the seed's 3 x 3 x 3 block
// nearest its centre (a project rule: the block is the seed picking's one-voxel tolerance).
#pragma once

#include "vtouchSparseVesselMask.h"

#include <array>
#include <cstdint>
#include <limits>

namespace vtouch
{
/// The vessel voxel of `index`'s 3 x 3 x 3 block nearest its centre (ties: the first in scan
/// order, z slowest), as an index of `mask`; { -1, -1, -1 } when the block holds none.
inline std::array<std::int64_t, 3> nearestVesselVoxel(const SparseVesselMask& mask,
  const std::array<std::int64_t, 3>& index)
{
  const std::array<std::int64_t, 3>& d = mask.dims();
  double best = std::numeric_limits<double>::infinity();
  std::array<std::int64_t, 3> found{ -1, -1, -1 };
  for (int dk = -1; dk <= 1; ++dk)
    for (int dj = -1; dj <= 1; ++dj)
      for (int di = -1; di <= 1; ++di)
      {
        const std::int64_t i = index[0] + di, j = index[1] + dj, k = index[2] + dk;
        if (i < 0 || j < 0 || k < 0 || i >= d[0] || j >= d[1] || k >= d[2] ||
            !mask.test(static_cast<std::uint64_t>(i + d[0] * (j + d[1] * k))))
        {
          continue;
        }
        const double dist = di * di + dj * dj + dk * dk;
        if (dist < best)
        {
          best = dist;
          found = { i, j, k };
        }
      }
  return found;
}
} // namespace vtouch

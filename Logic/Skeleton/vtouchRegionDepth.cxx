#include "vtouchRegionDepth.h"

#include <algorithm>
#include <limits>

namespace vtouch
{

std::vector<std::uint16_t> RegionDepth::layers(const SparseVesselMask& mask,
  const ProgressSpan& progress)
{
  const auto& d = mask.dims();
  std::vector<std::uint16_t> depth(mask.vesselCount(), 0);
  std::vector<std::uint64_t> front, next;
  const auto coordinates = [&d](std::uint64_t lin)
  {
    const auto l = static_cast<std::int64_t>(lin);
    return std::array<std::int64_t, 3>{ l % d[0], (l / d[0]) % d[1], l / (d[0] * d[1]) };
  };
  const auto inMask = [&](std::int64_t i, std::int64_t j, std::int64_t k)
  {
    return i >= 0 && j >= 0 && k >= 0 && i < d[0] && j < d[1] && k < d[2] &&
           mask.test(static_cast<std::uint64_t>(i + d[0] * (j + d[1] * k)));
  };
  // Every voxel is visited twice: once for the border, once when its layer is reached.
  ProgressCounter counter(progress, 2 * mask.vesselCount());
  mask.forEach(
    [&](std::uint64_t lin)
    {
      counter.tick();
      const auto c = coordinates(lin);
      const bool border = !inMask(c[0] - 1, c[1], c[2]) || !inMask(c[0] + 1, c[1], c[2]) ||
                          !inMask(c[0], c[1] - 1, c[2]) || !inMask(c[0], c[1] + 1, c[2]) ||
                          !inMask(c[0], c[1], c[2] - 1) || !inMask(c[0], c[1], c[2] + 1);
      if (border)
      {
        depth[mask.rank(lin)] = 1;
        front.push_back(lin);
      }
    });
  std::uint16_t layer = 1;
  while (!front.empty())
  {
    layer = static_cast<std::uint16_t>(
      std::min<int>(layer + 1, std::numeric_limits<std::uint16_t>::max()));
    next.clear();
    for (std::uint64_t lin : front)
    {
      counter.tick();
      const auto c = coordinates(lin);
      for (std::int64_t dk = -1; dk <= 1; ++dk)
        for (std::int64_t dj = -1; dj <= 1; ++dj)
          for (std::int64_t di = -1; di <= 1; ++di)
          {
            const std::int64_t i = c[0] + di, j = c[1] + dj, k = c[2] + dk;
            if (!inMask(i, j, k))
            {
              continue;
            }
            const auto n = static_cast<std::uint64_t>(i + d[0] * (j + d[1] * k));
            std::uint16_t& dn = depth[mask.rank(n)];
            if (dn == 0)
            {
              dn = layer;
              next.push_back(n);
            }
          }
    }
    front.swap(next);
  }
  return depth;
}

} // namespace vtouch

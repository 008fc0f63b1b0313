#include "vtouchTubeNeckCutter.h"

#include <algorithm>
#include <limits>

namespace vtouch
{
namespace
{
struct Grid
{
  std::array<std::int64_t, 3> d;
  std::array<std::int64_t, 3> at(std::uint64_t lin) const
  {
    const auto l = static_cast<std::int64_t>(lin);
    return { l % d[0], (l / d[0]) % d[1], l / (d[0] * d[1]) };
  }
  bool inside(std::int64_t i, std::int64_t j, std::int64_t k) const
  {
    return i >= 0 && j >= 0 && k >= 0 && i < d[0] && j < d[1] && k < d[2];
  }
  std::uint64_t lin(std::int64_t i, std::int64_t j, std::int64_t k) const
  {
    return static_cast<std::uint64_t>(i + d[0] * (j + d[1] * k));
  }
};

template<typename F>
void forNeighbours(const Grid& g, std::uint64_t lin, F&& f)
{
  const auto c = g.at(lin);
  for (std::int64_t dk = -1; dk <= 1; ++dk)
    for (std::int64_t dj = -1; dj <= 1; ++dj)
      for (std::int64_t di = -1; di <= 1; ++di)
      {
        if ((di || dj || dk) && g.inside(c[0] + di, c[1] + dj, c[2] + dk))
        {
          f(g.lin(c[0] + di, c[1] + dj, c[2] + dk));
        }
      }
}
} // namespace

TubeNeckCutter::Result TubeNeckCutter::cut(const SparseVesselMask& region,
  const std::vector<std::uint16_t>& depth,
  const std::vector<float>& tubularity,
  float coreTubularity,
  float thinCoreTubularity,
  const std::array<std::int64_t, 3>* seed,
  const ProgressSpan& progress)
{
  const Grid g{ region.dims() };
  // Three passes over the region (cores, reach, kept), then the seed's component.
  ProgressCounter counter(progress.part(0.0, 0.8), 3 * region.vesselCount());
  // reach[rank]: layers left to spread (0 = not reached). Cores start at depth + 1.
  std::vector<std::uint16_t> reach(region.vesselCount(), 0);
  std::vector<std::vector<std::uint64_t>> buckets;
  Result result;
  region.forEach(
    [&](std::uint64_t lin)
    {
      counter.tick();
      const std::uint32_t r = region.rank(lin);
      bool core = tubularity[r] >= coreTubularity;
      if (!core && depth[r] <= 1 && tubularity[r] >= thinCoreTubularity)
      {
        bool thin = true;
        forNeighbours(g,
          lin,
          [&](std::uint64_t n) { thin = thin && (!region.test(n) || depth[region.rank(n)] <= 1); });
        core = thin;
      }
      if (core)
      {
        ++result.coreVoxels;
        const std::uint16_t start = static_cast<std::uint16_t>(
          std::min<int>(depth[r] + 1, std::numeric_limits<std::uint16_t>::max() - 1));
        reach[r] = start;
        if (buckets.size() <= start)
        {
          buckets.resize(start + 1u);
        }
        buckets[start].push_back(lin);
      }
    });
  // Largest reach first: each voxel is settled once with its largest reach.
  for (std::size_t b = buckets.size(); b-- > 1;)
  {
    for (std::size_t q = 0; q < buckets[b].size(); ++q)
    {
      const std::uint64_t lin = buckets[b][q];
      counter.tick();
      if (reach[region.rank(lin)] != b)
      {
        continue; // reached later with more
      }
      forNeighbours(g,
        lin,
        [&](std::uint64_t n)
        {
          if (!region.test(n))
          {
            return;
          }
          std::uint16_t& rn = reach[region.rank(n)];
          if (rn + 1u < b)
          {
            rn = static_cast<std::uint16_t>(b - 1);
            buckets[b - 1].push_back(n);
          }
        });
    }
    buckets[b].clear();
    buckets[b].shrink_to_fit();
  }
  SparseVesselMask kept(region.dims());
  region.forEach(
    [&](std::uint64_t lin)
    {
      counter.tick();
      if (reach[region.rank(lin)] > 0)
      {
        kept.set(lin);
      }
    });
  kept.finalize();
  if (!seed)
  {
    result.mask = std::move(kept);
    return result;
  }
  result.seedKept = nearestKept(kept, region, depth, *seed, result.seed);
  result.mask = result.seedKept ? component(kept, result.seed, progress.part(0.8, 1.0))
                                : SparseVesselMask(region.dims());
  if (!result.seedKept)
  {
    result.mask.finalize();
  }
  return result;
}

bool TubeNeckCutter::nearestKept(const SparseVesselMask& kept,
  const SparseVesselMask& region,
  const std::vector<std::uint16_t>& depth,
  const std::array<std::int64_t, 3>& s,
  std::array<std::int64_t, 3>& found)
{
  const Grid g{ region.dims() };
  // The kept voxel nearest the seed, within the seed's cube of half size depth + 2 (the seed's
  // own voxel may have been trimmed with a bump of wall).
  int radius = 2;
  if (g.inside(s[0], s[1], s[2]) && region.test(g.lin(s[0], s[1], s[2])))
  {
    radius += depth[region.rank(g.lin(s[0], s[1], s[2]))];
  }
  std::int64_t best = std::numeric_limits<std::int64_t>::max();
  for (std::int64_t dk = -radius; dk <= radius; ++dk)
    for (std::int64_t dj = -radius; dj <= radius; ++dj)
      for (std::int64_t di = -radius; di <= radius; ++di)
      {
        const std::int64_t i = s[0] + di, j = s[1] + dj, k = s[2] + dk;
        const std::int64_t d2 = di * di + dj * dj + dk * dk;
        if (d2 < best && g.inside(i, j, k) && kept.test(g.lin(i, j, k)))
        {
          best = d2;
          found = { i, j, k };
        }
      }
  return best != std::numeric_limits<std::int64_t>::max();
}

SparseVesselMask TubeNeckCutter::component(const SparseVesselMask& mask,
  const std::array<std::int64_t, 3>& seed,
  const ProgressSpan& progress)
{
  const Grid g{ mask.dims() };
  SparseVesselMask out(mask.dims());
  if (!g.inside(seed[0], seed[1], seed[2]) || !mask.test(g.lin(seed[0], seed[1], seed[2])))
  {
    out.finalize();
    return out;
  }
  std::vector<std::uint64_t> stack{ g.lin(seed[0], seed[1], seed[2]) };
  out.set(stack.back());
  ProgressCounter counter(progress, mask.vesselCount());
  while (!stack.empty())
  {
    counter.tick();
    const std::uint64_t lin = stack.back();
    stack.pop_back();
    forNeighbours(g,
      lin,
      [&](std::uint64_t n)
      {
        if (mask.test(n) && !out.test(n))
        {
          out.set(n);
          stack.push_back(n);
        }
      });
  }
  out.finalize();
  return out;
}

} // namespace vtouch

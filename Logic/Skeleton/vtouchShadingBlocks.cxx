#include "vtouchShadingBlocks.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace vtouch
{

double ShadingBlocks::quantile(std::vector<double>& v, double q)
{
  const auto n = static_cast<std::ptrdiff_t>(v.size());
  const std::ptrdiff_t at =
    std::min<std::ptrdiff_t>(n - 1, static_cast<std::ptrdiff_t>(q * static_cast<double>(n)));
  std::nth_element(v.begin(), v.begin() + at, v.end());
  return v[static_cast<std::size_t>(at)];
}

std::vector<ShadingBlock> ShadingBlocks::levels(const std::array<std::int64_t, 3>& wholeDims,
  std::uint64_t stride,
  const std::vector<Sample>& samples,
  std::int64_t minimumEdge_voxels,
  std::uint64_t minimumSamples)
{
  // Edge e: at least minimumSamples lattice voxels in a whole block.
  const double perVoxel = 1.0 / static_cast<double>(std::max<std::uint64_t>(1, stride));
  std::int64_t e = std::max<std::int64_t>(1, minimumEdge_voxels);
  while (static_cast<double>(e * e * e) * perVoxel < static_cast<double>(minimumSamples))
  {
    ++e;
  }
  std::array<std::int64_t, 3> nb{};
  for (std::size_t a = 0; a < 3; ++a)
  {
    nb[a] = (wholeDims[a] + e - 1) / e;
  }
  std::vector<std::vector<double>> values(static_cast<std::size_t>(nb[0] * nb[1] * nb[2]));
  for (const Sample& x : samples)
  {
    const auto l = static_cast<std::int64_t>(x.linear);
    const std::int64_t i = l % wholeDims[0], j = (l / wholeDims[0]) % wholeDims[1],
                       k = l / (wholeDims[0] * wholeDims[1]);
    values[static_cast<std::size_t>((k / e * nb[1] + j / e) * nb[0] + i / e)].push_back(x.value);
  }
  std::vector<ShadingBlock> blocks;
  std::vector<double> levels;
  for (std::size_t n = 0; n < values.size(); ++n)
  {
    std::vector<double>& v = values[n];
    if (v.size() < minimumSamples)
    {
      continue; // a thin remainder at the volume's face
    }
    const double median = quantile(v, 0.5);
    if (!(median > 0.0))
    {
      continue; // the image's zero (padding, air): no evidence
    }
    const auto id = static_cast<std::int64_t>(n);
    const std::int64_t index[3] = { id % nb[0], (id / nb[0]) % nb[1], id / (nb[0] * nb[1]) };
    ShadingBlock b;
    for (std::size_t a = 0; a < 3; ++a)
    {
      const std::int64_t lo = index[a] * e, hi = std::min(wholeDims[a], lo + e) - 1;
      b.centre[a] = 0.5 * static_cast<double>(lo + hi);
    }
    b.logLevel = std::log(median);
    b.weight = static_cast<double>(v.size());
    blocks.push_back(b);
    levels.push_back(median);
  }
  if (blocks.empty())
  {
    return blocks;
  }
  // Blocks far below the typical one are air or lung, another tissue, not a darker gain.
  const double typical = quantile(levels, 0.5);
  for (ShadingBlock& b : blocks)
  {
    b.eligible = b.kept = std::exp(b.logLevel) >= 0.25 * typical;
  }
  return blocks;
}

} // namespace vtouch

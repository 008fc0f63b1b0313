// The thickest-end rule of the automatic root (see the header).
#include "vtouchSkeletonThickerEnd.h"

#include <algorithm>
#include <numeric>

namespace vtouch
{
namespace skeleton
{

std::vector<std::uint32_t> clusterKeyOrder(const std::vector<Cluster>& clusters,
  const std::vector<float>& ss,
  const SparseVesselMask& mask)
{
  std::vector<std::uint32_t> byKey(clusters.size());
  std::iota(byKey.begin(), byKey.end(), 0U);
  const auto key = [&](std::uint32_t c)
  { return std::make_pair(ss[mask.rank(clusters[c].firstVoxel)], clusters[c].firstVoxel); };
  std::sort(
    byKey.begin(), byKey.end(), [&](std::uint32_t a, std::uint32_t b) { return key(a) < key(b); });
  std::vector<std::uint32_t> position(clusters.size());
  for (std::uint32_t p = 0; p < byKey.size(); ++p)
  {
    position[byKey[p]] = p;
  }
  return position;
}

std::optional<std::uint32_t> thickerEnd(const std::vector<Cluster>& clusters,
  const std::vector<std::uint32_t>& position)
{
  if (clusters.empty())
  {
    return std::nullopt;
  }
  // Of `next`'s neighbours, the one of most voxels, ties to the first in key order.
  const auto largest = [&](const std::vector<std::uint32_t>& next)
  {
    std::uint32_t best = next.front();
    for (const std::uint32_t n : next)
    {
      const bool more = clusters[n].count > clusters[best].count;
      const bool earlier =
        clusters[n].count == clusters[best].count && position[n] < position[best];
      best = more || earlier ? n : best;
    }
    return best;
  };
  const auto walk = [&](std::uint32_t c, bool down)
  {
    float t = clusters[c].maxBs;
    for (std::uint32_t k = 0; k < kThickerEndBands; ++k)
    {
      const std::vector<std::uint32_t>& next = down ? clusters[c].lower : clusters[c].higher;
      if (next.empty())
      {
        break;
      }
      c = largest(next);
      t = std::max(t, clusters[c].maxBs);
    }
    return t;
  };
  const auto root = static_cast<std::uint32_t>(
    std::min_element(position.begin(), position.end()) - position.begin());
  const float rootBs = walk(root, false);
  std::int64_t best = -1;
  float bestBs = 0.0F;
  for (std::uint32_t c = 0; c < clusters.size(); ++c)
  {
    if (clusters[c].band > kThickerEndBands && clusters[c].higher.empty())
    {
      const float t = walk(c, true);
      const auto b = static_cast<std::uint32_t>(best);
      if (best < 0 || t > bestBs || (t == bestBs && position[c] < position[b]))
      {
        best = c;
        bestBs = t;
      }
    }
  }
  if (best < 0 || bestBs <= kThickerEndFactor * rootBs)
  {
    return std::nullopt;
  }
  return static_cast<std::uint32_t>(best);
}

} // namespace skeleton
} // namespace vtouch

// Voxel coding stage 7: loop closing where two SS fronts meet.
#include "vtouchVoxelCodingImpl.h"

#include <queue>

namespace vtouch
{

double VoxelCoder::Impl::distanceToSkeleton(const std::array<double, 3>& q) const
{
  double best = std::numeric_limits<double>::infinity();
  for (const RawSkeletonPath& p : out.paths)
  {
    for (const auto& c : p.center_mm)
    {
      best = std::min(best, distance(c, q));
    }
  }
  return best;
}

void VoxelCoder::Impl::closeLoops()
{
  const StageTimer timer{ *this, "loops" };
  const std::size_t clusterCount = clusters.size();
  for (std::uint32_t c = 0; c < clusterCount; ++c)
  {
    if (clusters[c].lower.size() < 2)
    {
      continue;
    }
    const std::vector<std::uint32_t> lower = clusters[c].lower;
    for (std::uint32_t p : lower)
    {
      if (clusters[p].path >= 0)
      {
        continue;
      }
      // Side A: the cluster itself when it is on the skeleton, else another lower neighbour
      // already on it, else a trace down through another lower neighbour.
      Trace a;
      if (clusters[c].path >= 0)
      {
        a.path = clusters[c].path;
        a.point = clusters[c].point;
      }
      else
      {
        for (std::uint32_t q : lower)
        {
          if (q != p && clusters[q].path >= 0 && a.path < 0)
          {
            a.path = clusters[q].path;
            a.point = clusters[q].point;
            a.voxels.push_back(clusters[c].bestVoxel);
          }
        }
        for (std::uint32_t q : lower)
        {
          if (q != p && a.path < 0)
          {
            a = descend(clusters[q].bestVoxel, kInf, patienceFor(clusters[q]));
            a.voxels.insert(a.voxels.begin(), clusters[c].bestVoxel);
          }
        }
        if (a.path < 0)
        {
          continue;
        }
      }
      const P3 aEnd =
        a.voxels.empty() ? out.paths[a.path].center_mm[a.point] : centerOf(a.voxels.front());
      const double radius =
        std::max(out.paths[a.path].radius_mm[a.point], static_cast<double>(clusters[c].maxBs));
      const std::uint32_t start = clusters[p].bestVoxel;
      const double margin = 2.0 * radius + 2.0 * bandWidth;
      const float ignoreAbove = ss[mask.rank(start)] - static_cast<float>(margin);
      const Trace b = descend(start, ignoreAbove, patienceFor(clusters[p]));
      if (b.path < 0 || b.voxels.empty())
      {
        continue;
      }
      const double drop = ss[mask.rank(start)] - ss[mask.rank(b.voxels.back())];
      const double length = a.length + b.length + distance(aEnd, centerOf(start));
      // Both sides arriving at one place of the skeleton are one front too.
      const double apart =
        distance(out.paths[a.path].center_mm[a.point], out.paths[b.path].center_mm[b.point]);
      if (drop < margin + std::max(3.0 * bandWidth, radius) || apart < margin ||
          length < par.minimumBranchLength * radius)
      {
        continue;
      }
      // The other side of a real loop runs away from the skeleton; a trace alongside it (inside
      // a thick vessel) is the same lumen.
      const std::uint32_t middle = b.voxels[b.voxels.size() / 2];
      if (distanceToSkeleton(centerOf(middle)) <= radiusAt(middle) + bandWidth)
      {
        continue;
      }
      Trace joined;
      joined.path = a.path;
      joined.point = a.point;
      joined.voxels.assign(b.voxels.rbegin(), b.voxels.rend());
      joined.voxels.insert(joined.voxels.end(), a.voxels.begin(), a.voxels.end());
      emitPath(joined, false, b.path, b.point);
      ++out.loops;
    }
  }
}

namespace
{
std::uint64_t placeKey(std::pair<int, int> place)
{
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(place.first)) << 32) |
         static_cast<std::uint32_t>(place.second);
}
} // namespace

double VoxelCoder::Impl::skeletonDistance(std::pair<int, int> from,
  std::pair<int, int> to,
  double cutoff,
  const std::unordered_multimap<std::uint64_t, std::pair<int, int>>& links) const
{
  // Dijkstra from `from` over the skeleton's points, visiting only what lies within `cutoff`:
  // consecutive points of a path are joined by their distance, junction places by zero.
  std::unordered_map<std::uint64_t, double> best;
  using Entry = std::pair<double, std::pair<int, int>>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> queue;
  best[placeKey(from)] = 0.0;
  queue.push({ 0.0, from });
  while (!queue.empty())
  {
    const auto [d, u] = queue.top();
    queue.pop();
    if (d > best[placeKey(u)])
    {
      continue;
    }
    if (u == to)
    {
      return d;
    }
    const auto relax = [&](std::pair<int, int> v, double w)
    {
      if (d + w > cutoff)
      {
        return;
      }
      const auto it = best.find(placeKey(v));
      if (it == best.end() || d + w < it->second)
      {
        best[placeKey(v)] = d + w;
        queue.push({ d + w, v });
      }
    };
    const RawSkeletonPath& p = out.paths[u.first];
    for (int step : { -1, 1 })
    {
      const int q = u.second + step;
      if (q >= 0 && q < static_cast<int>(p.center_mm.size()))
      {
        relax({ u.first, q }, distance(p.center_mm[u.second], p.center_mm[q]));
      }
    }
    const auto range = links.equal_range(placeKey(u));
    for (auto it = range.first; it != range.second; ++it)
    {
      relax(it->second, 0.0);
    }
  }
  return std::numeric_limits<double>::infinity();
}

void VoxelCoder::Impl::closeTracedLoops(std::size_t firstPath)
{
  const StageTimer timer{ *this, "loops" };
  // Junction links in both directions: (path, point) -> (path, point).
  std::unordered_multimap<std::uint64_t, std::pair<int, int>> links;
  const auto link = [&](const RawJunction& j)
  {
    const std::pair<int, int> child{ j.childPath,
      j.childTail ? static_cast<int>(out.paths[j.childPath].center_mm.size()) - 1 : 0 };
    const std::pair<int, int> parent{ j.parentPath, j.parentPoint };
    links.emplace(placeKey(child), parent);
    links.emplace(placeKey(parent), child);
  };
  for (const RawJunction& j : out.junctions)
  {
    link(j);
  }
  for (std::uint32_t c = 0; c < clusters.size(); ++c)
  {
    // The places on the skeleton next to the cluster: its own and its lower neighbours'.
    std::vector<std::pair<int, int>> sides;
    if (clusters[c].path >= static_cast<int>(firstPath))
    {
      sides.push_back({ clusters[c].path, clusters[c].point });
    }
    for (std::uint32_t q : clusters[c].lower)
    {
      if (clusters[q].path >= static_cast<int>(firstPath))
      {
        sides.push_back({ clusters[q].path, clusters[q].point });
      }
    }
    if (sides.size() < 2)
    {
      continue;
    }
    const double radius = std::max(static_cast<double>(clusters[c].maxBs), 0.5 * minSpacing);
    const double margin = 2.0 * radius + 2.0 * bandWidth;
    const double cutoff = 2.0 * (margin + par.minimumBranchLength * radius);
    for (std::size_t a = 0; a < sides.size(); ++a)
    {
      for (std::size_t b = a + 1; b < sides.size(); ++b)
      {
        const RawSkeletonPath& pa = out.paths[sides[a].first];
        const RawSkeletonPath& pb = out.paths[sides[b].first];
        if (distance(pa.center_mm[sides[a].second], pb.center_mm[sides[b].second]) > margin)
        {
          continue;
        }
        // Along one path a few points apart (the usual case: a cluster and the one below it on
        // the same trace): joined, no search needed.
        if (sides[a].first == sides[b].first &&
            std::abs(sides[a].second - sides[b].second) * maxSpacing * std::sqrt(3.0) <= cutoff)
        {
          continue;
        }
        if (skeletonDistance(sides[a], sides[b], cutoff, links) <= cutoff)
        {
          continue;
        }
        // Two sides a step apart in the vessel that the skeleton joins only the long way round:
        // both fronts of a ring were traced (from two tips where they met), but not joined.
        Trace t;
        t.path = sides[a].first;
        t.point = sides[a].second;
        t.voxels.push_back(clusters[c].bestVoxel);
        emitPath(t, false, sides[b].first, sides[b].second);
        ++out.loops;
        link(out.junctions[out.junctions.size() - 2]);
        link(out.junctions.back());
      }
    }
  }
}

void VoxelCoder::Impl::pruneStubEnds(std::size_t firstPath)
{
  for (std::size_t p = firstPath; p < out.paths.size(); ++p)
  {
    RawSkeletonPath& path = out.paths[p];
    const int n = static_cast<int>(path.center_mm.size());
    int first = n, last = -1; // the outermost points other paths attach to
    for (const RawJunction& j : out.junctions)
    {
      if (j.parentPath == static_cast<int>(p))
      {
        first = std::min(first, j.parentPoint);
        last = std::max(last, j.parentPoint);
      }
    }
    if (last < 0)
    {
      continue;
    }
    const auto stubLength = [&](int from, int to)
    {
      double length = 0.0;
      for (int i = std::min(from, to); i < std::max(from, to); ++i)
      {
        length += distance(path.center_mm[i], path.center_mm[i + 1]);
      }
      return length;
    };
    const auto isStub = [&](int junctionPoint, int end)
    {
      return junctionPoint != end &&
             stubLength(junctionPoint, end) <
               std::max(par.minimumBranchLength * nearbyRadius(static_cast<int>(p), junctionPoint),
                 2.0 * bandWidth);
    };
    if (path.tailJunction < 0 && isStub(last, n - 1))
    {
      path.voxels.resize(static_cast<std::size_t>(last) + 1);
      path.center_mm.resize(static_cast<std::size_t>(last) + 1);
      path.radius_mm.resize(static_cast<std::size_t>(last) + 1);
    }
    if (path.headJunction < 0 && first < static_cast<int>(path.center_mm.size()) - 1 &&
        isStub(first, 0))
    {
      path.voxels.erase(path.voxels.begin(), path.voxels.begin() + first);
      path.center_mm.erase(path.center_mm.begin(), path.center_mm.begin() + first);
      path.radius_mm.erase(path.radius_mm.begin(), path.radius_mm.begin() + first);
      for (RawJunction& j : out.junctions)
      {
        if (j.parentPath == static_cast<int>(p))
        {
          j.parentPoint -= first;
        }
      }
    }
  }
}

} // namespace vtouch

// Measures on the paths of a raw skeleton (see vtouchSkeletonPaths.h), and the two public helpers
// of vtouchVoxelCoding.h that make and measure paths.
#include "vtouchSkeletonPaths.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <queue>

namespace vtouch
{

int appendSkeletonPoint(RawSkeletonPath& path,
  const std::array<std::int64_t, 3>& target,
  const std::array<double, 3>& center,
  double radius)
{
  if (!path.voxels.empty())
  {
    std::array<std::int64_t, 3> cur = path.voxels.back();
    if (cur == target)
    {
      return static_cast<int>(path.voxels.size()) - 1;
    }
    const std::int64_t steps = std::max(
      { std::abs(target[0] - cur[0]), std::abs(target[1] - cur[1]), std::abs(target[2] - cur[2]) });
    const std::array<double, 3> from = path.center_mm.back();
    const double r0 = path.radius_mm.back();
    for (std::int64_t s = 1; s < steps; ++s)
    {
      for (int a = 0; a < 3; ++a)
      {
        cur[a] += (target[a] > cur[a]) - (target[a] < cur[a]);
      }
      const double t = static_cast<double>(s) / static_cast<double>(steps);
      path.voxels.push_back(cur);
      path.center_mm.push_back({ from[0] + t * (center[0] - from[0]),
        from[1] + t * (center[1] - from[1]),
        from[2] + t * (center[2] - from[2]) });
      path.radius_mm.push_back(r0 + t * (radius - r0));
    }
  }
  path.voxels.push_back(target);
  path.center_mm.push_back(center);
  path.radius_mm.push_back(radius);
  return static_cast<int>(path.voxels.size()) - 1;
}

double nearbyRadius(const RawSkeletonPath& p, int point)
{
  // The largest inscribed ball centred on the path that contains the point. Walking outward,
  // no ball beyond the largest radius seen so far can reach back to the point.
  double r = p.radius_mm[point];
  for (int step : { -1, 1 })
  {
    double reach = r;
    for (int i = point + step; i >= 0 && i < static_cast<int>(p.radius_mm.size()); i += step)
    {
      const auto& a = p.center_mm[i];
      const auto& b = p.center_mm[point];
      const double d = std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]);
      if (d > reach)
      {
        break;
      }
      reach = std::max(reach, p.radius_mm[i]);
      if (d <= p.radius_mm[i])
      {
        r = std::max(r, p.radius_mm[i]);
      }
    }
  }
  return r;
}

namespace skeleton
{

double endCapRadius(const RawSkeletonPath& p, int point, double length)
{
  const int n = static_cast<int>(p.center_mm.size());
  const bool head = point == 0 && p.headJunction < 0;
  const bool tail = point == n - 1 && p.tailJunction < 0;
  if (!head && !tail)
  {
    return 0.0;
  }
  double r = 0.0;
  double walked = 0.0;
  for (int i = point, step = head ? 1 : -1; i >= 0 && i < n && walked <= length; i += step)
  {
    r = std::max(r, p.radius_mm[i]);
    if (i + step >= 0 && i + step < n)
    {
      walked += distance(p.center_mm[i], p.center_mm[i + step]);
    }
  }
  return r;
}

double vesselRadiusNear(const RawSkeletonPath& path, int point, double slack_mm)
{
  const int n = static_cast<int>(path.center_mm.size());
  const Point_mm& at = path.center_mm[point];
  double radius = path.radius_mm[point];
  for (int pass = 0; pass < 3; ++pass)
  {
    const double reach = 3.0 * radius + slack_mm;
    for (int step : { -1, 1 })
    {
      for (int i = point; i >= 0 && i < n; i += step)
      {
        const Point_mm& c = path.center_mm[i];
        if (std::hypot(c[0] - at[0], c[1] - at[1], c[2] - at[2]) > reach)
        {
          break;
        }
        radius = std::max(radius, path.radius_mm[i]);
      }
    }
  }
  return radius;
}

std::optional<FreeEnd> freeEndStem(const RawSkeletonPath& path,
  int id,
  bool tail,
  const std::vector<char>& attached,
  double voxel_mm)
{
  const int n = static_cast<int>(path.center_mm.size());
  const int step = tail ? -1 : 1;
  const int end = tail ? n - 1 : 0;
  const auto dist = [&](int i, int j)
  {
    const Point_mm& a = path.center_mm[i];
    const Point_mm& b = path.center_mm[j];
    return std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]);
  };
  const double radius = vesselRadiusNear(path, end, 2.0 * voxel_mm);
  int stem = end;
  while (path.radius_mm[stem] < 0.7 * radius)
  {
    stem += step;
    if (stem < 0 || stem >= n || attached[stem])
    {
      return std::nullopt;
    }
  }
  int inner = stem + step;
  while (inner + step >= 0 && inner + step < n && dist(inner, stem) < radius)
  {
    inner += step;
  }
  if (inner < 0 || inner >= n || dist(inner, stem) <= 0.0)
  {
    return std::nullopt;
  }
  const double length = dist(inner, stem);
  FreeEnd e;
  e.path = id;
  e.point = stem;
  e.centre = path.center_mm[stem];
  e.radius_mm = radius;
  const Point_mm& c = path.center_mm[inner];
  e.outward = {
    (e.centre[0] - c[0]) / length, (e.centre[1] - c[1]) / length, (e.centre[2] - c[2]) / length
  };
  return e;
}

double distanceToSkeleton(const RawSkeleton& skeleton, const Point_mm& q)
{
  double best = std::numeric_limits<double>::infinity();
  for (const RawSkeletonPath& p : skeleton.paths)
  {
    for (const auto& c : p.center_mm)
    {
      best = std::min(best, distance(c, q));
    }
  }
  return best;
}

std::uint64_t placeKey(std::pair<int, int> place)
{
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(place.first)) << 32) |
         static_cast<std::uint32_t>(place.second);
}

double skeletonDistance(const RawSkeleton& skeleton,
  std::pair<int, int> from,
  std::pair<int, int> to,
  double cutoff,
  const JunctionLinks& links)
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
    const RawSkeletonPath& p = skeleton.paths[u.first];
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

void linkJunction(const RawSkeleton& skeleton, const RawJunction& j, JunctionLinks& links)
{
  const std::pair<int, int> child{ j.childPath,
    j.childTail ? static_cast<int>(skeleton.paths[j.childPath].center_mm.size()) - 1 : 0 };
  const std::pair<int, int> parent{ j.parentPath, j.parentPoint };
  links.emplace(placeKey(child), parent);
  links.emplace(placeKey(parent), child);
}

} // namespace skeleton
} // namespace vtouch

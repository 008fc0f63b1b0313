// Voxel coding stages 5-6: center-adjusted back-tracing and paths (end caps:
// vtouchVoxelCodingEnds.cxx).
#include "vtouchVoxelCodingImpl.h"
#include "vtouchJunctionRecentring.h"

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

namespace
{
// Joining a branch across a thick junction (joinAlongBranchAxis), in radii of the junction.
constexpr double kJoinNear = 1.0;    // trace voxels closer than this to the first touch are dropped
constexpr double kJoinFar = 2.0;     // the branch axis is taken between kJoinFar and kJoinNear
constexpr double kJoinOffAxis = 0.5; // the parent point must lie this close to the extended axis
} // namespace

std::uint32_t VoxelCoder::Impl::ridgeVoxelNear(std::uint32_t lin, std::uint32_t cluster)
{
  // Within the slab, no farther from `lin` than the ridge can be (the vessel's radius minus
  // `lin`'s distance to the wall, plus a voxel and a half of discretisation).
  const float own = bs[mask.rank(lin)];
  const double limit = static_cast<double>(clusters[cluster].maxBs - own) + 1.5 * maxSpacing;
  const std::array<double, 3> c0 = centerOf(lin);
  std::vector<std::uint32_t>& region = ridgeScratch;
  region.clear();
  region.push_back(lin);
  flags[mask.rank(lin)] |= kRegion;
  std::uint32_t best = lin;
  for (std::size_t q = 0; q < region.size(); ++q)
  {
    if (bs[mask.rank(region[q])] > bs[mask.rank(best)])
    {
      best = region[q];
    }
    forNeighbours(region[q],
      [&](std::uint64_t u, int, std::uint32_t ru)
      {
        if (!(flags[ru] & kRegion) && (aux[ru] & ~kLabelled) == cluster &&
            distance(centerOf(static_cast<std::uint32_t>(u)), c0) <= limit)
        {
          flags[ru] |= kRegion;
          region.push_back(static_cast<std::uint32_t>(u));
        }
      });
  }
  for (std::uint32_t v : region)
  {
    flags[mask.rank(v)] &= static_cast<std::uint8_t>(~kRegion);
  }
  return best;
}

std::array<double, 3> VoxelCoder::Impl::adjustedCenter(std::uint32_t traced)
{
  const StageTimer timer{ *this, "center" };
  const std::uint32_t cluster = clusterOf(traced);
  // A trace can be held off the ridge of the BS code: each step must lower the SS code, and in a
  // bend the SS front puts the lower side next to the inner wall; on anisotropic voxels the step
  // back toward the ridge, across a long voxel side, often raises it (a sinuous vessel on
  // 1 x 1 x 2 mm voxels was traced along the inner wall of every crest). The centroid is then
  // taken around the slab's ridge nearby, not around the traced voxel.
  const std::uint32_t lin = bs[mask.rank(traced)] < 0.75F * clusters[cluster].maxBs
                              ? ridgeVoxelNear(traced, cluster)
                              : traced;
  const std::array<double, 3> c0 = centerOf(lin);
  const double reach = 1.25 * bs[mask.rank(lin)] + 0.5 * bandWidth;
  const double reach2 = reach * reach;
  scratch.clear();
  scratch.push_back(lin);
  flags[mask.rank(lin)] |= kRegion;
  double sum[3] = { 0.0, 0.0, 0.0 };
  bool truncated = false;
  const double deepBs = std::max(1.5 * minSpacing, 0.25 * static_cast<double>(bs[mask.rank(lin)]));
  for (std::size_t q = 0; q < scratch.size(); ++q)
  {
    const std::array<double, 3> p = centerOf(scratch[q]);
    for (int a = 0; a < 3; ++a)
    {
      sum[a] += p[a];
    }
    forNeighbours(scratch[q],
      [&](std::uint64_t u, int, std::uint32_t ru)
      {
        if (!(flags[ru] & kRegion) && (aux[ru] & ~kLabelled) == cluster)
        {
          if (distance2(centerOf(static_cast<std::uint32_t>(u)), c0) <= reach2)
          {
            flags[ru] |= kRegion;
            scratch.push_back(static_cast<std::uint32_t>(u));
          }
          else if (bs[ru] > deepBs)
          {
            truncated = true; // the slab goes on into a vessel beyond the ball, not its wall
          }
        }
      });
  }
  for (std::uint32_t v : scratch)
  {
    flags[mask.rank(v)] &= static_cast<std::uint8_t>(~kRegion);
  }
  // Where the slab goes on into a vessel beyond the ball (it spans a junction: the SS front is
  // tilted there and bulges toward the crotch), its centroid is pulled off the axis toward the
  // crotch; the traced voxel, on the ridge of the BS code, is not: keep it.
  if (truncated)
  {
    return c0;
  }
  const double n = static_cast<double>(scratch.size());
  return { sum[0] / n, sum[1] / n, sum[2] / n };
}

std::pair<int, int> VoxelCoder::Impl::touchedSkeleton(std::uint32_t lin) const
{
  if (flags[mask.rank(lin)] & kSkeleton)
  {
    return skeletonVoxel.at(lin);
  }
  std::pair<int, int> hit{ -1, -1 };
  forNeighbours(lin,
    [&](std::uint64_t u, int, std::uint32_t ru)
    {
      if (hit.first < 0 && (flags[ru] & kSkeleton))
      {
        hit = skeletonVoxel.at(static_cast<std::uint32_t>(u));
      }
    });
  return hit;
}

VoxelCoder::Impl::Trace VoxelCoder::Impl::descend(std::uint32_t start,
  float ignoreAbove,
  std::size_t patience) const
{
  Trace t;
  std::uint32_t v = start;
  std::uint32_t lastCluster = std::numeric_limits<std::uint32_t>::max();
  std::size_t markedRun = 0;
  while (true)
  {
    const std::uint32_t rv = mask.rank(v);
    if (ss[rv] <= ignoreAbove)
    {
      const std::pair<int, int> hit = touchedSkeleton(v);
      if (hit.first >= 0)
      {
        t.path = hit.first;
        t.point = hit.second;
        break;
      }
    }
    if (!t.voxels.empty())
    {
      t.length += distance(centerOf(t.voxels.back()), centerOf(v));
    }
    t.voxels.push_back(v);
    const std::uint32_t c = clusterOf(v);
    if (c != lastCluster)
    {
      lastCluster = c;
      markedRun = clusters[c].path >= 0 ? markedRun + 1 : 0;
      if (markedRun > patience && ss[rv] <= ignoreAbove)
      {
        t.path = clusters[c].path;
        t.point = clusters[c].point;
        break;
      }
    }
    std::uint32_t best = v;
    float bestBs = -1.0F;
    float bestSs = ss[rv];
    forNeighbours(v,
      [&](std::uint64_t u, int, std::uint32_t ru)
      {
        if (ss[ru] < ss[rv] && (bs[ru] > bestBs || (bs[ru] == bestBs && ss[ru] < bestSs)))
        {
          best = static_cast<std::uint32_t>(u);
          bestBs = bs[ru];
          bestSs = ss[ru];
        }
      });
    if (best == v)
    {
      break; // no lower neighbour: the root
    }
    v = best;
  }
  return t;
}

void VoxelCoder::Impl::markPoint(int path, int point, std::uint32_t lin)
{
  const std::uint32_t r = mask.rank(lin);
  if (!(flags[r] & kSkeleton))
  {
    flags[r] |= kSkeleton;
    skeletonVoxel[lin] = { path, point };
  }
  Cluster& c = clusters[clusterOf(lin)];
  if (c.path < 0)
  {
    c.path = path;
    c.point = point;
  }
}

void VoxelCoder::Impl::emitPath(const Trace& t, bool startOnBorder, int tailPath, int tailPoint)
{
  const int id = static_cast<int>(out.paths.size());
  out.paths.emplace_back();
  closedEnd.push_back({ false, tailPath < 0 && !startOnBorder });
  if (t.path >= 0)
  {
    const RawSkeletonPath& parent = out.paths[t.path];
    const auto voxel = parent.voxels[t.point];
    const auto center = parent.center_mm[t.point];
    const double radius = parent.radius_mm[t.point];
    RawSkeletonPath& path = out.paths[id];
    path.voxels.push_back(voxel);
    path.center_mm.push_back(center);
    path.radius_mm.push_back(radius);
    out.junctions.push_back({ id, false, t.path, t.point });
    path.headJunction = static_cast<int>(out.junctions.size()) - 1;
  }
  else
  {
    closedEnd.back()[0] = !clusters[clusterOf(t.voxels.back())].onBorder;
  }
  for (std::size_t i = t.voxels.size(); i-- > 0;)
  {
    const std::uint32_t lin = t.voxels[i];
    const int first = static_cast<int>(out.paths[id].voxels.size());
    const int point =
      appendSkeletonPoint(out.paths[id], voxelArray(lin), adjustedCenter(lin), radiusAt(lin));
    // The voxels bridging a gap (a junction joined along the branch axis) are skeleton too.
    for (int k = std::max(first, 1); k < point; ++k)
    {
      const auto& v = out.paths[id].voxels[k];
      const auto bridge = static_cast<std::uint64_t>(v[0] + nx * (v[1] + ny * v[2]));
      if (mask.test(bridge))
      {
        markPoint(id, k, static_cast<std::uint32_t>(bridge));
      }
    }
    markPoint(id, point, lin);
  }
  if (tailPath >= 0)
  {
    RawSkeletonPath& path = out.paths[id];
    const RawSkeletonPath& parent = out.paths[tailPath];
    appendSkeletonPoint(
      path, parent.voxels[tailPoint], parent.center_mm[tailPoint], parent.radius_mm[tailPoint]);
    out.junctions.push_back({ id, true, tailPath, tailPoint });
    path.tailJunction = static_cast<int>(out.junctions.size()) - 1;
  }
}

void VoxelCoder::Impl::traceComponent()
{
  const StageTimer timer{ *this, "trace(all)" };
  // Tips: clusters without higher neighbours (local maxima of the SS code), farthest first.
  std::vector<std::uint32_t> tips;
  std::uint32_t root = 0;
  for (std::uint32_t c = 0; c < clusters.size(); ++c)
  {
    if (clusters[c].higher.empty() && clusters[c].band > 0)
    {
      tips.push_back(c);
    }
    if (clusters[c].band == 0)
    {
      root = c;
    }
  }
  std::sort(tips.begin(),
    tips.end(),
    [&](std::uint32_t a, std::uint32_t b)
    { return clusters[a].band != clusters[b].band ? clusters[a].band > clusters[b].band : a < b; });
  const std::size_t firstPath = out.paths.size();
  for (std::uint32_t tip : tips)
  {
    if (clusters[tip].path >= 0)
    {
      continue;
    }
    const std::size_t patience = patienceFor(clusters[tip]);
    Trace t = descend(tipStart(clusters[tip]), kInf, patience);
    if (t.path < 0 && out.paths.size() > firstPath)
    {
      t.path = clusters[root].path; // reached the root beside the first path
      t.point = clusters[root].point;
    }
    if (t.voxels.empty())
    {
      continue;
    }
    if (t.path >= 0)
    {
      double radius = nearbyRadius(t.path, t.point);
      const double tipToJunction =
        t.length + distance(centerOf(t.voxels.back()), out.paths[t.path].center_mm[t.point]);
      radius = std::max(radius, endCapRadius(t.path, t.point, tipToJunction));
      if (tipToJunction < std::max(par.minimumBranchLength * radius, 2.0 * bandWidth))
      {
        continue; // a spur
      }
      joinAlongBranchAxis(t, radius);
    }
    else if (t.voxels.size() < 2)
    {
      continue;
    }
    emitPath(t, clusters[tip].onBorder, -1, -1);
  }
  if (out.paths.size() > firstPath)
  {
    closeLoops();
    closeTracedLoops(firstPath);
    joinFacingEnds(firstPath);
    pruneStubEnds(firstPath);
    trimClosedEnds(firstPath);
    // A vessel running through a junction gets its own axis back there (vtouchJunctionRecentring);
    // a path through a bifurcation is straightened beyond it.
    straightenThroughPaths(firstPath, recentreJunctions(out, firstPath, minSpacing));
  }
}

void VoxelCoder::Impl::straightenThroughPaths(std::size_t firstPath,
  const std::vector<bool>& recentred)
{
  const std::size_t nJunctions = out.junctions.size();
  for (std::size_t j = 0; j < nJunctions; ++j)
  {
    const RawJunction junction = out.junctions[j];
    if (junction.childTail || junction.parentPath < static_cast<int>(firstPath) ||
        (j < recentred.size() && recentred[j]))
    {
      continue;
    }
    RawSkeletonPath& path = out.paths[junction.parentPath];
    const int n = static_cast<int>(path.center_mm.size());
    const int at = junction.parentPoint;
    if (at <= 0 || at >= n - 1)
    {
      continue; // the parent ends here: not a through path
    }
    const double radius = nearbyRadius(junction.parentPath, at);
    const std::array<double, 3> c = path.center_mm[at];
    // The first point beyond one junction radius on the far (tail) side of the junction.
    int a = at + 1;
    while (a < n - 1 && distance(path.center_mm[a], c) <= kJoinNear * radius)
    {
      ++a;
    }
    if (distance(path.center_mm[a], c) <= kJoinNear * radius)
    {
      continue; // the path ends within the junction
    }
    bool pinned = false;
    for (const RawJunction& other : out.junctions)
    {
      pinned = pinned || (other.parentPath == junction.parentPath && other.parentPoint > at &&
                           other.parentPoint < a);
    }
    if (pinned)
    {
      continue;
    }
    const std::array<double, 3> e = path.center_mm[a];
    const double total = distance(e, c);
    for (int i = at + 1; i < a; ++i)
    {
      const double t = std::min(1.0, distance(path.center_mm[i], c) / total);
      path.center_mm[i] = {
        c[0] + t * (e[0] - c[0]), c[1] + t * (e[1] - c[1]), c[2] + t * (e[2] - c[2])
      };
    }
  }
}

void VoxelCoder::Impl::joinAlongBranchAxis(Trace& t, double junctionRadius)
{
  const RawSkeletonPath& parent = out.paths[t.path];
  const std::array<double, 3> touch = parent.center_mm[t.point];
  const double near = kJoinNear * junctionRadius;
  const double far = kJoinFar * junctionRadius;
  // t.voxels runs from the tip down to the touch: find the last voxel outside `near` (a) and the
  // last one outside `far` (b), both on the branch's own axis, away from the junction.
  std::size_t ia = t.voxels.size(), ib = t.voxels.size();
  for (std::size_t i = t.voxels.size(); i-- > 0;)
  {
    const double d = distance(centerOf(t.voxels[i]), touch);
    if (ia == t.voxels.size() && d > near)
    {
      ia = i;
    }
    if (d > far)
    {
      ib = i;
      break;
    }
  }
  if (ia == t.voxels.size() || ib == t.voxels.size() || ib >= ia)
  {
    return; // a short branch: keep the first touch
  }
  const std::array<double, 3> a = adjustedCenter(t.voxels[ia]);
  const std::array<double, 3> b = adjustedCenter(t.voxels[ib]);
  std::array<double, 3> dir{ a[0] - b[0], a[1] - b[1], a[2] - b[2] };
  const double len = std::sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
  if (len <= 0.0)
  {
    return;
  }
  for (double& x : dir)
  {
    x /= len;
  }
  // The parent point nearest to the branch axis extended beyond a (the junction centre), among
  // the parent's points within `far` of the touch along the path (bounded work per branch).
  int best = -1;
  double bestOff = std::numeric_limits<double>::infinity();
  const auto consider = [&](int i)
  {
    const std::array<double, 3>& q = parent.center_mm[i];
    const std::array<double, 3> w{ q[0] - a[0], q[1] - a[1], q[2] - a[2] };
    const double along = w[0] * dir[0] + w[1] * dir[1] + w[2] * dir[2];
    if (along <= 0.0)
    {
      return;
    }
    const double off =
      std::sqrt(std::max(0.0, w[0] * w[0] + w[1] * w[1] + w[2] * w[2] - along * along));
    if (off < bestOff)
    {
      bestOff = off;
      best = i;
    }
  };
  consider(t.point);
  for (int step : { -1, 1 })
  {
    for (int i = t.point + step; i >= 0 && i < static_cast<int>(parent.center_mm.size()); i += step)
    {
      if (distance(parent.center_mm[i], touch) > far)
      {
        break;
      }
      consider(i);
    }
  }
  if (best < 0 || bestOff > kJoinOffAxis * junctionRadius)
  {
    return;
  }
  t.point = best;
  t.voxels.resize(ia + 1);
}

std::uint32_t VoxelCoder::Impl::tipStart(const Cluster& c) const
{
  const std::array<double, 3> m = c.centroid();
  std::int64_t v[3];
  for (int a = 0; a < 3; ++a)
  {
    v[a] = std::clamp<std::int64_t>(std::llround(m[a] / sp[a]),
      0,
      (a == 0    ? nx
        : a == 1 ? ny
                 : nz) -
        1);
  }
  const std::uint64_t lin = static_cast<std::uint64_t>(v[0] + nx * (v[1] + ny * v[2]));
  return mask.test(lin) ? static_cast<std::uint32_t>(lin) : c.bestVoxel;
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

double VoxelCoder::Impl::endCapRadius(int path, int point, double length) const
{
  const RawSkeletonPath& p = out.paths[path];
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

double VoxelCoder::Impl::nearbyRadius(int path, int point) const
{
  return vtouch::nearbyRadius(out.paths[path], point);
}

} // namespace vtouch

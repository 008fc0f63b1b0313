// Voxel coding: the tracer that stages 4 (trace) and 5 (loops) share: back-tracing and paths.
#include "vtouchSkeletonTracer.h"

#include <algorithm>
#include <limits>

namespace vtouch
{
namespace skeleton
{
namespace
{
constexpr std::uint8_t kRegion = VoxelCodes::kRegion;
constexpr std::uint8_t kSkeleton = VoxelCodes::kSkeleton;
} // namespace

SkeletonTracer::SkeletonTracer(const VoxelGrid& g,
  RunMeter& m,
  VoxelCodes& c,
  ClusterGraph& clusters,
  SkeletonDraft& d)
  : grid(g)
  , meter(m)
  , codes(c)
  , graph(clusters)
  , draft(d)
  , out(d.skeleton)
{
}

double SkeletonTracer::nearbyRadius(int path, int point) const
{
  return vtouch::nearbyRadius(out.paths[path], point);
}

std::uint32_t SkeletonTracer::ridgeVoxelNear(std::uint32_t lin, std::uint32_t cluster)
{
  // Within the slab, no farther from `lin` than the ridge can be (the vessel's radius minus
  // `lin`'s distance to the wall, plus a voxel and a half of discretisation).
  const float own = codes.bs[grid.mask.rank(lin)];
  const double limit =
    static_cast<double>(graph.clusters[cluster].maxBs - own) + 1.5 * grid.maxSpacing;
  const std::array<double, 3> c0 = grid.centerOf(lin);
  std::vector<std::uint32_t>& region = ridgeScratch;
  region.clear();
  region.push_back(lin);
  codes.flags[grid.mask.rank(lin)] |= kRegion;
  std::uint32_t best = lin;
  for (std::size_t q = 0; q < region.size(); ++q)
  {
    if (codes.bs[grid.mask.rank(region[q])] > codes.bs[grid.mask.rank(best)])
    {
      best = region[q];
    }
    grid.forNeighbours(region[q],
      [&](std::uint64_t u, int, std::uint32_t ru)
      {
        if (!(codes.flags[ru] & kRegion) && graph.clusterOfRank(ru) == cluster &&
            distance(grid.centerOf(static_cast<std::uint32_t>(u)), c0) <= limit)
        {
          codes.flags[ru] |= kRegion;
          region.push_back(static_cast<std::uint32_t>(u));
        }
      });
  }
  for (std::uint32_t v : region)
  {
    codes.flags[grid.mask.rank(v)] &= static_cast<std::uint8_t>(~kRegion);
  }
  return best;
}

Point_mm SkeletonTracer::adjustedCenter(std::uint32_t traced)
{
  const StageTimer timer{ meter, "center" };
  const std::uint32_t cluster = clusterOf(traced);
  // A trace can be held off the ridge of the BS code: each step must lower the SS code, and in a
  // bend the SS front puts the lower side next to the inner wall; on anisotropic voxels the step
  // back toward the ridge, across a long voxel side, often raises it (a sinuous vessel on
  // 1 x 1 x 2 mm voxels was traced along the inner wall of every crest). The centroid is then
  // taken around the slab's ridge nearby, not around the traced voxel.
  const std::uint32_t lin = codes.bs[grid.mask.rank(traced)] < 0.75F * graph.clusters[cluster].maxBs
                              ? ridgeVoxelNear(traced, cluster)
                              : traced;
  const std::array<double, 3> c0 = grid.centerOf(lin);
  const double reach = 1.25 * codes.bs[grid.mask.rank(lin)] + 0.5 * grid.bandWidth;
  const double reach2 = reach * reach;
  scratch.clear();
  scratch.push_back(lin);
  codes.flags[grid.mask.rank(lin)] |= kRegion;
  double sum[3] = { 0.0, 0.0, 0.0 };
  bool truncated = false;
  const double deepBs =
    std::max(1.5 * grid.minSpacing, 0.25 * static_cast<double>(codes.bs[grid.mask.rank(lin)]));
  for (std::size_t q = 0; q < scratch.size(); ++q)
  {
    const std::array<double, 3> p = grid.centerOf(scratch[q]);
    for (int a = 0; a < 3; ++a)
    {
      sum[a] += p[a];
    }
    grid.forNeighbours(scratch[q],
      [&](std::uint64_t u, int, std::uint32_t ru)
      {
        if (!(codes.flags[ru] & kRegion) && graph.clusterOfRank(ru) == cluster)
        {
          if (distance2(grid.centerOf(static_cast<std::uint32_t>(u)), c0) <= reach2)
          {
            codes.flags[ru] |= kRegion;
            scratch.push_back(static_cast<std::uint32_t>(u));
          }
          else if (codes.bs[ru] > deepBs)
          {
            truncated = true; // the slab goes on into a vessel beyond the ball, not its wall
          }
        }
      });
  }
  for (std::uint32_t v : scratch)
  {
    codes.flags[grid.mask.rank(v)] &= static_cast<std::uint8_t>(~kRegion);
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

std::pair<int, int> SkeletonTracer::touchedSkeleton(std::uint32_t lin) const
{
  if (codes.flags[grid.mask.rank(lin)] & kSkeleton)
  {
    return skeletonVoxel.at(lin);
  }
  std::pair<int, int> hit{ -1, -1 };
  grid.forNeighbours(lin,
    [&](std::uint64_t u, int, std::uint32_t ru)
    {
      if (hit.first < 0 && (codes.flags[ru] & kSkeleton))
      {
        hit = skeletonVoxel.at(static_cast<std::uint32_t>(u));
      }
    });
  return hit;
}

Trace SkeletonTracer::descend(std::uint32_t start, float ignoreAbove, std::size_t patience) const
{
  Trace t;
  std::uint32_t v = start;
  std::uint32_t lastCluster = std::numeric_limits<std::uint32_t>::max();
  std::size_t markedRun = 0;
  while (true)
  {
    const std::uint32_t rv = grid.mask.rank(v);
    if (codes.ss[rv] <= ignoreAbove)
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
      t.length += distance(grid.centerOf(t.voxels.back()), grid.centerOf(v));
    }
    t.voxels.push_back(v);
    const std::uint32_t c = clusterOf(v);
    if (c != lastCluster)
    {
      lastCluster = c;
      markedRun = graph.clusters[c].path >= 0 ? markedRun + 1 : 0;
      if (markedRun > patience && codes.ss[rv] <= ignoreAbove)
      {
        t.path = graph.clusters[c].path;
        t.point = graph.clusters[c].point;
        break;
      }
    }
    std::uint32_t best = v;
    float bestBs = -1.0F;
    float bestSs = codes.ss[rv];
    grid.forNeighbours(v,
      [&](std::uint64_t u, int, std::uint32_t ru)
      {
        if (codes.ss[ru] < codes.ss[rv] &&
            (codes.bs[ru] > bestBs || (codes.bs[ru] == bestBs && codes.ss[ru] < bestSs)))
        {
          best = static_cast<std::uint32_t>(u);
          bestBs = codes.bs[ru];
          bestSs = codes.ss[ru];
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

void SkeletonTracer::markPoint(int path, int point, std::uint32_t lin)
{
  const std::uint32_t r = grid.mask.rank(lin);
  if (!(codes.flags[r] & kSkeleton))
  {
    codes.flags[r] |= kSkeleton;
    skeletonVoxel[lin] = { path, point };
  }
  Cluster& c = graph.clusters[clusterOf(lin)];
  if (c.path < 0)
  {
    c.path = path;
    c.point = point;
  }
}

void SkeletonTracer::emitPath(const Trace& t, bool startOnBorder, int tailPath, int tailPoint)
{
  const int id = static_cast<int>(out.paths.size());
  out.paths.emplace_back();
  draft.closedEnd.push_back({ false, tailPath < 0 && !startOnBorder });
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
    draft.closedEnd.back()[0] = !graph.clusters[clusterOf(t.voxels.back())].onBorder;
  }
  for (std::size_t i = t.voxels.size(); i-- > 0;)
  {
    const std::uint32_t lin = t.voxels[i];
    const int first = static_cast<int>(out.paths[id].voxels.size());
    const int point =
      appendSkeletonPoint(out.paths[id], grid.voxelArray(lin), adjustedCenter(lin), radiusAt(lin));
    // The voxels bridging a gap (a junction joined along the branch axis) are skeleton too.
    for (int k = std::max(first, 1); k < point; ++k)
    {
      const auto& v = out.paths[id].voxels[k];
      const std::uint64_t bridge = grid.linOf(v[0], v[1], v[2]);
      if (grid.mask.test(bridge))
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

} // namespace skeleton
} // namespace vtouch

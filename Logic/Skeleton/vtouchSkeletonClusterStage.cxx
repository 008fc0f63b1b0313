// Voxel coding stage 3: clusters and the cluster graph, root choice.
#include "vtouchSkeletonClusterStage.h"

#include "vtouchSkeletonEndCapRule.h"
#include "vtouchSkeletonThickerEnd.h"

#include <algorithm>
#include <numeric>

namespace vtouch
{
namespace skeleton
{
namespace
{
constexpr std::uint32_t kLabelled = ClusterGraph::kLabelled;

/// The root of `r`'s set in the union-find forest `parent` (path halving).
std::uint32_t find(std::uint32_t* parent, std::uint32_t r)
{
  while (parent[r] != r)
  {
    parent[r] = parent[parent[r]];
    r = parent[r];
  }
  return r;
}
} // namespace

ClusterStage::ClusterStage(const VoxelGrid& g, RunMeter& m, const VoxelCodes& c, ClusterGraph& out)
  : grid(g)
  , meter(m)
  , codes(c)
  , graph(out)
{
}

void ClusterStage::build()
{
  const StageTimer timer{ meter, "clusters" };
  // The passes' arrays, held here (their size does not change while they run).
  std::uint32_t* const aux = graph.label.data(); // union-find parents, then labels
  const float* const ss = codes.ss.data();
  const float* const bs = codes.bs.data();
  std::vector<Cluster>& clusters = graph.clusters;
  const float inverseBandWidth = grid.inverseBandWidth;
  const auto band = [&](std::uint32_t r)
  { return static_cast<std::uint32_t>(ss[r] * inverseBandWidth); };
  // The passes visit each voxel's neighbourhood: in scan (rank) order the arrays are
  // read nearly sequentially, in SS order every access is a cache miss (2-3x slower). Scan order
  // needs the whole mask to be this component (the usual case); otherwise the SS order is kept.
  const bool whole = codes.order.size() == grid.mask.vesselCount();
  const auto visit = [&](auto&& f)
  {
    if (whole)
    {
      std::uint32_t r = 0;
      grid.mask.forEach([&](std::uint64_t lin) { f(static_cast<std::uint32_t>(lin), r++); });
    }
    else
    {
      for (std::uint32_t lin : codes.order)
      {
        f(lin, grid.mask.rank(lin));
      }
    }
  };
  // Union-find (in aux, the smaller rank is the root) of the 26-neighbours in the same SS band;
  // each pair is joined once, from the later of the two in scan order.
  if (!whole)
  {
    for (std::uint32_t lin : codes.order)
    {
      const std::uint32_t r = grid.mask.rank(lin);
      aux[r] = r;
    }
  }
  std::uint32_t visited = 0;
  visit(
    [&](std::uint32_t lin, std::uint32_t r)
    {
      if ((++visited & 0xFFFF) == 0)
      {
        meter.checkpoint(); // the union-find pass is not counted as work: a check point of its own
      }
      if (whole)
      {
        aux[r] = r;
      }
      const std::uint32_t b = band(r);
      std::uint32_t rootR = find(aux, r);
      grid.forNeighbours(
        lin,
        [&](std::uint64_t, int, std::uint32_t ru)
        {
          if (band(ru) == b)
          {
            // Only this voxel's set changes here: its root is tracked.
            const std::uint32_t y = find(aux, ru);
            if (y != rootR)
            {
              aux[std::max(rootR, y)] = std::min(rootR, y);
              rootR = std::min(rootR, y);
            }
          }
        },
        grid.kHalf);
    });
  // The roots become the clusters, numbered in the key order: the SS of the set's root (its
  // smallest voxel), then that voxel's index (clusterKeyOrder). The number breaks the ties of
  // the tips' order and sets the order in which LoopStage visits the clusters. Project rule
  // (issue 19 item 2): the propagation's queue leaves the voxels of one bucket in an order that
  // depends on the whole volume, so a distributed rank, which codes its piece with the single
  // run's field (its voxels in SS order, ties by index), numbered its clusters otherwise and
  // traced tied tips in another order (the 512 x 512 x 256 scaling tree on 2 ranks: an extra
  // loop, Docs/CLIENT-SERVER.md "One cluster order").
  clusters.clear();
  std::vector<std::uint32_t> setRoots;
  visited = 0;
  for (std::uint32_t lin : codes.order)
  {
    if ((++visited & 0xFFFF) == 0)
    {
      meter.checkpoint();
    }
    const std::uint32_t r = grid.mask.rank(lin);
    if (aux[r] == r)
    {
      setRoots.push_back(lin);
    }
  }
  std::sort(setRoots.begin(),
    setRoots.end(),
    [&](std::uint32_t a, std::uint32_t b)
    {
      const float sa = ss[grid.mask.rank(a)], sb = ss[grid.mask.rank(b)];
      return sa != sb ? sa < sb : a < b;
    });
  clusters.reserve(setRoots.size());
  for (std::uint32_t lin : setRoots)
  {
    const std::uint32_t r = grid.mask.rank(lin);
    aux[r] = kLabelled | static_cast<std::uint32_t>(clusters.size());
    clusters.emplace_back();
    clusters.back().band = band(r);
    clusters.back().firstVoxel = lin; // the set's root: its smallest rank
  }
  // Label of each voxel (its set's cluster) and the cluster sums.
  const auto resolve = [&](std::uint32_t lin, std::uint32_t r)
  {
    if (!(aux[r] & kLabelled))
    {
      // Union parents precede their children in rank order, so in scan order the parent is
      // already labelled; in SS order, follow the chain.
      std::uint32_t x = aux[r];
      while (!(aux[x] & kLabelled))
      {
        x = aux[x];
      }
      aux[r] = aux[x];
    }
    Cluster& c = clusters[aux[r] & ~kLabelled];
    std::int64_t x[3];
    grid.coords(lin, x);
    ++c.count;
    c.onBorder = c.onBorder || x[0] == 0 || x[1] == 0 || x[2] == 0 || x[0] == grid.nx - 1 ||
                 x[1] == grid.ny - 1 || x[2] == grid.nz - 1;
    for (int a = 0; a < 3; ++a)
    {
      c.sum[a] += static_cast<double>(x[a] + grid.first_Whole[a]) * grid.sp[a]; // centerOf's
      c.indexSum[a] += x[a];
    }
    // Ties of BS go to the lower SS code, then to the smaller index, whatever the visiting order.
    const float bestSs = c.count == 1 ? 0.0F : ss[grid.mask.rank(c.bestVoxel)];
    if (c.count == 1 || bs[r] > c.maxBs ||
        (bs[r] == c.maxBs && (ss[r] < bestSs || (ss[r] == bestSs && lin < c.bestVoxel))))
    {
      c.maxBs = bs[r];
      c.bestVoxel = lin;
    }
  };
  // Cluster graph: clusters of different bands that touch.
  const auto link = [&](std::uint32_t lin, std::uint32_t r)
  {
    const std::uint32_t c = aux[r] & ~kLabelled;
    // Most neighbours of another band belong to one or two clusters: skip repeats cheaply.
    std::uint32_t linked[2] = { c, c };
    grid.forNeighbours(
      lin,
      [&](std::uint64_t, int, std::uint32_t ru)
      {
        const std::uint32_t cu = aux[ru] & ~kLabelled;
        if (cu == linked[0] || cu == linked[1] || clusters[cu].band == clusters[c].band)
        {
          return;
        }
        linked[1] = linked[0];
        linked[0] = cu;
        const std::uint32_t hi = clusters[cu].band > clusters[c].band ? cu : c;
        const std::uint32_t lo = hi == c ? cu : c;
        ClusterGraph::addUnique(clusters[hi].lower, lo);
        ClusterGraph::addUnique(clusters[lo].higher, hi);
      },
      grid.kHalf);
    meter.tick();
  };
  if (whole)
  {
    // One pass: in scan order the 13 neighbours before a voxel are already resolved.
    visit(
      [&](std::uint32_t lin, std::uint32_t r)
      {
        resolve(lin, r);
        link(lin, r);
      });
  }
  else
  {
    visit(resolve);
    visit(link);
  }
  // Neighbour lists in cluster (SS) order, independent of the visiting order.
  for (Cluster& c : clusters)
  {
    std::sort(c.lower.begin(), c.lower.end());
    std::sort(c.higher.begin(), c.higher.end());
  }
}

std::optional<std::uint32_t> ClusterStage::thickerRoot() const
{
  const std::vector<Cluster>& clusters = graph.clusters;
  // The clusters are numbered in the key order (build()): each one's position is its number.
  std::vector<std::uint32_t> position(clusters.size());
  std::iota(position.begin(), position.end(), 0U);
  const std::optional<std::uint32_t> end = thickerEnd(clusters, position);
  if (!end)
  {
    return std::nullopt;
  }
  // One root voxel at the centre of the end cap: every trace then converges to one point
  // (project rule, issue 19 item 2: the centroid from integer index sums, as the end cap's,
  // vtouchSkeletonEndCapRule.h, so that a distributed run finds the same voxel).
  const Cluster& c = clusters[*end];
  const std::array<std::int64_t, 3> v =
    nearestIndex(indexCentroid({ c.indexSum[0], c.indexSum[1], c.indexSum[2] }, c.count),
      { grid.nx, grid.ny, grid.nz });
  const std::uint64_t lin = grid.linOf(v[0], v[1], v[2]);
  if (grid.mask.test(lin))
  {
    return static_cast<std::uint32_t>(lin);
  }
  // Else its voxel of largest BS, ties to the lower SS, then to the smaller index (bestVoxel).
  return c.bestVoxel;
}

std::uint32_t ClusterStage::tipStart(const VoxelGrid& grid, const Cluster& c)
{
  const std::uint64_t lin = grid.nearestVoxel(c.centroid());
  return grid.mask.test(lin) ? static_cast<std::uint32_t>(lin) : c.bestVoxel;
}

} // namespace skeleton
} // namespace vtouch

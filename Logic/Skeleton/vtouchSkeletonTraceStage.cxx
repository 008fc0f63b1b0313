// Voxel coding stage 4: back-tracing from the tips.
#include "vtouchSkeletonTraceStage.h"

#include "vtouchDistributedFaceTips.h"
#include "vtouchDistributedTipOrder.h"

#include "vtouchSkeletonClusterStage.h"
#include "vtouchSkeletonPaths.h"

#include <algorithm>
#include <limits>
#include <vector>

namespace vtouch
{
namespace skeleton
{
namespace
{
constexpr float kInf = VoxelCodes::kInf;
} // namespace

TraceStage::TraceStage(SkeletonTracer& t,
  double minimumBranchLength_radii,
  bool rootBandOnly,
  const std::vector<std::int64_t>* faceTips)
  : tracer(t)
  , minimumBranchLength(minimumBranchLength_radii)
  , onlyRootBandIsRoot(rootBandOnly)
  , faceTipBands(faceTips)
{
}

std::size_t TraceStage::run()
{
  const std::vector<Cluster>& clusters = tracer.graph.clusters; // path, point change as it goes
  const RawSkeleton& out = tracer.out;
  // Tips: clusters without higher neighbours (local maxima of the SS code), farthest first. With
  // the face tips' answers, a face tip ranks by the band of the single run's tip beyond the face,
  // and one with no tip beyond waits for the end (a loop's second side).
  std::vector<std::uint32_t> tips, loopSides;
  std::uint32_t root = 0;
  const auto answer = [&](std::uint32_t c)
  { return faceTipBands ? (*faceTipBands)[c] : DistributedFaceTips::kNotAFaceTip; };
  for (std::uint32_t c = 0; c < clusters.size(); ++c)
  {
    if (clusters[c].higher.empty() && clusters[c].band > 0)
    {
      (answer(c) == DistributedFaceTips::kNoTipBeyond ? loopSides : tips).push_back(c);
    }
    if (clusters[c].band == 0)
    {
      root = c;
    }
  }
  // The rank key (DistributedTipOrder): the band, then the place in the single run's order of
  // the volume's tips (h17j: a face tip answered with a tip of the band of a true tip this rank
  // holds goes before or after it as the single run traces the two). Without answers (the single
  // run) every tip is unplaced: the band alone.
  const auto rank = [&](std::uint32_t c)
  { return answer(c) >= 0 ? answer(c) : DistributedTipOrder::unplacedRankKey(clusters[c].band); };
  // Ties in rank: the higher own band first (h19j). A tie between different own bands needs a
  // face tip (a true tip's rank is its own): a true tip and the face tips answered with its rank
  // are where its chain starts and enters the piece again, and the single run's one trace meets
  // them in descending SS; traced the other way round, the later entry's trace starts a path in the
  // middle of the chain, and the earlier one joins it as a branch. Then the cluster index.
  std::sort(tips.begin(),
    tips.end(),
    [&](std::uint32_t a, std::uint32_t b)
    {
      if (rank(a) != rank(b))
      {
        return rank(a) > rank(b);
      }
      return clusters[a].band != clusters[b].band ? clusters[a].band > clusters[b].band : a < b;
    });
  const std::size_t firstPath = out.paths.size();
  for (std::uint32_t tip : tips)
  {
    traceTip(tip, false, firstPath, root);
  }
  for (std::uint32_t side : loopSides)
  {
    traceTip(side, true, firstPath, root);
  }
  return out.paths.size() - firstPath;
}

void TraceStage::traceTip(std::uint32_t tip,
  bool asLoopSide,
  std::size_t firstPath,
  std::uint32_t root)
{
  const std::vector<Cluster>& clusters = tracer.graph.clusters;
  const VoxelGrid& grid = tracer.grid;
  const RawSkeleton& out = tracer.out;
  if (clusters[tip].path >= 0)
  {
    return;
  }
  const std::size_t patience = tracer.patienceFor(clusters[tip]);
  Trace t = tracer.descend(ClusterStage::tipStart(grid, clusters[tip]), kInf, patience);
  const bool atRoot =
    !onlyRootBandIsRoot ||
    (!t.voxels.empty() && tracer.codes.ss[grid.mask.rank(t.voxels.back())] < grid.bandWidth);
  if (onlyRootBandIsRoot && t.path < 0 && atRoot)
  {
    // The global field may hold several roots (the automatic roots across the ranks: one per
    // component, issue 19 item 2): join the root band's cluster this trace reached, when a
    // path already represents it (the first trace to reach it becomes that path). The single
    // run's rule below joins the last root cluster, which holds one root per coded component.
    const std::uint32_t reached =
      tracer.graph.clusterOfRank(static_cast<std::uint32_t>(grid.mask.rank(t.voxels.back())));
    if (clusters[reached].band == 0 && clusters[reached].path >= 0)
    {
      t.path = clusters[reached].path; // reached its root beside the first path there
      t.point = clusters[reached].point;
    }
  }
  else if (t.path < 0 && out.paths.size() > firstPath && atRoot)
  {
    t.path = clusters[root].path; // reached the root beside the first path
    t.point = clusters[root].point;
  }
  if (t.voxels.empty())
  {
    return;
  }
  if (t.path >= 0 && !asLoopSide)
  {
    double radius = tracer.nearbyRadius(t.path, t.point);
    const double tipToJunction =
      t.length + distance(grid.centerOf(t.voxels.back()), out.paths[t.path].center_mm[t.point]);
    radius = std::max(radius, endCapRadius(out.paths[t.path], t.point, tipToJunction));
    if (tipToJunction < std::max(minimumBranchLength * radius, 2.0 * grid.bandWidth))
    {
      return; // a spur
    }
    joinAlongBranchAxis(t, radius);
  }
  else if (t.path < 0 && t.voxels.size() < 2)
  {
    return;
  }
  tracer.emitPath(t, clusters[tip].onBorder, -1, -1);
}

void TraceStage::joinAlongBranchAxis(Trace& t, double junctionRadius)
{
  const VoxelGrid& grid = tracer.grid;
  const RawSkeleton& out = tracer.out;
  const RawSkeletonPath& parent = out.paths[t.path];
  const std::array<double, 3> touch = parent.center_mm[t.point];
  const double near = kJoinNear * junctionRadius;
  const double far = kJoinFar * junctionRadius;
  // t.voxels runs from the tip down to the touch: find the last voxel outside `near` (a) and the
  // last one outside `far` (b), both on the branch's own axis, away from the junction.
  std::size_t ia = t.voxels.size(), ib = t.voxels.size();
  for (std::size_t i = t.voxels.size(); i-- > 0;)
  {
    const double d = distance(grid.centerOf(t.voxels[i]), touch);
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
  const std::array<double, 3> a = tracer.adjustedCenter(t.voxels[ia]);
  const std::array<double, 3> b = tracer.adjustedCenter(t.voxels[ib]);
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

} // namespace skeleton
} // namespace vtouch

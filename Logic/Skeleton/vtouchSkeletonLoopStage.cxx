// Voxel coding stage 5: loop closing where two SS fronts meet.
#include "vtouchSkeletonLoopStage.h"

#include "vtouchSkeletonPaths.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <optional>
#include <queue>
#include <unordered_map>

namespace vtouch
{
namespace skeleton
{
namespace
{
constexpr float kInf = VoxelCodes::kInf;
/// A check point every 256 clusters of the loop passes (h18q: the passes had none, and took
/// 1.2-1.8 s of a 128^3 raw phantom piece's coding on 2 ranks, the longest stretch without a
/// progress report of that coding, and minutes of a 256^3 one; project rule: most clusters cost
/// nanoseconds there, a check point a progress callback).
constexpr std::uint32_t kClusterCheckMask = 0xFF;

/// A check point every 16 searches of the loop passes (a descent, a distance along the
/// skeleton, an end's scan of the paths near it: each up to milliseconds on the 256^3 raw
/// phantom's pieces; h18q, project rule as above).
class SearchCheck
{
public:
  explicit SearchCheck(RunMeter& meter)
    : Meter(meter)
  {
  }
  void tick()
  {
    if ((++this->Count & 0xFU) == 0)
    {
      this->Meter.checkpoint();
    }
  }

private:
  RunMeter& Meter;
  std::uint32_t Count = 0;
};
} // namespace

LoopStage::LoopStage(SkeletonTracer& t,
  double minimumBranchLength_radii,
  std::size_t first,
  bool entriesEndLegs)
  : tracer(t)
  , minimumBranchLength(minimumBranchLength_radii)
  , firstPath(first)
  , legsEndAtEntries(entriesEndLegs)
{
}

void LoopStage::run()
{
  closeLoops();
  closeTracedLoops();
  joinFacingEnds();
}

void LoopStage::closeLoops()
{
  const VoxelGrid& grid = tracer.grid;
  const VoxelCodes& codes = tracer.codes;
  const std::vector<Cluster>& clusters = tracer.graph.clusters; // path, point change as it goes
  RawSkeleton& out = tracer.out;
  const StageTimer timer{ tracer.meter, "loops" };
  SearchCheck searches(tracer.meter);
  const std::size_t clusterCount = clusters.size();
  for (std::uint32_t c = 0; c < clusterCount; ++c)
  {
    if ((c & kClusterCheckMask) == 0)
    {
      tracer.meter.checkpoint(); // not counted as work: a check point of its own (h18q)
    }
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
      searches.tick();
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
            a = tracer.descend(clusters[q].bestVoxel, kInf, tracer.patienceFor(clusters[q]));
            a.voxels.insert(a.voxels.begin(), clusters[c].bestVoxel);
          }
        }
        if (a.path < 0)
        {
          continue;
        }
      }
      const Point_mm aEnd =
        a.voxels.empty() ? out.paths[a.path].center_mm[a.point] : grid.centerOf(a.voxels.front());
      const double radius =
        std::max(out.paths[a.path].radius_mm[a.point], static_cast<double>(clusters[c].maxBs));
      const std::uint32_t start = clusters[p].bestVoxel;
      const double margin = 2.0 * radius + 2.0 * grid.bandWidth;
      const float ignoreAbove = codes.ss[grid.mask.rank(start)] - static_cast<float>(margin);
      const Trace b = tracer.descend(start, ignoreAbove, tracer.patienceFor(clusters[p]));
      if (b.voxels.empty())
      {
        continue;
      }
      // The global-field mode: B reached no path and ends where a vessel enters the piece (an SS
      // minimum out of the root band, where the single run's B would have gone on to the root).
      const bool toEntry = b.path < 0 && legsEndAtEntries &&
                           codes.ss[grid.mask.rank(b.voxels.back())] >= grid.bandWidth;
      if (b.path < 0 && !toEntry)
      {
        continue;
      }
      const double drop =
        codes.ss[grid.mask.rank(start)] - codes.ss[grid.mask.rank(b.voxels.back())];
      const double length = a.length + b.length + distance(aEnd, grid.centerOf(start));
      // Both sides arriving at one place of the skeleton are one front too (an entry is no place
      // of the skeleton: B arrived apart from A).
      const double apart = toEntry ? std::numeric_limits<double>::infinity()
                                   : distance(out.paths[a.path].center_mm[a.point],
                                       out.paths[b.path].center_mm[b.point]);
      if (drop < margin + std::max(3.0 * grid.bandWidth, radius) || apart < margin ||
          length < minimumBranchLength * radius)
      {
        continue;
      }
      // The other side of a real loop runs away from the skeleton; a trace alongside it (inside
      // a thick vessel) is the same lumen.
      const std::uint32_t middle = b.voxels[b.voxels.size() / 2];
      if (distanceToSkeleton(out, grid.centerOf(middle)) <=
          tracer.radiusAt(middle) + grid.bandWidth)
      {
        continue;
      }
      Trace joined;
      joined.path = a.path;
      joined.point = a.point;
      joined.voxels.assign(b.voxels.rbegin(), b.voxels.rend());
      joined.voxels.insert(joined.voxels.end(), a.voxels.begin(), a.voxels.end());
      if (toEntry)
      {
        // Its tail is the entry: a cut end at the face when the cluster touches the border.
        tracer.emitPath(joined, clusters[tracer.clusterOf(b.voxels.back())].onBorder, -1, -1);
        continue;
      }
      tracer.emitPath(joined, false, b.path, b.point);
      ++out.loops;
    }
  }
}

void LoopStage::closeTracedLoops()
{
  const VoxelGrid& grid = tracer.grid;
  const std::vector<Cluster>& clusters = tracer.graph.clusters; // path, point change as it goes
  RawSkeleton& out = tracer.out;
  const StageTimer timer{ tracer.meter, "loops" };
  SearchCheck searches(tracer.meter);
  // Junction links in both directions: (path, point) -> (path, point).
  JunctionLinks links;
  const auto link = [&](const RawJunction& j) { linkJunction(out, j, links); };
  for (const RawJunction& j : out.junctions)
  {
    link(j);
  }
  for (std::uint32_t c = 0; c < clusters.size(); ++c)
  {
    if ((c & kClusterCheckMask) == 0)
    {
      tracer.meter.checkpoint(); // not counted as work: a check point of its own (h18q)
    }
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
    const double radius = std::max(static_cast<double>(clusters[c].maxBs), 0.5 * grid.minSpacing);
    const double margin = 2.0 * radius + 2.0 * grid.bandWidth;
    const double cutoff = 2.0 * (margin + minimumBranchLength * radius);
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
            std::abs(sides[a].second - sides[b].second) * grid.maxSpacing * std::sqrt(3.0) <=
              cutoff)
        {
          continue;
        }
        // Joined nearby already? Measured with the vessel's radius: the cluster can be a strand
        // of noise on the wall, whose own radius would take a second bridge across the same
        // meeting zone for a second loop.
        const double vessel = std::max({ radius,
          vesselRadiusNear(pa, sides[a].second, 2.0 * grid.maxSpacing),
          vesselRadiusNear(pb, sides[b].second, 2.0 * grid.maxSpacing) });
        const double nearby = std::max(
          cutoff, 2.0 * (2.0 * vessel + 2.0 * grid.bandWidth + minimumBranchLength * vessel));
        searches.tick();
        if (skeletonDistance(out, sides[a], sides[b], nearby, links) <= nearby)
        {
          continue;
        }
        // Two sides a step apart in the vessel that the skeleton joins only the long way round:
        // both fronts of a ring were traced (from two tips where they met), but not joined.
        Trace t;
        t.path = sides[a].first;
        t.point = sides[a].second;
        t.voxels.push_back(clusters[c].bestVoxel);
        tracer.emitPath(t, false, sides[b].first, sides[b].second);
        ++out.loops;
        link(out.junctions[out.junctions.size() - 2]);
        link(out.junctions.back());
      }
    }
  }
}

std::vector<std::uint32_t> LoopStage::medialBridge(std::uint32_t from,
  std::uint32_t to,
  double radius) const
{
  const VoxelGrid& grid = tracer.grid;
  const VoxelCodes& codes = tracer.codes;
  // Dijkstra over the vessel voxels within reach of the two ends; a step costs its length times
  // (radius / BS)^2, so the cheapest way keeps to the ridge of the BS code (the medial axis) and
  // follows a curved vessel instead of cutting its chord.
  const Point_mm a = grid.centerOf(from);
  const Point_mm b = grid.centerOf(to);
  const Point_mm mid{ 0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1]), 0.5 * (a[2] + b[2]) };
  const double reach = 0.5 * distance(a, b) + 2.0 * radius;
  std::unordered_map<std::uint32_t, std::pair<double, std::uint32_t>> best; // cost, previous
  using Entry = std::pair<double, std::uint32_t>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> queue;
  best[from] = { 0.0, from };
  queue.push({ 0.0, from });
  while (!queue.empty())
  {
    const auto [cost, v] = queue.top();
    queue.pop();
    if (cost > best[v].first)
    {
      continue;
    }
    if (v == to)
    {
      std::vector<std::uint32_t> chain;
      for (std::uint32_t u = best[to].second; u != from; u = best[u].second)
      {
        chain.push_back(u);
      }
      std::reverse(chain.begin(), chain.end());
      return chain; // from `from` to `to`, both excluded
    }
    const Point_mm cv = grid.centerOf(v);
    grid.forNeighbours(v,
      [&](std::uint64_t u, int, std::uint32_t ru)
      {
        const auto lin = static_cast<std::uint32_t>(u);
        const Point_mm cu = grid.centerOf(lin);
        if (distance(cu, mid) > reach)
        {
          return;
        }
        const double weight =
          radius / std::max(static_cast<double>(codes.bs[ru]), 0.5 * grid.minSpacing);
        const double next = cost + distance(cu, cv) * weight * weight;
        const auto it = best.find(lin);
        if (it == best.end() || next < it->second.first)
        {
          best[lin] = { next, v };
          queue.push({ next, lin });
        }
      });
  }
  return {};
}

void LoopStage::joinFacingEnds()
{
  const VoxelGrid& grid = tracer.grid;
  RawSkeleton& out = tracer.out;
  const StageTimer timer{ tracer.meter, "loops" };
  SearchCheck searches(tracer.meter);
  std::vector<char> attached; // per path point: a junction's parent point
  std::vector<FreeEnd> ends;
  for (std::size_t p = firstPath; p < out.paths.size(); ++p)
  {
    searches.tick(); // each path scans every junction
    const RawSkeletonPath& path = out.paths[p];
    const int n = static_cast<int>(path.center_mm.size());
    attached.assign(static_cast<std::size_t>(n), 0);
    for (const RawJunction& j : out.junctions)
    {
      if (j.parentPath == static_cast<int>(p))
      {
        attached[static_cast<std::size_t>(j.parentPoint)] = 1;
      }
    }
    for (const bool tail : { false, true })
    {
      const int end = tail ? n - 1 : 0;
      if ((tail ? path.tailJunction : path.headJunction) >= 0 || attached[end] || n < 3)
      {
        continue;
      }
      if (const std::optional<FreeEnd> e =
            freeEndStem(path, static_cast<int>(p), tail, attached, grid.maxSpacing))
      {
        ends.push_back(*e);
      }
    }
  }
  if (ends.size() < 2)
  {
    return;
  }
  JunctionLinks links;
  const auto link = [&](const RawJunction& j) { linkJunction(out, j, links); };
  for (const RawJunction& j : out.junctions)
  {
    link(j);
  }
  // Each stem joins the nearest point of the skeleton in front of it that passes the tests; the
  // nearest stems first, and a stem that was joined to is not joined from again.
  struct Candidate
  {
    double gap;
    std::size_t end;
    int path, point;
  };
  std::vector<Candidate> candidates;
  // Each path's bounding box: an end looks only at the paths within its reach (a large tree has
  // thousands of ends and paths).
  std::vector<std::array<Point_mm, 2>> boxes(out.paths.size());
  for (std::size_t p = firstPath; p < out.paths.size(); ++p)
  {
    boxes[p] = { out.paths[p].center_mm.front(), out.paths[p].center_mm.front() };
    for (const Point_mm& c : out.paths[p].center_mm)
    {
      for (int a = 0; a < 3; ++a)
      {
        boxes[p][0][a] = std::min(boxes[p][0][a], c[a]);
        boxes[p][1][a] = std::max(boxes[p][1][a], c[a]);
      }
    }
  }
  for (std::size_t e = 0; e < ends.size(); ++e)
  {
    searches.tick();
    const FreeEnd& end = ends[e];
    const double reach = 4.0 * end.radius_mm + 2.0 * grid.bandWidth;
    for (std::size_t p = firstPath; p < out.paths.size(); ++p)
    {
      bool near = true;
      for (int a = 0; a < 3; ++a)
      {
        near = near && end.centre[a] >= boxes[p][0][a] - reach &&
               end.centre[a] <= boxes[p][1][a] + reach;
      }
      if (!near)
      {
        continue;
      }
      const RawSkeletonPath& path = out.paths[p];
      for (std::size_t i = 0; i < path.center_mm.size(); ++i)
      {
        const Point_mm& c = path.center_mm[i];
        const Point_mm ab{ c[0] - end.centre[0], c[1] - end.centre[1], c[2] - end.centre[2] };
        const double gap = std::sqrt(ab[0] * ab[0] + ab[1] * ab[1] + ab[2] * ab[2]);
        const double facing =
          end.outward[0] * ab[0] + end.outward[1] * ab[1] + end.outward[2] * ab[2];
        // On the vessel, not on a strand of noise on its wall.
        const bool inVessel = path.radius_mm[i] >= 0.5 * end.radius_mm;
        if (gap > 0.0 && gap <= reach && facing >= 0.5 * gap && inVessel)
        {
          candidates.push_back({ gap, e, static_cast<int>(p), static_cast<int>(i) });
        }
      }
    }
  }
  std::sort(candidates.begin(),
    candidates.end(),
    [](const Candidate& x, const Candidate& y) { return x.gap < y.gap; });
  std::vector<char> used(ends.size(), 0);
  for (const Candidate& cand : candidates)
  {
    searches.tick();
    const FreeEnd& end = ends[cand.end];
    const auto target = std::find_if(ends.begin(),
      ends.end(),
      [&](const FreeEnd& f) { return f.path == cand.path && f.point == cand.point; });
    if (used[cand.end] ||
        (target != ends.end() && used[static_cast<std::size_t>(target - ends.begin())]))
    {
      continue;
    }
    const Point_mm& c = out.paths[cand.path].center_mm[cand.point];
    // The straight segment between the two lies in the vessel (samples half a voxel apart).
    const int samples = static_cast<int>(std::ceil(cand.gap / (0.5 * grid.minSpacing)));
    bool inside = true;
    for (int i = 1; i < samples && inside; ++i)
    {
      const double t = static_cast<double>(i) / samples;
      std::int64_t index[3];
      for (int a = 0; a < 3; ++a)
      {
        // Whole-lattice mm rounded to the whole index (the single run's), then the mask's.
        index[a] = std::llround((end.centre[a] + t * (c[a] - end.centre[a])) / grid.sp[a]) -
                   grid.first_Whole[a];
      }
      inside = index[0] >= 0 && index[0] < grid.nx && index[1] >= 0 && index[1] < grid.ny &&
               index[2] >= 0 && index[2] < grid.nz &&
               grid.mask.test(
                 static_cast<std::uint64_t>(index[0] + grid.nx * (index[1] + grid.ny * index[2])));
    }
    if (!inside)
    {
      continue;
    }
    const double radius = end.radius_mm;
    const double cutoff =
      2.0 * (4.0 * radius + 2.0 * grid.bandWidth + minimumBranchLength * radius);
    if (skeletonDistance(out, { end.path, end.point }, { cand.path, cand.point }, cutoff, links) <=
        cutoff)
    {
      continue; // joined nearby already: not a ring left open
    }
    const auto linOf = [&](const std::array<std::int64_t, 3>& v)
    { return static_cast<std::uint32_t>(v[0] + grid.nx * (v[1] + grid.ny * v[2])); };
    std::vector<std::uint32_t> bridge = medialBridge(linOf(out.paths[end.path].voxels[end.point]),
      linOf(out.paths[cand.path].voxels[cand.point]),
      radius);
    Trace t;
    t.path = end.path;
    t.point = end.point;
    t.voxels.assign(bridge.rbegin(), bridge.rend()); // emitPath appends from the back
    tracer.emitPath(t, false, cand.path, cand.point);
    ++out.loops;
    link(out.junctions[out.junctions.size() - 2]);
    link(out.junctions.back());
    used[cand.end] = 1;
    if (target != ends.end())
    {
      used[static_cast<std::size_t>(target - ends.begin())] = 1;
    }
  }
}

} // namespace skeleton
} // namespace vtouch

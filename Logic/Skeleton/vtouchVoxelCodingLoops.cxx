// Voxel coding stage 7: loop closing where two SS fronts meet.
#include "vtouchVoxelCodingImpl.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <queue>
#include <unordered_map>

namespace vtouch
{
using P3Array = std::array<double, 3>;

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

void VoxelCoder::Impl::linkJunction(const RawJunction& j,
  std::unordered_multimap<std::uint64_t, std::pair<int, int>>& links) const
{
  const std::pair<int, int> child{ j.childPath,
    j.childTail ? static_cast<int>(out.paths[j.childPath].center_mm.size()) - 1 : 0 };
  const std::pair<int, int> parent{ j.parentPath, j.parentPoint };
  links.emplace(placeKey(child), parent);
  links.emplace(placeKey(parent), child);
}

namespace
{
struct FreeEnd
{
  int path = -1;
  int point = -1;         // the end point's index on its path
  P3Array centre{};       // mm
  P3Array outward{};      // unit: from a point about one radius in toward the end
  double radius_mm = 0.0; // the vessel's radius near the end
};

/// The radius of the vessel a path point lies in, also where the point is on a strand of noise
/// on the wall (whose own radius is about a voxel): the largest radius of the path within three
/// of them, plus `slack_mm`, of the point, grown three times.
double vesselRadiusNear(const RawSkeletonPath& path, int point, double slack_mm)
{
  const int n = static_cast<int>(path.center_mm.size());
  const P3Array& at = path.center_mm[point];
  double radius = path.radius_mm[point];
  for (int pass = 0; pass < 3; ++pass)
  {
    const double reach = 3.0 * radius + slack_mm;
    for (int step : { -1, 1 })
    {
      for (int i = point; i >= 0 && i < n; i += step)
      {
        const P3Array& c = path.center_mm[i];
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

/// A free end judged where the vessel is: the traced tip can be a strand of noise on the wall
/// (radius about one voxel, pointing into the wall), so the end is taken at its stem, the first
/// point in from the tip whose radius reaches 0.7 of the vessel's (vesselRadiusNear), with the
/// outward direction over about one radius further in. Empty when the path is too short or a
/// junction's point comes first.
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
    const P3Array& a = path.center_mm[i];
    const P3Array& b = path.center_mm[j];
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
  const P3Array& c = path.center_mm[inner];
  e.outward = {
    (e.centre[0] - c[0]) / length, (e.centre[1] - c[1]) / length, (e.centre[2] - c[2]) / length
  };
  return e;
}
} // namespace

void VoxelCoder::Impl::closeTracedLoops(std::size_t firstPath)
{
  const StageTimer timer{ *this, "loops" };
  // Junction links in both directions: (path, point) -> (path, point).
  std::unordered_multimap<std::uint64_t, std::pair<int, int>> links;
  const auto link = [&](const RawJunction& j) { linkJunction(j, links); };
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
        // Joined nearby already? Measured with the vessel's radius: the cluster can be a strand
        // of noise on the wall, whose own radius would take a second bridge across the same
        // meeting zone for a second loop.
        const double vessel = std::max({ radius,
          vesselRadiusNear(pa, sides[a].second, 2.0 * maxSpacing),
          vesselRadiusNear(pb, sides[b].second, 2.0 * maxSpacing) });
        const double nearby = std::max(
          cutoff, 2.0 * (2.0 * vessel + 2.0 * bandWidth + par.minimumBranchLength * vessel));
        if (skeletonDistance(sides[a], sides[b], nearby, links) <= nearby)
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

std::vector<std::uint32_t> VoxelCoder::Impl::medialBridge(std::uint32_t from,
  std::uint32_t to,
  double radius) const
{
  // Dijkstra over the vessel voxels within reach of the two ends; a step costs its length times
  // (radius / BS)^2, so the cheapest way keeps to the ridge of the BS code (the medial axis) and
  // follows a curved vessel instead of cutting its chord.
  const P3Array a = centerOf(from);
  const P3Array b = centerOf(to);
  const P3Array mid{ 0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1]), 0.5 * (a[2] + b[2]) };
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
    const P3Array cv = centerOf(v);
    forNeighbours(v,
      [&](std::uint64_t u, int, std::uint32_t ru)
      {
        const auto lin = static_cast<std::uint32_t>(u);
        const P3Array cu = centerOf(lin);
        if (distance(cu, mid) > reach)
        {
          return;
        }
        const double weight = radius / std::max(static_cast<double>(bs[ru]), 0.5 * minSpacing);
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

void VoxelCoder::Impl::joinFacingEnds(std::size_t firstPath)
{
  const StageTimer timer{ *this, "loops" };
  std::vector<char> attached; // per path point: a junction's parent point
  std::vector<FreeEnd> ends;
  for (std::size_t p = firstPath; p < out.paths.size(); ++p)
  {
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
            freeEndStem(path, static_cast<int>(p), tail, attached, maxSpacing))
      {
        ends.push_back(*e);
      }
    }
  }
  if (ends.size() < 2)
  {
    return;
  }
  std::unordered_multimap<std::uint64_t, std::pair<int, int>> links;
  const auto link = [&](const RawJunction& j) { linkJunction(j, links); };
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
  std::vector<std::array<P3Array, 2>> boxes(out.paths.size());
  for (std::size_t p = firstPath; p < out.paths.size(); ++p)
  {
    boxes[p] = { out.paths[p].center_mm.front(), out.paths[p].center_mm.front() };
    for (const P3Array& c : out.paths[p].center_mm)
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
    const FreeEnd& end = ends[e];
    const double reach = 4.0 * end.radius_mm + 2.0 * bandWidth;
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
        const P3Array& c = path.center_mm[i];
        const P3Array ab{ c[0] - end.centre[0], c[1] - end.centre[1], c[2] - end.centre[2] };
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
    const FreeEnd& end = ends[cand.end];
    const auto target = std::find_if(ends.begin(),
      ends.end(),
      [&](const FreeEnd& f) { return f.path == cand.path && f.point == cand.point; });
    if (used[cand.end] ||
        (target != ends.end() && used[static_cast<std::size_t>(target - ends.begin())]))
    {
      continue;
    }
    const P3Array& c = out.paths[cand.path].center_mm[cand.point];
    // The straight segment between the two lies in the vessel (samples half a voxel apart).
    const int samples = static_cast<int>(std::ceil(cand.gap / (0.5 * minSpacing)));
    bool inside = true;
    for (int i = 1; i < samples && inside; ++i)
    {
      const double t = static_cast<double>(i) / samples;
      std::int64_t index[3];
      for (int a = 0; a < 3; ++a)
      {
        index[a] = std::llround((end.centre[a] + t * (c[a] - end.centre[a])) / sp[a]);
      }
      inside = index[0] >= 0 && index[0] < nx && index[1] >= 0 && index[1] < ny && index[2] >= 0 &&
               index[2] < nz &&
               mask.test(static_cast<std::uint64_t>(index[0] + nx * (index[1] + ny * index[2])));
    }
    if (!inside)
    {
      continue;
    }
    const double radius = end.radius_mm;
    const double cutoff = 2.0 * (4.0 * radius + 2.0 * bandWidth + par.minimumBranchLength * radius);
    if (skeletonDistance({ end.path, end.point }, { cand.path, cand.point }, cutoff, links) <=
        cutoff)
    {
      continue; // joined nearby already: not a ring left open
    }
    const auto linOf = [&](const std::array<std::int64_t, 3>& v)
    { return static_cast<std::uint32_t>(v[0] + nx * (v[1] + ny * v[2])); };
    std::vector<std::uint32_t> bridge = medialBridge(linOf(out.paths[end.path].voxels[end.point]),
      linOf(out.paths[cand.path].voxels[cand.point]),
      radius);
    Trace t;
    t.path = end.path;
    t.point = end.point;
    t.voxels.assign(bridge.rbegin(), bridge.rend()); // emitPath appends from the back
    emitPath(t, false, cand.path, cand.point);
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
      // The vessel's radius there: the junction can be on a strand of noise on the wall.
      return junctionPoint != end &&
             stubLength(junctionPoint, end) <
               std::max(par.minimumBranchLength *
                          std::max(nearbyRadius(static_cast<int>(p), junctionPoint),
                            vesselRadiusNear(path, junctionPoint, 2.0 * maxSpacing)),
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

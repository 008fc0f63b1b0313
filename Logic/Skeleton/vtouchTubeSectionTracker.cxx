#include "vtouchTubeSectionTracker.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

namespace vtouch
{

namespace
{
constexpr double kPi = 3.14159265358979323846;
using Settings = TubeSectionTracker::Settings;

/// Ray lengths (voxels) of the section through `c` in the plane (u, v): the foreground's run from
/// c along u cos a + v sin a, + half a step; 0 when c is outside. Capped at cap_voxels.
void sectionRays(const SectionSampler& sampler,
  const Vec3& c,
  const Vec3& u,
  const Vec3& v,
  double cap_voxels,
  const Settings& s,
  std::vector<double>& rho)
{
  const double voxel = sampler.voxel_mm();
  const int n = std::max(8, s.rays);
  rho.assign(static_cast<std::size_t>(n), 0.0);
  if (!sampler.inside(c))
  {
    return;
  }
  const double step = s.rayStep_voxels * voxel;
  for (int k = 0; k < n; ++k)
  {
    const double a = 2.0 * kPi * k / n;
    const Vec3 dir = u * std::cos(a) + v * std::sin(a);
    rho[static_cast<std::size_t>(k)] =
      (sampler.runLength(c, dir, cap_voxels * voxel, step) + 0.5 * step) / voxel;
  }
}

double median(std::vector<double> x)
{
  if (x.empty())
  {
    return std::numeric_limits<double>::quiet_NaN();
  }
  const std::size_t m = x.size() / 2;
  std::nth_element(x.begin(), x.begin() + static_cast<std::ptrdiff_t>(m), x.end());
  const double hi = x[m];
  if (x.size() % 2 == 1)
  {
    return hi;
  }
  return 0.5 * (hi + *std::max_element(x.begin(), x.begin() + static_cast<std::ptrdiff_t>(m)));
}

double lowerQuartile(std::vector<double> x)
{
  if (x.empty())
  {
    return std::numeric_limits<double>::quiet_NaN();
  }
  const std::size_t q = x.size() / 4;
  std::nth_element(x.begin(), x.begin() + static_cast<std::ptrdiff_t>(q), x.end());
  return x[q];
}

/// Arcs of `on` around the circle, counting only arcs of >= 2 rays once single-ray gaps are
/// bridged (a lone ray is noise: one voxel of background noise inside a contact, or one ray
/// slipping between two voxels of the wall).
int arcCount(const std::vector<char>& on)
{
  const std::size_t n = on.size();
  std::vector<char> m(on);
  for (std::size_t k = 0; k < n; ++k)
  {
    if (!on[k] && on[(k + n - 1) % n] && on[(k + 1) % n])
    {
      m[k] = 1;
    }
  }
  std::vector<char> cleaned(m);
  for (std::size_t k = 0; k < n; ++k)
  {
    if (m[k] && !m[(k + n - 1) % n] && !m[(k + 1) % n])
    {
      cleaned[k] = 0;
    }
  }
  int arcs = 0;
  bool any = false;
  for (std::size_t k = 0; k < n; ++k)
  {
    any = any || cleaned[k];
    if (cleaned[k] && !cleaned[(k + n - 1) % n])
    {
      ++arcs;
    }
  }
  return any && arcs == 0 ? 1 : arcs; // all on: one arc around
}

/// The centre of the tube of radius r (voxels) in the section through p normal to t: the circle of
/// radius r fitted to the ends of the wall rays (ending within r + margin), re-taken from the new
/// centre up to four times. False when the section from the centre is not a tube touched at most
/// on one side (see the header).
bool centreOnTube(const SectionSampler& sampler,
  const Vec3& p,
  const Vec3& tangent,
  double r,
  const Settings& s,
  Vec3& centre)
{
  Vec3 t, u, v;
  SectionSampler::sectionBasis(tangent, t, u, v);
  const int n = std::max(8, s.rays);
  const double voxel = sampler.voxel_mm();
  const double cap = r + s.wallMargin_voxels + 3.0;
  std::vector<double> rho;
  Vec3 c = p;
  if (!sampler.inside(c))
  {
    // A thin tube's prediction can leave its lumen: start from the nearest foreground of the
    // section within r + 1 voxel (rings every half voxel, 16 directions).
    bool found = false;
    for (double ring = 0.5; !found && ring <= r + 1.0 + 1e-9; ring += 0.5)
    {
      for (int k = 0; !found && k < 16; ++k)
      {
        const double a = 2.0 * kPi * k / 16;
        const Vec3 q = p + (u * std::cos(a) + v * std::sin(a)) * (ring * voxel);
        if (sampler.inside(q))
        {
          c = q;
          found = true;
        }
      }
    }
    if (!found)
    {
      return false;
    }
  }
  for (int outer = 0; outer < 4; ++outer)
  {
    sectionRays(sampler, c, u, v, cap, s, rho);
    std::vector<std::array<double, 2>> wall;
    for (int k = 0; k < n; ++k)
    {
      const double rk = rho[static_cast<std::size_t>(k)];
      if (rk > 0.0 && rk <= r + s.wallMargin_voxels)
      {
        const double a = 2.0 * kPi * k / n;
        wall.push_back({ rk * std::cos(a), rk * std::sin(a) });
      }
    }
    if (static_cast<double>(wall.size()) < s.minimumWallFraction * n)
    {
      return false;
    }
    // Gauss-Newton for min sum (|w - x| - r)^2 over x in the plane (voxels, relative to c).
    double x[2] = { 0.0, 0.0 };
    for (int it = 0; it < 8; ++it)
    {
      const double radius = r;
      double h00 = 1e-6, h01 = 0.0, h11 = 1e-6, g0 = 0.0, g1 = 0.0;
      for (const auto& w : wall)
      {
        const double dx = x[0] - w[0], dy = x[1] - w[1];
        const double d = std::max(1e-9, std::hypot(dx, dy));
        const double j0 = dx / d, j1 = dy / d, res = d - radius;
        h00 += j0 * j0;
        h01 += j0 * j1;
        h11 += j1 * j1;
        g0 += j0 * res;
        g1 += j1 * res;
      }
      const double det = h00 * h11 - h01 * h01;
      if (!(std::abs(det) > 1e-12))
      {
        break;
      }
      const double s0 = -(h11 * g0 - h01 * g1) / det;
      const double s1 = -(h00 * g1 - h01 * g0) / det;
      x[0] += s0;
      x[1] += s1;
      if (std::hypot(s0, s1) < 1e-3)
      {
        break;
      }
    }
    const Vec3 moved = c + (u * x[0] + v * x[1]) * voxel;
    const bool settled = std::hypot(x[0], x[1]) < 0.05;
    c = moved;
    if (settled)
    {
      break;
    }
  }
  sectionRays(sampler, c, u, v, cap, s, rho);
  int wallRays = 0;
  std::vector<char> runsOn(static_cast<std::size_t>(n), 0);
  for (int k = 0; k < n; ++k)
  {
    const double rk = rho[static_cast<std::size_t>(k)];
    wallRays += std::abs(rk - r) <= s.wallMargin_voxels ? 1 : 0;
    runsOn[static_cast<std::size_t>(k)] = rk > r + s.wallMargin_voxels ? 1 : 0;
  }
  if (!sampler.inside(c) || static_cast<double>(wallRays) < s.minimumWallFraction * n ||
      arcCount(runsOn) > 1)
  {
    return false;
  }
  centre = c;
  return true;
}

/// A junction's zone: sections within it are legitimately not a single tube's.
struct Zone
{
  Vec3 centre;
  double radius;
  double vesselRadius = 0.0; ///< the larger radius there (mm)
};

bool inZone(const std::vector<Zone>& zones, const Vec3& p)
{
  for (const Zone& z : zones)
  {
    if ((p - z.centre).norm() <= z.radius)
    {
      return true;
    }
  }
  return false;
}

struct Target
{
  int index;
  Vec3 position;
};

struct Track
{
  std::vector<Vec3> centres; ///< from the start's centre on (the start itself first)
  int hit = -1;              ///< the target reached, or -1
};

/// Follows the tube of radius r (voxels) from `start` along `direction` (see the header).
Track follow(const SectionSampler& sampler,
  const Vec3& start,
  const Vec3& direction,
  double r,
  const std::vector<Target>& targets,
  const std::vector<Zone>& zones,
  double maximumLength_mm,
  const Settings& s)
{
  const double voxel = sampler.voxel_mm();
  const double step = s.trackStep_voxels * voxel;
  const double reach = std::max(s.targetReach_voxels, 0.5 * r) * voxel;
  const int lag = std::max(1, static_cast<int>(std::lround(2.0 / s.trackStep_voxels)));
  Track track;
  track.centres.push_back(start);
  Vec3 t = direction * (1.0 / std::max(1e-12, direction.norm()));
  Vec3 c = start;
  double length = 0.0;
  // Coasting: where the section is not a tube's for a step (a branch leaves, a junction), the
  // track goes on straight, through a junction's zone and up to max(1 voxel, r) beyond, and
  // re-centres after it; it ends where the section stays un-tube-like, back at its last centred
  // point.
  const double coastLimit = std::max(1.0, r) * voxel;
  double coasted = 0.0;
  std::size_t lastCentred = 0;
  double lengthAtLastCentred = 0.0;
  while (length < maximumLength_mm)
  {
    const Vec3 predicted = c + t * step;
    Vec3 next;
    const bool fitted = centreOnTube(sampler, predicted, t, r, s, next) &&
                        (next - predicted).norm() <= (0.5 * r + s.maximumShift_voxels) * voxel;
    if (!fitted)
    {
      if ((coasted + step > coastLimit + 1e-9 && !inZone(zones, predicted)) ||
          !sampler.inside(predicted))
      {
        track.centres.resize(lastCentred + 1);
        length = lengthAtLastCentred;
        break;
      }
      coasted = inZone(zones, predicted) ? 0.0 : coasted + step;
      next = predicted;
    }
    else
    {
      coasted = 0.0;
      const Vec3 back = track.centres[static_cast<std::size_t>(
        std::max(0, static_cast<int>(track.centres.size()) - lag))];
      Vec3 heading = next - back;
      const double hn = heading.norm();
      if (hn > 1e-9)
      {
        heading = heading * (1.0 / hn);
        if (heading.dot(t) < s.maximumTurnCosine)
        {
          track.centres.resize(lastCentred + 1);
          break;
        }
        t = heading;
      }
    }
    length += (next - c).norm();
    c = next;
    track.centres.push_back(c);
    if (fitted)
    {
      lastCentred = track.centres.size() - 1;
      lengthAtLastCentred = length;
    }
    double best = reach;
    for (const Target& target : targets)
    {
      const double d = (target.position - c).norm();
      if (d <= best)
      {
        best = d;
        track.hit = target.index;
      }
    }
    if (track.hit >= 0)
    {
      break;
    }
  }
  if (track.hit < 0 && track.centres.size() > lastCentred + 1)
  {
    track.centres.resize(lastCentred + 1); // ran out of length while coasting
  }
  (void)length;
  return track;
}

/// Points every voxel along the polyline from `from` through `via` to `to` (both ends excluded;
/// `to` may be omitted: then up to the polyline's last point, included).
std::vector<Vec3> resampled(const Vec3& from,
  const std::vector<Vec3>& via,
  const Vec3* to,
  double spacing_mm)
{
  std::vector<Vec3> line{ from };
  line.insert(line.end(), via.begin(), via.end());
  if (to)
  {
    line.push_back(*to);
  }
  double total = 0.0;
  for (std::size_t i = 1; i < line.size(); ++i)
  {
    total += (line[i] - line[i - 1]).norm();
  }
  std::vector<Vec3> out;
  if (total <= 1e-9)
  {
    return out;
  }
  // Equal steps no longer than the spacing, so the ends are not crowded.
  const int pieces = std::max(1, static_cast<int>(std::ceil(total / spacing_mm - 1e-9)));
  const double stepLength = total / pieces;
  std::size_t seg = 1;
  double before = 0.0; // arc length at line[seg - 1]
  for (int q = 1; q <= pieces; ++q)
  {
    if (q == pieces && to)
    {
      break; // `to` itself stays the path's own point
    }
    const double at = q * stepLength;
    while (seg + 1 < line.size() && before + (line[seg] - line[seg - 1]).norm() < at)
    {
      before += (line[seg] - line[seg - 1]).norm();
      ++seg;
    }
    const double len = (line[seg] - line[seg - 1]).norm();
    const double f = len > 1e-12 ? std::clamp((at - before) / len, 0.0, 1.0) : 1.0;
    out.push_back(line[seg - 1] + (line[seg] - line[seg - 1]) * f);
  }
  return out;
}

struct Plan
{
  int first; ///< first point replaced
  int last;  ///< last point replaced (inclusive); may be n - 1 (a free tail) or first - 1
  std::vector<Vec3> positions;
  double radiusFrom_mm, radiusTo_mm;
  bool remove = false; ///< clutter: the points go (the path is split there or its end trimmed)
  std::vector<Vec3> before{}; ///< remove: the tube's track kept before the cut
  std::vector<Vec3> after{};  ///< remove: the tube's track kept after the cut
};

struct PointSection
{
  double s = 0.0;     ///< median ray (voxels)
  bool round = false; ///< longest ray within the round-shape bound
  bool zone = false;  ///< near a junction: not judged
  bool clean = false;
};

/// Removes the point ranges `cuts[path]` (sorted, disjoint, inclusive) from the paths: each path
/// is split into the pieces between them (the first piece keeps the path's id and head, the last
/// its tail; pieces of fewer than 2 points go); paths joined to a removed point, or to a piece
/// that goes, are detached (that end becomes free). Returns the number of junctions detached.
int cutStretches(QSkeleton& skeleton,
  const std::vector<std::vector<std::pair<int, int>>>& cuts,
  std::vector<std::vector<TubeSectionTracker::Section>>& sections)
{
  using Section = TubeSectionTracker::Section;
  const std::size_t originalPaths = skeleton.paths.size();
  // Where each original point goes: (path, index) or (-1, -1).
  std::vector<std::vector<std::pair<int, int>>> where(originalPaths);
  bool any = false;
  for (std::size_t pi = 0; pi < originalPaths; ++pi)
  {
    const int n = static_cast<int>(skeleton.paths[pi].points.size());
    where[pi].resize(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i)
    {
      where[pi][static_cast<std::size_t>(i)] = { static_cast<int>(pi), i };
    }
    any = any || !cuts[pi].empty();
  }
  if (!any)
  {
    return 0;
  }
  for (std::size_t pi = 0; pi < originalPaths; ++pi)
  {
    if (cuts[pi].empty())
    {
      continue;
    }
    SkeletonPath original = std::move(skeleton.paths[pi]);
    std::vector<Section> originalSections = std::move(sections[pi]);
    const int n = static_cast<int>(original.points.size());
    std::vector<char> removed(static_cast<std::size_t>(n), 0);
    for (const auto& [first, last] : cuts[pi])
    {
      for (int i = std::max(0, first); i <= std::min(n - 1, last); ++i)
      {
        removed[static_cast<std::size_t>(i)] = 1;
      }
    }
    // Pieces of consecutive kept points.
    std::vector<std::pair<int, int>> pieces;
    for (int i = 0; i < n;)
    {
      if (removed[static_cast<std::size_t>(i)])
      {
        ++i;
        continue;
      }
      int e = i;
      while (e + 1 < n && !removed[static_cast<std::size_t>(e + 1)])
      {
        ++e;
      }
      if (e - i + 1 >= 2)
      {
        pieces.emplace_back(i, e);
      }
      i = e + 1;
    }
    for (auto& w : where[pi])
    {
      w = { -1, -1 };
    }
    skeleton.paths[pi] = SkeletonPath{};
    skeleton.paths[pi].id = static_cast<int>(pi);
    sections[pi].clear();
    for (std::size_t c = 0; c < pieces.size(); ++c)
    {
      const auto [first, last] = pieces[c];
      const int id = c == 0 ? static_cast<int>(pi) : static_cast<int>(skeleton.paths.size());
      SkeletonPath piece;
      piece.id = id;
      piece.head.junction = first == 0 ? original.head.junction : -1;
      piece.tail.junction = last == n - 1 ? original.tail.junction : -1;
      piece.points.assign(original.points.begin() + first, original.points.begin() + last + 1);
      std::vector<Section> st(
        originalSections.begin() + first, originalSections.begin() + last + 1);
      for (int i = first; i <= last; ++i)
      {
        where[pi][static_cast<std::size_t>(i)] = { id, i - first };
      }
      if (c == 0)
      {
        skeleton.paths[pi] = std::move(piece);
        sections[pi] = std::move(st);
      }
      else
      {
        skeleton.paths.push_back(std::move(piece));
        sections.push_back(std::move(st));
      }
    }
    if (pieces.empty())
    {
      // Nothing of the path stays: an empty placeholder, dropped below.
      skeleton.paths[pi].head.junction = skeleton.paths[pi].tail.junction = -1;
    }
  }
  // Junctions: re-point parents and children; detach those whose parent point or child end went.
  std::vector<Junction> kept;
  std::vector<int> newIndex(skeleton.junctions.size(), -1);
  int detached = 0;
  for (std::size_t ji = 0; ji < skeleton.junctions.size(); ++ji)
  {
    Junction jn = skeleton.junctions[ji];
    const auto parent =
      where[static_cast<std::size_t>(jn.parentPath)][static_cast<std::size_t>(jn.parentPoint)];
    // The child's end: its head (index 0) or its tail (last index) of the original path.
    const std::size_t childPath = static_cast<std::size_t>(jn.childPath);
    const int childIndex =
      jn.childEnd == Junction::End::Head ? 0 : static_cast<int>(where[childPath].size()) - 1;
    const auto child = childIndex >= 0 ? where[childPath][static_cast<std::size_t>(childIndex)]
                                       : std::pair<int, int>{ -1, -1 };
    if (parent.first < 0 || child.first < 0)
    {
      ++detached;
      continue;
    }
    jn.parentPath = parent.first;
    jn.parentPoint = parent.second;
    jn.childPath = child.first;
    newIndex[ji] = static_cast<int>(kept.size());
    kept.push_back(jn);
  }
  for (SkeletonPath& path : skeleton.paths)
  {
    for (PathEnd* end : { &path.head, &path.tail })
    {
      end->junction = end->junction >= 0 ? newIndex[static_cast<std::size_t>(end->junction)] : -1;
    }
  }
  skeleton.junctions = std::move(kept);
  // A child whose junction stayed: its end refers to the junction's new index (set above). Drop
  // paths that lost every point, and pieces left on the clutter: joined to nothing (both ends
  // free, no path joins them) and without a run of 3 clean or re-traced sections (renumbering
  // ids and references).
  std::vector<char> carries(skeleton.paths.size(), 0);
  for (const Junction& jn : skeleton.junctions)
  {
    carries[static_cast<std::size_t>(jn.parentPath)] = 1;
  }
  const auto orphan = [&](std::size_t pi)
  {
    const SkeletonPath& path = skeleton.paths[pi];
    if (path.head.junction >= 0 || path.tail.junction >= 0 || carries[pi])
    {
      return false;
    }
    int run = 0;
    for (const Section x : sections[pi])
    {
      run = x == Section::Clean || x == Section::Retraced ? run + 1 : 0;
      if (run >= 3)
      {
        return false;
      }
    }
    return true;
  };
  std::vector<int> newPath(skeleton.paths.size(), -1);
  std::vector<SkeletonPath> paths;
  std::vector<std::vector<Section>> newSections;
  for (std::size_t pi = 0; pi < skeleton.paths.size(); ++pi)
  {
    if (skeleton.paths[pi].points.size() >= 2 &&
        !(pi < originalPaths ? !cuts[pi].empty() && orphan(pi) : orphan(pi)))
    {
      newPath[pi] = static_cast<int>(paths.size());
      paths.push_back(std::move(skeleton.paths[pi]));
      paths.back().id = newPath[pi];
      newSections.push_back(std::move(sections[pi]));
    }
  }
  for (Junction& jn : skeleton.junctions)
  {
    jn.parentPath = newPath[static_cast<std::size_t>(jn.parentPath)];
    jn.childPath = newPath[static_cast<std::size_t>(jn.childPath)];
  }
  skeleton.paths = std::move(paths);
  sections = std::move(newSections);
  // Labels: free ends, and junction points (only where a junction still is).
  for (SkeletonPath& path : skeleton.paths)
  {
    for (SkeletonPoint& q : path.points)
    {
      if (q.label == PointLabel::Bifurcation)
      {
        q.label = PointLabel::Ordinary;
      }
    }
    path.points.front().label =
      path.head.junction >= 0 ? PointLabel::Bifurcation : PointLabel::EndPoint;
    path.points.back().label =
      path.tail.junction >= 0 ? PointLabel::Bifurcation : PointLabel::EndPoint;
  }
  for (const Junction& jn : skeleton.junctions)
  {
    skeleton.paths[static_cast<std::size_t>(jn.parentPath)]
      .points[static_cast<std::size_t>(jn.parentPoint)]
      .label = PointLabel::Bifurcation;
  }
  return detached;
}

} // namespace

TubeSectionTracker::Result TubeSectionTracker::track(QSkeleton& skeleton,
  const SectionForeground& foreground,
  const SectionGeometry& geometry,
  const Settings& s)
{
  Result result;
  const SectionSampler sampler(foreground, geometry);
  const double voxel = sampler.voxel_mm();
  const double largestSpacing =
    std::max({ geometry.spacing_mm[0], geometry.spacing_mm[1], geometry.spacing_mm[2] });

  // Junction zones (as TubeLikenessPruner's) and each path's attachment points.
  std::vector<Zone> zones;
  std::vector<std::vector<int>> attached(skeleton.paths.size());
  for (const Junction& j : skeleton.junctions)
  {
    const SkeletonPath& parent = skeleton.paths[static_cast<std::size_t>(j.parentPath)];
    const SkeletonPoint& q = parent.points[static_cast<std::size_t>(j.parentPoint)];
    const SkeletonPath& child = skeleton.paths[static_cast<std::size_t>(j.childPath)];
    const SkeletonPoint& end =
      j.childEnd == Junction::End::Head ? child.points.front() : child.points.back();
    zones.push_back({ q.position_World_mm,
      s.junctionZoneRadii * std::max(q.radius_mm, end.radius_mm) +
        s.junctionZoneMargin_voxels * voxel,
      std::max(q.radius_mm, end.radius_mm) });
    attached[static_cast<std::size_t>(j.parentPath)].push_back(j.parentPoint);
  }

  std::vector<double> rho;
  std::vector<std::vector<std::pair<int, int>>> clutterCuts(skeleton.paths.size());
  // Phase 1: every path's sections and which of them are clean.
  struct PathJudgement
  {
    std::vector<PointSection> sec;
    std::vector<double> arc;          ///< arc length from the head (voxels)
    std::vector<int> cuts;            ///< the path's ends and the points where others join
    std::vector<int> vessel;          ///< piece between two cuts each point lies in
    std::vector<double> vesselMedian; ///< per piece: the median s of its round sections
    bool tube = false;                ///< has a clean run of >= 3 points: a vessel
  };
  std::vector<PathJudgement> judged(skeleton.paths.size());
  for (std::size_t pi = 0; pi < skeleton.paths.size(); ++pi)
  {
    const SkeletonPath& path = skeleton.paths[pi];
    const int n = static_cast<int>(path.points.size());
    PathJudgement& pj = judged[pi];
    auto& sec = pj.sec;
    auto& arc = pj.arc;
    auto& cuts = pj.cuts;
    auto& vessel = pj.vessel;
    auto& vesselMedian = pj.vesselMedian;
    // Sections.
    sec.resize(static_cast<std::size_t>(n));
    arc.assign(static_cast<std::size_t>(n), 0.0);
    for (int i = 0; i < n; ++i)
    {
      const SkeletonPoint& q = path.points[static_cast<std::size_t>(i)];
      if (i > 0)
      {
        arc[static_cast<std::size_t>(i)] =
          arc[static_cast<std::size_t>(i - 1)] +
          (q.position_World_mm - path.points[static_cast<std::size_t>(i - 1)].position_World_mm)
              .norm() /
            voxel;
      }
      PointSection& ps = sec[static_cast<std::size_t>(i)];
      for (const Zone& z : zones)
      {
        ps.zone = ps.zone || (q.position_World_mm - z.centre).norm() <= z.radius;
      }
      Vec3 t, u, v;
      SectionSampler::sectionBasis(q.tangent_World, t, u, v);
      const double R = std::max(0.5, q.radius_mm / voxel);
      sectionRays(sampler, q.position_World_mm, u, v, 2.0 * R + 4.0, s, rho);
      ps.s = median(rho);
      const double longest = *std::max_element(rho.begin(), rho.end());
      ps.round = ps.s > 0.0 &&
                 longest <= ps.s + std::max(s.roundExcess_voxels, s.roundExcessFraction * ps.s);
    }
    // Vessels: the pieces of the path between the points where other paths join it.
    cuts = { 0, std::max(0, n - 1) };
    cuts.insert(cuts.end(), attached[pi].begin(), attached[pi].end());
    std::sort(cuts.begin(), cuts.end());
    cuts.erase(std::unique(cuts.begin(), cuts.end()), cuts.end());
    vessel.assign(static_cast<std::size_t>(n), 0);
    for (std::size_t c = 0; c + 1 < cuts.size(); ++c)
    {
      for (int i = cuts[c]; i <= cuts[c + 1]; ++i)
      {
        vessel[static_cast<std::size_t>(i)] = static_cast<int>(c);
      }
    }
    // The tube's radius along each vessel: lower quartile of the round sections' s in a window.
    vesselMedian.assign(cuts.size(), 0.0);
    for (std::size_t c = 0; c + 1 < cuts.size(); ++c)
    {
      std::vector<double> x;
      for (int i = cuts[c]; i <= cuts[c + 1]; ++i)
      {
        if (sec[static_cast<std::size_t>(i)].round)
        {
          x.push_back(sec[static_cast<std::size_t>(i)].s);
        }
      }
      vesselMedian[c] = x.empty() ? 0.0 : median(x);
    }
    const auto window = [&](int i)
    {
      const int c = vessel[static_cast<std::size_t>(i)];
      return std::max(s.radiusWindow_voxels, s.radiusWindowRadii * vesselMedian[c]);
    };
    for (int i = 0; i < n; ++i)
    {
      PointSection& ps = sec[static_cast<std::size_t>(i)];
      if (ps.zone)
      {
        continue;
      }
      ++result.pointsJudged;
      const double w = window(i);
      std::vector<double> x;
      for (int j = 0; j < n; ++j)
      {
        // Across the points where other paths join: the coder joins paths on the clutter to
        // the vessel inside it, and a vessel's piece between two such points is all clutter.
        if (sec[static_cast<std::size_t>(j)].round &&
            std::abs(arc[static_cast<std::size_t>(j)] - arc[static_cast<std::size_t>(i)]) <= w)
        {
          x.push_back(sec[static_cast<std::size_t>(j)].s);
        }
      }
      const double tau = lowerQuartile(x);
      ps.clean = ps.round && std::isfinite(tau) &&
                 ps.s <= tau + std::max(s.radiusExcess_voxels, s.radiusExcessFraction * tau);
      result.pointsNotClean += ps.clean ? 0 : 1;
    }
    for (int i = 0, run = 0; i < n && !pj.tube; ++i)
    {
      run = sec[static_cast<std::size_t>(i)].clean ? run + 1 : 0;
      pj.tube = run >= s.minimumAnchorPoints;
    }
  }
  // Junctions between two vessels (both paths have clean runs: a real bifurcation, not a path
  // the coder drew on clutter joined to a vessel or to another such path), as the points of each
  // path where one is: a stretch that reaches one holds the junction's elongated sections (the
  // other vessel's lumen, over about a radius of the larger vessel) and is never clutter.
  std::vector<std::vector<int>> realJunctionPoints(skeleton.paths.size());
  for (const Junction& jn : skeleton.junctions)
  {
    if (judged[static_cast<std::size_t>(jn.parentPath)].tube &&
        judged[static_cast<std::size_t>(jn.childPath)].tube)
    {
      realJunctionPoints[static_cast<std::size_t>(jn.parentPath)].push_back(jn.parentPoint);
      const SkeletonPath& child = skeleton.paths[static_cast<std::size_t>(jn.childPath)];
      realJunctionPoints[static_cast<std::size_t>(jn.childPath)].push_back(
        jn.childEnd == Junction::End::Head ? 0 : static_cast<int>(child.points.size()) - 1);
    }
  }

  // Phase 2: the stretches of each path.
  result.sections.resize(skeleton.paths.size());
  for (std::size_t pi = 0; pi < skeleton.paths.size(); ++pi)
  {
    SkeletonPath& path = skeleton.paths[pi];
    const int n = static_cast<int>(path.points.size());
    auto& status = result.sections[pi];
    status.assign(static_cast<std::size_t>(n), Section::Junction);
    if (n < 3)
    {
      continue;
    }
    PathJudgement& pj = judged[pi];
    auto& sec = pj.sec;
    auto& arc = pj.arc;
    auto& vessel = pj.vessel;
    auto& vesselMedian = pj.vesselMedian;
    const auto window = [&](int i)
    {
      const int c = vessel[static_cast<std::size_t>(i)];
      return std::max(s.radiusWindow_voxels, s.radiusWindowRadii * vesselMedian[c]);
    };
    const auto inWindow = [&](int i, int j, double w)
    {
      return vessel[static_cast<std::size_t>(j)] == vessel[static_cast<std::size_t>(i)] &&
             std::abs(arc[static_cast<std::size_t>(j)] - arc[static_cast<std::size_t>(i)]) <= w;
    };
    // Anchors: the clean points, and an end attached to another path (the junction stays).
    for (int i = 0; i < n; ++i)
    {
      const PointSection& ps = sec[static_cast<std::size_t>(i)];
      status[static_cast<std::size_t>(i)] =
        ps.zone ? Section::Junction : (ps.clean ? Section::Clean : Section::NotClean);
    }
    const auto anchor = [&](int i)
    {
      return sec[static_cast<std::size_t>(i)].clean || (i == 0 && path.head.junction >= 0) ||
             (i == n - 1 && path.tail.junction >= 0);
    };
    // The tube's radius for a stretch: median s of the clean points on one side, within the
    // window, of the anchor's vessel (of any vessel when that has none); NaN (no track) when
    // fewer than 3 are clean there: a lone round section amid clutter is no vessel to follow.
    const auto tubeRadius = [&](int from, int towards)
    {
      const double w = window(from);
      for (const bool sameVessel : { true, false })
      {
        std::vector<double> x;
        for (int j = 0; j < n; ++j)
        {
          const bool side = towards > from ? j <= from : j >= from;
          const bool near = sameVessel ? inWindow(from, j, w)
                                       : std::abs(arc[static_cast<std::size_t>(j)] -
                                                  arc[static_cast<std::size_t>(from)]) <= w;
          if (side && near && sec[static_cast<std::size_t>(j)].clean)
          {
            x.push_back(sec[static_cast<std::size_t>(j)].s);
          }
        }
        if (static_cast<int>(x.size()) >= s.minimumAnchorPoints)
        {
          return median(x);
        }
      }
      return std::numeric_limits<double>::quiet_NaN();
    };
    // The direction a track leaves an anchor in: the chord from the path's point about two voxels
    // (or a radius) behind it, toward the stretch (`sign` +1: toward higher indices). The chord
    // of the clean side, not the smoothed tangent: smoothing bends it toward the stretch.
    const auto heading = [&](int from, int sign)
    {
      const double back = std::max(2.0, sec[static_cast<std::size_t>(from)].s);
      int q = from;
      while (
        q - sign >= 0 && q - sign < n &&
        std::abs(arc[static_cast<std::size_t>(q)] - arc[static_cast<std::size_t>(from)]) < back)
      {
        q -= sign;
      }
      const Vec3 chord = path.points[static_cast<std::size_t>(from)].position_World_mm -
                         path.points[static_cast<std::size_t>(q)].position_World_mm;
      const Vec3 tangent = path.points[static_cast<std::size_t>(from)].tangent_World * sign;
      return chord.norm() > 0.5 * voxel ? chord : tangent;
    };
    const double pathMedianRadius = [&]
    {
      std::vector<double> x;
      for (const SkeletonPoint& q : path.points)
      {
        x.push_back(q.radius_mm);
      }
      return median(x);
    }();

    std::vector<Plan> plans;
    // Stretches: runs of points between anchors that hold a judged point that is not clean.
    // Junction zones inside a run are tracked through: the coder joined paths that run on the
    // clutter to this one there; they are re-attached to the track.
    int j = 0;
    while (j < n)
    {
      if (anchor(j))
      {
        ++j;
        continue;
      }
      int k = j;
      bool judgedNotClean = false;
      while (k < n && !anchor(k))
      {
        judgedNotClean = judgedNotClean || !sec[static_cast<std::size_t>(k)].zone;
        ++k;
      }
      if (!judgedNotClean)
      {
        j = k;
        continue; // a junction's zone between clean points: the coder's junction stays
      }
      ++result.stretches;
      const std::size_t plansBefore = plans.size();
      Track forwardTrack, backwardTrack; // of a stretch between two anchors
      double rBackward = 0.0;
      const bool freeHead = j == 0 && path.head.junction < 0;
      const bool freeTail = k == n && path.tail.junction < 0;
      const double stretchLength = (arc[static_cast<std::size_t>(std::min(k, n - 1))] -
                                     arc[static_cast<std::size_t>(std::max(j - 1, 0))]) *
                                   voxel;
      const double maxLength = s.maximumTrackFactor * stretchLength + 4.0 * voxel;
      if (j >= 1 && k <= n - 1)
      {
        // Between two anchors of the path: forward from A, else backward from B.
        const int a = j - 1, b = k;
        bool done = false;
        const double rForward = tubeRadius(a, b);
        if (std::isfinite(rForward) && rForward > 0.0)
        {
          std::vector<Target> targets;
          for (int q = k; q < n; ++q)
          {
            if (anchor(q))
            {
              targets.push_back({ q, path.points[static_cast<std::size_t>(q)].position_World_mm });
            }
          }
          const Track tr = follow(sampler,
            path.points[static_cast<std::size_t>(a)].position_World_mm,
            heading(a, +1),
            rForward,
            targets,
            zones,
            maxLength,
            s);
          forwardTrack = tr;
          if (tr.hit >= 0)
          {
            const Vec3 to = path.points[static_cast<std::size_t>(tr.hit)].position_World_mm;
            std::vector<Vec3> via(tr.centres.begin() + 1, tr.centres.end());
            plans.push_back({ a + 1,
              tr.hit - 1,
              resampled(
                path.points[static_cast<std::size_t>(a)].position_World_mm, via, &to, voxel),
              path.points[static_cast<std::size_t>(a)].radius_mm,
              path.points[static_cast<std::size_t>(tr.hit)].radius_mm });
            done = true;
          }
        }
        rBackward = done ? 0.0 : tubeRadius(b, a);
        if (!done && std::isfinite(rBackward) && rBackward > 0.0)
        {
          std::vector<Target> targets;
          for (int q = j - 1; q >= 0; --q)
          {
            if (anchor(q))
            {
              targets.push_back({ q, path.points[static_cast<std::size_t>(q)].position_World_mm });
            }
          }
          const Track tr = follow(sampler,
            path.points[static_cast<std::size_t>(b)].position_World_mm,
            heading(b, -1),
            rBackward,
            targets,
            zones,
            maxLength,
            s);
          backwardTrack = tr;
          if (tr.hit >= 0)
          {
            const Vec3 to = path.points[static_cast<std::size_t>(b)].position_World_mm;
            std::vector<Vec3> via(tr.centres.rbegin(), tr.centres.rend() - 1);
            plans.push_back({ tr.hit + 1,
              b - 1,
              resampled(
                path.points[static_cast<std::size_t>(tr.hit)].position_World_mm, via, &to, voxel),
              path.points[static_cast<std::size_t>(tr.hit)].radius_mm,
              path.points[static_cast<std::size_t>(b)].radius_mm });
            done = true;
          }
        }
        result.stretchesTracked += done ? 1 : 0;
      }
      else if (freeTail && j >= 1)
      {
        const int a = j - 1;
        const double r = tubeRadius(a, n - 1);
        if (std::isfinite(r) && r > 0.0)
        {
          const Track tr = follow(sampler,
            path.points[static_cast<std::size_t>(a)].position_World_mm,
            heading(a, +1),
            r,
            {},
            zones,
            stretchLength + voxel,
            s);
          if (tr.centres.size() > 1)
          {
            std::vector<Vec3> via(tr.centres.begin() + 1, tr.centres.end());
            const double R = path.points[static_cast<std::size_t>(a)].radius_mm;
            plans.push_back({ a + 1,
              n - 1,
              resampled(
                path.points[static_cast<std::size_t>(a)].position_World_mm, via, nullptr, voxel),
              R,
              R });
            result.stretchesTracked += 1;
          }
        }
      }
      else if (freeHead && k <= n - 1)
      {
        const int b = k;
        const double r = tubeRadius(b, 0);
        if (std::isfinite(r) && r > 0.0)
        {
          const Track tr = follow(sampler,
            path.points[static_cast<std::size_t>(b)].position_World_mm,
            heading(b, -1),
            r,
            {},
            zones,
            stretchLength + voxel,
            s);
          if (tr.centres.size() > 1)
          {
            std::vector<Vec3> via(tr.centres.begin() + 1, tr.centres.end());
            std::vector<Vec3> pts = resampled(
              path.points[static_cast<std::size_t>(b)].position_World_mm, via, nullptr, voxel);
            std::reverse(pts.begin(), pts.end());
            const double R = path.points[static_cast<std::size_t>(b)].radius_mm;
            plans.push_back({ 0, b - 1, pts, R, R });
            result.stretchesTracked += 1;
          }
        }
      }
      if (plans.size() == plansBefore)
      {
        // Not re-traced. Clutter when its sections are wide (a plate's or a blob's, not a thin
        // vessel's noisy wall) and either mostly not round (a plate's band) or wider than the
        // tube it left (a blob), over more than the structure's diameter + 2 voxels: a junction's
        // elongated sections reach about a radius of the larger vessel on either side of it,
        // and no more.
        std::vector<double> widths;
        int notRound = 0;
        for (int q = j; q < k; ++q)
        {
          widths.push_back(sec[static_cast<std::size_t>(q)].s);
          notRound += sec[static_cast<std::size_t>(q)].round ? 0 : 1;
        }
        const double width = median(widths);
        const double length = (arc[static_cast<std::size_t>(std::min(k, n - 1))] -
                               arc[static_cast<std::size_t>(std::max(j - 1, 0))]);
        // The tube it left: the clean points' radius on either side (NaN at a free end).
        double tube = std::numeric_limits<double>::quiet_NaN();
        for (const double r :
          { j >= 1 ? tubeRadius(j - 1, k) : tube, k <= n - 1 ? tubeRadius(k, j - 1) : tube })
        {
          tube = std::isfinite(r) && !(r >= tube) ? r : tube; // the smaller one
        }
        const bool wider = std::isfinite(tube) && width > tube + std::max(s.radiusExcess_voxels,
                                                                   s.radiusExcessFraction * tube);
        bool nearJunction = false;
        for (const int q : realJunctionPoints[pi])
        {
          nearJunction = nearJunction || (q >= j - 1 && q <= k);
        }
        if (!nearJunction && k - j >= s.clutterMinimumPoints && (2 * notRound >= k - j || wider) &&
            width >= s.clutterMinimumWidth_voxels && length > width + 2.0)
        {
          Plan cut;
          cut.first = j;
          cut.last = k - 1;
          cut.radiusFrom_mm = path.points[static_cast<std::size_t>(std::max(j - 1, 0))].radius_mm;
          cut.radiusTo_mm = path.points[static_cast<std::size_t>(std::min(k, n - 1))].radius_mm;
          cut.remove = true;
          // Where a track from an anchor followed the tube on beyond a junction's reach (the
          // coder's path left the tube for the clutter), the tube's track stays: the piece
          // before the cut ends, and the piece after it starts, where the tube stops.
          const auto trackLength = [](const Track& tr)
          {
            double l = 0.0;
            for (std::size_t q = 1; q < tr.centres.size(); ++q)
            {
              l += (tr.centres[q] - tr.centres[q - 1]).norm();
            }
            return l;
          };
          if (j >= 1 && forwardTrack.centres.size() > 1 &&
              trackLength(forwardTrack) > 2.0 * (tubeRadius(j - 1, k) + 1.0) * voxel)
          {
            cut.before = resampled(forwardTrack.centres.front(),
              std::vector<Vec3>(forwardTrack.centres.begin() + 1, forwardTrack.centres.end()),
              nullptr,
              voxel);
          }
          if (k <= n - 1 && backwardTrack.centres.size() > 1 && std::isfinite(rBackward) &&
              trackLength(backwardTrack) > 2.0 * (rBackward + 1.0) * voxel)
          {
            cut.after = resampled(backwardTrack.centres.front(),
              std::vector<Vec3>(backwardTrack.centres.begin() + 1, backwardTrack.centres.end()),
              nullptr,
              voxel);
            std::reverse(cut.after.begin(), cut.after.end());
          }
          plans.push_back(std::move(cut));
          ++result.stretchesCut;
        }
      }
      j = k;
    }
    if (!plans.empty())
    {
      // Non-overlapping plans, applied from the last to the first (indices before stay valid).
      std::sort(
        plans.begin(), plans.end(), [](const Plan& x, const Plan& y) { return x.first < y.first; });
      std::vector<Plan> kept;
      for (Plan& p : plans)
      {
        if (kept.empty() || p.first > kept.back().last)
        {
          kept.push_back(std::move(p));
        }
      }
      std::vector<std::pair<int, int>> changed; // new index ranges [first, last] of replaced points
      std::vector<std::pair<int, int>> clutter; // new index ranges of clutter stretches to cut
      for (auto it = kept.rbegin(); it != kept.rend(); ++it)
      {
        const Plan& p = *it;
        const int removed = p.last - p.first + 1;
        // A clutter cut: the kept tracks on either side and one point between them that goes
        // (below, after the re-tracing), with whatever joined the clutter.
        std::vector<Vec3> positions = p.positions;
        int dummy = -1;
        if (p.remove)
        {
          positions = p.before;
          dummy = static_cast<int>(positions.size());
          positions.push_back(path.points[static_cast<std::size_t>(p.first)].position_World_mm);
          positions.insert(positions.end(), p.after.begin(), p.after.end());
        }
        const int added = static_cast<int>(positions.size());
        std::vector<SkeletonPoint> fresh(static_cast<std::size_t>(added));
        const double count = static_cast<double>(added + 1);
        for (int q = 0; q < added; ++q)
        {
          SkeletonPoint& sp = fresh[static_cast<std::size_t>(q)];
          sp.position_World_mm = positions[static_cast<std::size_t>(q)];
          const double f = (q + 1) / count;
          sp.radius_mm = dummy < 0 ? p.radiusFrom_mm + (p.radiusTo_mm - p.radiusFrom_mm) * f
                                   : (q < dummy ? p.radiusFrom_mm : p.radiusTo_mm);
          sp.label = PointLabel::Ordinary;
        }
        std::vector<int> moved(skeleton.junctions.size(), -1);
        for (std::size_t ji = 0; ji < skeleton.junctions.size(); ++ji)
        {
          const Junction& jn = skeleton.junctions[ji];
          if (jn.parentPath == static_cast<int>(pi) && jn.parentPoint >= p.first &&
              jn.parentPoint <= p.last)
          {
            // A path joined inside the re-traced stretch: to the nearest point of the track (to
            // the point that goes, in a clutter cut: it joined the clutter).
            const Vec3 old =
              path.points[static_cast<std::size_t>(jn.parentPoint)].position_World_mm;
            int best = dummy;
            double bestDistance = std::numeric_limits<double>::infinity();
            for (int q = 0; dummy < 0 && q < added; ++q)
            {
              const double d = (positions[static_cast<std::size_t>(q)] - old).norm();
              if (d < bestDistance)
              {
                bestDistance = d;
                best = q;
              }
            }
            moved[ji] = best >= 0 ? p.first + best : std::max(0, p.first - 1);
            ++result.junctionsMoved;
          }
        }
        path.points.erase(path.points.begin() + p.first, path.points.begin() + p.last + 1);
        path.points.insert(path.points.begin() + p.first, fresh.begin(), fresh.end());
        status.erase(status.begin() + p.first, status.begin() + p.last + 1);
        status.insert(status.begin() + p.first, static_cast<std::size_t>(added), Section::Retraced);
        if (dummy >= 0)
        {
          status[static_cast<std::size_t>(p.first + dummy)] = Section::NotClean;
        }
        for (std::size_t ji = 0; ji < skeleton.junctions.size(); ++ji)
        {
          Junction& jn = skeleton.junctions[ji];
          if (moved[ji] >= 0)
          {
            jn.parentPoint = moved[ji];
          }
          else if (jn.parentPath == static_cast<int>(pi) && jn.parentPoint > p.last)
          {
            jn.parentPoint += added - removed;
          }
        }
        for (auto& c : changed)
        {
          c.first += added - removed;
          c.second += added - removed;
        }
        for (auto& c : clutter)
        {
          c.first += added - removed;
          c.second += added - removed;
        }
        if (dummy >= 0)
        {
          clutter.emplace_back(p.first + dummy, p.first + dummy);
          if (dummy > 0)
          {
            changed.emplace_back(p.first, p.first + dummy - 1);
          }
          if (dummy + 1 < added)
          {
            changed.emplace_back(p.first + dummy + 1, p.first + added - 1);
          }
        }
        else
        {
          changed.emplace_back(p.first, p.first + added - 1);
        }
      }
      path.points.front().label =
        path.head.junction >= 0 ? PointLabel::Bifurcation : PointLabel::EndPoint;
      path.points.back().label =
        path.tail.junction >= 0 ? PointLabel::Bifurcation : PointLabel::EndPoint;
      // Re-smooth with the filter's windows: positions of the new points, derivatives around them.
      std::vector<std::size_t> corners;
      std::vector<Vec3> positions;
      for (const SkeletonPoint& q : path.points)
      {
        positions.push_back(q.position_World_mm);
      }
      for (const Junction& jn : skeleton.junctions)
      {
        if (jn.parentPath == static_cast<int>(pi))
        {
          corners.push_back(static_cast<std::size_t>(jn.parentPoint));
        }
      }
      const CurveGeometryWindows windows =
        skeletonPathWindows(pathMedianRadius, largestSpacing, s.smoothingWindow_mm);
      const std::vector<CurveSample> g = computeCurveGeometry(positions, windows, corners);
      const int reach = static_cast<int>(std::ceil(windows.torsion_mm / voxel)) + 1;
      const int m = static_cast<int>(path.points.size());
      for (const auto& [first, last] : changed)
      {
        for (int q = std::max(0, first - reach); q <= std::min(m - 1, last + reach); ++q)
        {
          SkeletonPoint& sp = path.points[static_cast<std::size_t>(q)];
          if (q >= first && q <= last)
          {
            sp.position_World_mm = g[static_cast<std::size_t>(q)].position;
          }
          sp.tangent_World = g[static_cast<std::size_t>(q)].tangent;
          sp.curvature_per_mm = g[static_cast<std::size_t>(q)].curvature;
          sp.torsion_per_mm = g[static_cast<std::size_t>(q)].torsion;
        }
      }
      if (!clutter.empty())
      {
        clutterCuts[pi] = std::move(clutter);
      }
    }
  }
  result.junctionsDetached += cutStretches(skeleton, clutterCuts, result.sections);
  // Attached ends coincide with their parent points (as the filter leaves them).
  for (const Junction& jn : skeleton.junctions)
  {
    const SkeletonPoint& parent = skeleton.paths[static_cast<std::size_t>(jn.parentPath)]
                                    .points[static_cast<std::size_t>(jn.parentPoint)];
    SkeletonPath& child = skeleton.paths[static_cast<std::size_t>(jn.childPath)];
    SkeletonPoint& end =
      jn.childEnd == Junction::End::Head ? child.points.front() : child.points.back();
    end.position_World_mm = parent.position_World_mm;
  }
  return result;
}

} // namespace vtouch

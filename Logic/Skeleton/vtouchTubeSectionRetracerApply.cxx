// PathRetracer's plans applied (vtouchTubeSectionRetracer.h; rules 3-4 of
// vtouchTubeSectionTracker.h): the stretches' points replaced by the tracks (or by the point that
// goes in a clutter cut), the paths joined inside them moved, and the path re-smoothed there.
#include "vtouchTubeSectionRetracer.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <utility>
#include <vector>

namespace vtouch
{
namespace tube_sections
{
namespace
{
/// The point of `positions` nearest to x, other than `dummy` (the point that goes): its index
/// (-1 when none) and its `distance` (mm).
int nearestOnTrack(const std::vector<Vec3>& positions, int dummy, const Vec3& x, double& distance)
{
  int best = -1;
  distance = std::numeric_limits<double>::infinity();
  for (int q = 0; q < static_cast<int>(positions.size()); ++q)
  {
    const double d = (positions[static_cast<std::size_t>(q)] - x).norm();
    if (q != dummy && d < distance)
    {
      distance = d;
      best = q;
    }
  }
  return best;
}

void shiftRanges(std::vector<std::pair<int, int>>& ranges, int by)
{
  for (auto& c : ranges)
  {
    c.first += by;
    c.second += by;
  }
}
} // namespace

/// Non-overlapping plans, applied from the last to the first (indices before stay valid); then
/// the ends' labels, the re-smoothing and the clutter cuts for TubeSectionTracker's cutting.
void PathRetracer::applyPlans(std::vector<RetracePlan>& plans)
{
  std::sort(plans.begin(),
    plans.end(),
    [](const RetracePlan& x, const RetracePlan& y) { return x.first < y.first; });
  std::vector<RetracePlan> kept;
  for (RetracePlan& p : plans)
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
    applyPlan(*it, changed, clutter);
  }
  path.points.front().label =
    path.head.junction >= 0 ? PointLabel::Bifurcation : PointLabel::EndPoint;
  path.points.back().label =
    path.tail.junction >= 0 ? PointLabel::Bifurcation : PointLabel::EndPoint;
  resmoothChanged(changed);
  if (!clutter.empty())
  {
    clutterCuts[pi] = std::move(clutter);
  }
}

/// One plan: its points replace [p.first, p.last] (radius interpolated between the ends, rule 3);
/// the paths joined inside move onto the track, or to the point that goes; the ranges already
/// applied (after this one) shift by the change in length.
void PathRetracer::applyPlan(const RetracePlan& p,
  std::vector<std::pair<int, int>>& changed,
  std::vector<std::pair<int, int>>& clutter)
{
  const int removed = p.last - p.first + 1;
  // A clutter cut: the kept tracks on either side and one point between them that goes
  // (TubeSectionTracker's cutting, after the re-tracing), with whatever joined the clutter.
  std::vector<Vec3> positions = p.positions;
  int dummy = -1;
  if (p.remove)
  {
    positions = p.before;
    dummy = static_cast<int>(positions.size());
    positions.push_back(path.points[static_cast<std::size_t>(p.first)].position_World_mm);
    positions.insert(positions.end(), p.after.begin(), p.after.end());
  }
  // A free end re-traced as far as the tube goes: a path joined to the stretch beyond the
  // tube's end (farther than a junction's reach from the track) joined the clutter the
  // coder ran onto, not the tube; moved onto the track it would jump across the clutter.
  // It is detached (through a point past the track's end that goes, as in a cut); step 5
  // judges it as a path of its own. (Project rule, issue 16 item 5.)
  if (!p.remove && p.freeEnd != 0)
  {
    bool far = false;
    for (const Junction& jn : skeleton.junctions)
    {
      double d = 0.0;
      far = far || (jn.parentPath == static_cast<int>(pi) && jn.parentPoint >= p.first &&
                     jn.parentPoint <= p.last &&
                     (nearestOnTrack(positions,
                        dummy,
                        path.points[static_cast<std::size_t>(jn.parentPoint)].position_World_mm,
                        d) < 0 ||
                       d > p.joinReach_mm));
    }
    if (far && p.freeEnd > 0)
    {
      dummy = static_cast<int>(positions.size());
      positions.push_back(path.points[static_cast<std::size_t>(p.last)].position_World_mm);
    }
    else if (far)
    {
      dummy = 0;
      positions.insert(
        positions.begin(), path.points[static_cast<std::size_t>(p.first)].position_World_mm);
    }
  }
  const int added = static_cast<int>(positions.size());
  std::vector<SkeletonPoint> fresh(static_cast<std::size_t>(added));
  const double count = static_cast<double>(added + 1);
  for (int q = 0; q < added; ++q)
  {
    SkeletonPoint& sp = fresh[static_cast<std::size_t>(q)];
    sp.position_World_mm = positions[static_cast<std::size_t>(q)];
    const double f = (q + 1) / count;
    sp.radius_mm = !p.remove ? p.radiusFrom_mm + (p.radiusTo_mm - p.radiusFrom_mm) * f
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
      const Vec3 old = path.points[static_cast<std::size_t>(jn.parentPoint)].position_World_mm;
      double bestDistance = 0.0;
      int best = p.remove ? dummy : nearestOnTrack(positions, dummy, old, bestDistance);
      if (!p.remove && dummy >= 0 && (best < 0 || bestDistance > p.joinReach_mm))
      {
        best = dummy; // beyond the tube's end: detached below
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
  shiftRanges(changed, added - removed);
  shiftRanges(clutter, added - removed);
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

/// Re-smooths with the filter's windows (skeletonPathWindows, rule 3): positions of the new
/// points, derivatives around them (within the torsion window's reach).
void PathRetracer::resmoothChanged(const std::vector<std::pair<int, int>>& changed)
{
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
}

} // namespace tube_sections
} // namespace vtouch

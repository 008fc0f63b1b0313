// PathRetracer's re-tracing (vtouchTubeSectionRetracer.h; rule 3 of vtouchTubeSectionTracker.h):
// a stretch replaced by the tube's own track, between two anchors or at a free end. A track
// runs from an anchor in a direction along the path (`sign`: +1 towards the tail, -1 towards
// the head); one function serves both directions, the plans it makes are in the path's order.
#include "vtouchTubeSectionRetracer.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

namespace vtouch
{
namespace tube_sections
{

/// A stretch [j, k) between two anchors of the path (A = j - 1, B = k): forward from A, else
/// backward from B. Replaced up to the clean point the track meets, or up to the junction it
/// reached past clutter (junctionReached: project rule, issue 16 item 5). The confirmed tracks
/// go to `tracks` (kept beside a cut, rule 4, when no plan was made).
void PathRetracer::planBetweenAnchors(int j,
  int k,
  double maxLength_mm,
  std::vector<RetracePlan>& plans,
  StretchTracks& tracks)
{
  const int a = j - 1, b = k;
  bool done = false;
  const double rForward = tubeRadius(a, b);
  if (std::isfinite(rForward) && rForward > 0.0)
  {
    done = planTrackAcross(a, +1, j, k, rForward, maxLength_mm, plans, tracks.forward);
  }
  tracks.rBackward_voxels = done ? 0.0 : tubeRadius(b, a);
  const double rBackward = tracks.rBackward_voxels;
  if (!done && std::isfinite(rBackward) && rBackward > 0.0)
  {
    done = planTrackAcross(b, -1, j, k, rBackward, maxLength_mm, plans, tracks.backward);
  }
  result.stretchesTracked += done ? 1 : 0;
}

/// The track of radius `r` (voxels) from anchor `from` in direction `sign` across the stretch
/// [j, k), towards the anchors beyond it: planned up to the anchor it hits, else up to the
/// junction it reached past clutter. Its confirmed part goes to `kept` (even when no plan is
/// made). True when a plan was made.
bool PathRetracer::planTrackAcross(int from,
  int sign,
  int j,
  int k,
  double r,
  double maxLength_mm,
  std::vector<RetracePlan>& plans,
  Track& kept)
{
  std::vector<Target> targets; // nearest first
  for (int q = sign > 0 ? k : j - 1; q >= 0 && q < n; q += sign)
  {
    if (anchor(q))
    {
      targets.push_back({ q, path.points[static_cast<std::size_t>(q)].position_World_mm });
    }
  }
  const Track tr = follow(sampler,
    path.points[static_cast<std::size_t>(from)].position_World_mm,
    heading(from, sign),
    r,
    targets,
    zones,
    maxLength_mm,
    s);
  kept = confirmedPart(tr); // kept beside a cut only as far as it is sure
  if (tr.hit >= 0)
  {
    plans.push_back(trackPlan(from, tr.hit, sign, tr, tr.centres.size() - 1));
    return true;
  }
  if (const auto [q, c] = junctionReached(tr, from, sign, r); q >= 0)
  {
    plans.push_back(trackPlan(from, q, sign, tr, c));
    ++result.stretchesEndedAtJunction;
    return true;
  }
  return false;
}

/// The points strictly between `from` and `to` replaced by the track's centres 1..lastCentre
/// (centre 0 is the start, at `from`), resampled every voxel, in the path's order (a backward
/// track's centres reversed); the radii run from the two ends'.
RetracePlan PathRetracer::trackPlan(int from,
  int to,
  int sign,
  const Track& tr,
  std::size_t lastCentre) const
{
  std::vector<Vec3> via(
    tr.centres.begin() + 1, tr.centres.begin() + static_cast<std::ptrdiff_t>(lastCentre) + 1);
  if (sign < 0)
  {
    std::reverse(via.begin(), via.end());
  }
  const SkeletonPoint& first = path.points[static_cast<std::size_t>(std::min(from, to))];
  const SkeletonPoint& last = path.points[static_cast<std::size_t>(std::max(from, to))];
  return { std::min(from, to) + 1,
    std::max(from, to) - 1,
    resampled(first.position_World_mm, via, &last.position_World_mm, voxel),
    first.radius_mm,
    last.radius_mm };
}

/// A free end from its anchor (`sign` +1: the tail [anchorIndex + 1, n), -1: the head
/// [0, anchorIndex)): replaced as far as the tube goes for sure (at most the stretch's length + 1
/// voxel; confirmedPart: project rule, issue 16 item 5). Paths joined to it farther than
/// 2 (r + 1) voxels from the track are detached when the plan is applied.
void PathRetracer::planFreeEnd(int anchorIndex,
  int sign,
  double stretchLength_mm,
  std::vector<RetracePlan>& plans)
{
  const double r = tubeRadius(anchorIndex, sign > 0 ? n - 1 : 0);
  if (std::isfinite(r) && r > 0.0)
  {
    const SkeletonPoint& at = path.points[static_cast<std::size_t>(anchorIndex)];
    const Track full = follow(sampler,
      at.position_World_mm,
      heading(anchorIndex, sign),
      r,
      {},
      zones,
      stretchLength_mm + voxel,
      s);
    // A free end: as far as the tube goes for sure (only the anchor when the track lost the
    // tube and found only touched sections after it: the end is trimmed there).
    const Track tr = confirmedPart(full);
    result.freeEndsEndedWhereTubeLost += tr.centres.size() < full.centres.size() ? 1 : 0;
    if (full.centres.size() > 1)
    {
      std::vector<Vec3> via(tr.centres.begin() + 1, tr.centres.end());
      std::vector<Vec3> pts = resampled(at.position_World_mm, via, nullptr, voxel);
      if (sign < 0)
      {
        std::reverse(pts.begin(), pts.end()); // in the path's order
      }
      plans.push_back({ sign > 0 ? anchorIndex + 1 : 0,
        sign > 0 ? n - 1 : anchorIndex - 1,
        pts,
        at.radius_mm,
        at.radius_mm });
      plans.back().freeEnd = sign;
      plans.back().joinReach_mm = 2.0 * (r + 1.0) * voxel;
      result.stretchesTracked += 1;
    }
  }
}

} // namespace tube_sections
} // namespace vtouch

// PathRetracer's re-tracing (vtouchTubeSectionRetracer.h; rule 3 of vtouchTubeSectionTracker.h):
// a stretch replaced by the tube's own track, between two anchors or at a free end.
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
      maxLength_mm,
      s);
    tracks.forward = confirmedPart(tr); // kept beside a cut only as far as it is sure
    if (tr.hit >= 0)
    {
      const Vec3 to = path.points[static_cast<std::size_t>(tr.hit)].position_World_mm;
      std::vector<Vec3> via(tr.centres.begin() + 1, tr.centres.end());
      plans.push_back({ a + 1,
        tr.hit - 1,
        resampled(path.points[static_cast<std::size_t>(a)].position_World_mm, via, &to, voxel),
        path.points[static_cast<std::size_t>(a)].radius_mm,
        path.points[static_cast<std::size_t>(tr.hit)].radius_mm });
      done = true;
    }
    else if (const auto [q, c] = junctionReached(tr, a, +1, rForward); q >= 0)
    {
      const Vec3 to = path.points[static_cast<std::size_t>(q)].position_World_mm;
      std::vector<Vec3> via(
        tr.centres.begin() + 1, tr.centres.begin() + static_cast<std::ptrdiff_t>(c) + 1);
      plans.push_back({ a + 1,
        q - 1,
        resampled(path.points[static_cast<std::size_t>(a)].position_World_mm, via, &to, voxel),
        path.points[static_cast<std::size_t>(a)].radius_mm,
        path.points[static_cast<std::size_t>(q)].radius_mm });
      done = true;
      ++result.stretchesEndedAtJunction;
    }
  }
  tracks.rBackward_voxels = done ? 0.0 : tubeRadius(b, a);
  const double rBackward = tracks.rBackward_voxels;
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
      maxLength_mm,
      s);
    tracks.backward = confirmedPart(tr);
    if (tr.hit >= 0)
    {
      const Vec3 to = path.points[static_cast<std::size_t>(b)].position_World_mm;
      std::vector<Vec3> via(tr.centres.rbegin(), tr.centres.rend() - 1);
      plans.push_back({ tr.hit + 1,
        b - 1,
        resampled(path.points[static_cast<std::size_t>(tr.hit)].position_World_mm, via, &to, voxel),
        path.points[static_cast<std::size_t>(tr.hit)].radius_mm,
        path.points[static_cast<std::size_t>(b)].radius_mm });
      done = true;
    }
    else if (const auto [q, c] = junctionReached(tr, b, -1, rBackward); q >= 0)
    {
      const Vec3 to = path.points[static_cast<std::size_t>(b)].position_World_mm;
      std::vector<Vec3> via(
        tr.centres.rbegin() + static_cast<std::ptrdiff_t>(tr.centres.size() - 1 - c),
        tr.centres.rend() - 1);
      plans.push_back({ q + 1,
        b - 1,
        resampled(path.points[static_cast<std::size_t>(q)].position_World_mm, via, &to, voxel),
        path.points[static_cast<std::size_t>(q)].radius_mm,
        path.points[static_cast<std::size_t>(b)].radius_mm });
      done = true;
      ++result.stretchesEndedAtJunction;
    }
  }
  result.stretchesTracked += done ? 1 : 0;
}

/// A free tail [j, n) from its anchor j - 1: replaced as far as the tube goes for sure (at most
/// the stretch's length + 1 voxel; confirmedPart: project rule, issue 16 item 5). Paths joined
/// to it farther than 2 (r + 1) voxels from the track are detached when the plan is applied.
void PathRetracer::planFreeTail(int j, double stretchLength_mm, std::vector<RetracePlan>& plans)
{
  const int a = j - 1;
  const double r = tubeRadius(a, n - 1);
  if (std::isfinite(r) && r > 0.0)
  {
    const Track full = follow(sampler,
      path.points[static_cast<std::size_t>(a)].position_World_mm,
      heading(a, +1),
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
      const double R = path.points[static_cast<std::size_t>(a)].radius_mm;
      plans.push_back({ a + 1,
        n - 1,
        resampled(path.points[static_cast<std::size_t>(a)].position_World_mm, via, nullptr, voxel),
        R,
        R });
      plans.back().freeEnd = +1;
      plans.back().joinReach_mm = 2.0 * (r + 1.0) * voxel;
      result.stretchesTracked += 1;
    }
  }
}

/// A free head [0, k) from its anchor k: as planFreeTail, the track reversed.
void PathRetracer::planFreeHead(int k, double stretchLength_mm, std::vector<RetracePlan>& plans)
{
  const int b = k;
  const double r = tubeRadius(b, 0);
  if (std::isfinite(r) && r > 0.0)
  {
    const Track full = follow(sampler,
      path.points[static_cast<std::size_t>(b)].position_World_mm,
      heading(b, -1),
      r,
      {},
      zones,
      stretchLength_mm + voxel,
      s);
    const Track tr = confirmedPart(full);
    result.freeEndsEndedWhereTubeLost += tr.centres.size() < full.centres.size() ? 1 : 0;
    if (full.centres.size() > 1)
    {
      std::vector<Vec3> via(tr.centres.begin() + 1, tr.centres.end());
      std::vector<Vec3> pts =
        resampled(path.points[static_cast<std::size_t>(b)].position_World_mm, via, nullptr, voxel);
      std::reverse(pts.begin(), pts.end());
      const double R = path.points[static_cast<std::size_t>(b)].radius_mm;
      plans.push_back({ 0, b - 1, pts, R, R });
      plans.back().freeEnd = -1;
      plans.back().joinReach_mm = 2.0 * (r + 1.0) * voxel;
      result.stretchesTracked += 1;
    }
  }
}

} // namespace tube_sections
} // namespace vtouch

// PathRetracer's cutting (vtouchTubeSectionRetracer.h; rule 4 of vtouchTubeSectionTracker.h): a
// stretch no track crossed, planned for removal when it is clutter.
#include "vtouchTubeSectionRetracer.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

namespace vtouch
{
namespace tube_sections
{
namespace
{
double trackLength_mm(const Track& tr)
{
  double l = 0.0;
  for (std::size_t q = 1; q < tr.centres.size(); ++q)
  {
    l += (tr.centres[q] - tr.centres[q - 1]).norm();
  }
  return l;
}
} // namespace

/// A vessel running between vessels of at most its calibre (issue 16 item 2, branch h16p; project
/// rule): every section of the stretch [j, k) ends within betweenVesselsReach_radii tube radii +
/// 1 voxel of the path. A vessel of radius r touched by a vessel of radius r' <= r has that
/// vessel's far wall within r + 2 r' <= 3 r of its axis, on each side it is touched; a plate's
/// band runs on to the plate's edge. (Two touching vessels make the section a band too, two
/// arcs on opposite sides, which is why the band test alone cut it: a vessel of radius 4 touched
/// on both sides over 5 voxels or more.)
bool PathRetracer::betweenVessels(int j, int k, double tube_voxels) const
{
  if (!(s.betweenVesselsReach_radii > 0.0) || !std::isfinite(tube_voxels))
  {
    return false;
  }
  const double reach_mm = (s.betweenVesselsReach_radii * tube_voxels + 1.0) * voxel;
  const double step_mm = s.rayStep_voxels * voxel;
  const int rays = std::max(8, s.rays);
  constexpr double kPi = 3.14159265358979323846;
  for (int q = j; q < k; ++q)
  {
    const SkeletonPoint& p = path.points[static_cast<std::size_t>(q)];
    Vec3 t, u, v;
    SectionSampler::sectionBasis(p.tangent_World, t, u, v);
    if (!sampler.inside(p.position_World_mm))
    {
      return false;
    }
    for (int a = 0; a < rays; ++a)
    {
      const double angle = 2.0 * kPi * a / rays;
      const Vec3 dir = u * std::cos(angle) + v * std::sin(angle);
      const double run_mm =
        sampler.runLength(p.position_World_mm, dir, reach_mm + step_mm, step_mm);
      // The ray must end on background inside the grid: where it leaves the volume (a vessel
      // cut by the volume's border) what lies beyond is unknown.
      std::array<std::int64_t, 3> end;
      if (run_mm > reach_mm ||
          !sampler.nearestVoxel(p.position_World_mm + dir * (run_mm + step_mm), end))
      {
        return false;
      }
    }
  }
  return true;
}

/// A loop's chord (session 20; project rule): the stretch [j, k) runs from the path's joined end
/// (the anchor just before or after it) to a point m where a bridge joins - a path whose other end
/// is joined to the same parent as that end - so the stretch, the bridge and the parent close a
/// loop. The coder draws one where a vessel runs along a slab of clutter and a branch of it is
/// coded through the slab to a point farther up the vessel (128^3 seed 55 noise 35: 14 points 2-6
/// voxels off, the loop's two sides both in the merged region). Cut up to the bridge, the path
/// stays joined to the network through it. Returns m, or -1.
int PathRetracer::loopChordEnd(int j, int k) const
{
  // The joined end is an anchor itself: the stretch starts just after it (or ends just before).
  const bool head = j <= 1 && path.head.junction >= 0;
  const bool tail = k >= n - 1 && path.tail.junction >= 0;
  if (head == tail)
  {
    return -1; // neither end (or a stretch over the whole path)
  }
  const int parent =
    skeleton.junctions[static_cast<std::size_t>(head ? path.head.junction : path.tail.junction)]
      .parentPath;
  int m = -1;
  for (const Junction& jn : skeleton.junctions)
  {
    const bool inside = head ? jn.parentPoint >= 1 && jn.parentPoint <= std::min(k, n - 2)
                             : jn.parentPoint >= std::max(j - 1, 1) && jn.parentPoint <= n - 2;
    if (jn.parentPath != static_cast<int>(pi) || !inside || jn.childPath == static_cast<int>(pi))
    {
      continue;
    }
    const SkeletonPath& bridge = skeleton.paths[static_cast<std::size_t>(jn.childPath)];
    const int other =
      jn.childEnd == Junction::End::Head ? bridge.tail.junction : bridge.head.junction;
    if (other < 0 || skeleton.junctions[static_cast<std::size_t>(other)].parentPath != parent)
    {
      continue;
    }
    // The bridge nearest the stretch's far end: the whole chord goes.
    m = m < 0 ? jn.parentPoint : (head ? std::max(m, jn.parentPoint) : std::min(m, jn.parentPoint));
  }
  // The path goes on past the bridge as a vessel: a run of 3 clean sections there (else the
  // path is clutter of its own, which step 5 judges whole).
  int run = 0, best = 0;
  for (int q = m; m >= 0 && q >= 0 && q < n; q += head ? 1 : -1)
  {
    run = sec[static_cast<std::size_t>(q)].clean ? run + 1 : 0;
    best = std::max(best, run);
  }
  return best >= s.minimumAnchorPoints ? m : -1;
}

/// The stretch [j, k), not re-traced. Clutter when its sections are wide (a plate's or a blob's,
/// not a thin vessel's noisy wall) and either mostly not round (a plate's band) or wider than the
/// tube it left (a blob), over more than the structure's diameter + 2 voxels: a junction's
/// elongated sections reach about a radius of the larger vessel on either side of it, and no
/// more. (Project rule, issue 16 items 2 and 5; Docs/CENTERLINES.md step 4.)
void PathRetracer::planClutterCut(int j,
  int k,
  const StretchTracks& tracks,
  std::vector<RetracePlan>& plans)
{
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
  const bool wider = std::isfinite(tube) &&
                     width > tube + std::max(s.radiusExcess_voxels, s.radiusExcessFraction * tube);
  // It does not reach a junction between two vessels, where the other vessel's lumen
  // legitimately elongates the sections - but for a loop's chord, its own joined end's.
  const int chordTo = loopChordEnd(j, k);
  const bool chordAtHead = chordTo >= 0 && j <= 1 && path.head.junction >= 0;
  const int joinedEnd = chordAtHead ? 0 : n - 1;
  bool nearJunction = false;
  for (const int q : realJunctionPoints[pi])
  {
    nearJunction = nearJunction || (q >= j - 1 && q <= k && !(chordTo >= 0 && q == joinedEnd));
  }
  if (nearJunction || k - j < s.clutterMinimumPoints || !(2 * notRound >= k - j || wider) ||
      !(width >= s.clutterMinimumWidth_voxels) || !(length > width + 2.0) ||
      (!wider && betweenVessels(j, k, tube)))
  {
    return;
  }
  RetracePlan cut;
  cut.first = chordTo >= 0 && !chordAtHead ? chordTo + 1 : j;
  cut.last = chordAtHead ? chordTo - 1 : k - 1;
  cut.radiusFrom_mm = path.points[static_cast<std::size_t>(std::max(j - 1, 0))].radius_mm;
  cut.radiusTo_mm = path.points[static_cast<std::size_t>(std::min(k, n - 1))].radius_mm;
  cut.remove = true;
  // Where a track from an anchor followed the tube on beyond a junction's reach (the coder's
  // path left the tube for the clutter), the tube's track stays: the piece before the cut ends,
  // and the piece after it starts, where the tube stops.
  const Track& forwardTrack = tracks.forward;
  const Track& backwardTrack = tracks.backward;
  const double rBackward = tracks.rBackward_voxels;
  // A loop's chord keeps no track: the bridge is the tube's way to the parent.
  if (chordTo < 0 && j >= 1 && forwardTrack.centres.size() > 1 &&
      trackLength_mm(forwardTrack) > 2.0 * (tubeRadius(j - 1, k) + 1.0) * voxel)
  {
    cut.before = resampled(forwardTrack.centres.front(),
      std::vector<Vec3>(forwardTrack.centres.begin() + 1, forwardTrack.centres.end()),
      nullptr,
      voxel);
  }
  if (chordTo < 0 && k <= n - 1 && backwardTrack.centres.size() > 1 && std::isfinite(rBackward) &&
      trackLength_mm(backwardTrack) > 2.0 * (rBackward + 1.0) * voxel)
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

} // namespace tube_sections
} // namespace vtouch

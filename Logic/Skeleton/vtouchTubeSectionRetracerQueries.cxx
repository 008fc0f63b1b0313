// PathRetracer's section queries (vtouchTubeSectionRetracer.h): what the stretch, track and cut
// phases ask of the path's judged sections (rules 2-4 of vtouchTubeSectionTracker.h).
#include "vtouchTubeSectionRetracer.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

namespace vtouch
{
namespace tube_sections
{

/// The radius window (voxels of arc length) around point i: max(12 voxels, 3 x the median s of
/// its vessel) (rule 1's tau window, reused for the anchor's radius in rule 2).
double PathRetracer::window(int i) const
{
  const int c = vessel[static_cast<std::size_t>(i)];
  return std::max(s.radiusWindow_voxels, s.radiusWindowRadii * vesselMedian[c]);
}

/// Point j on i's vessel (the piece between two cuts) and within w of arc length of it.
bool PathRetracer::inWindow(int i, int j, double w) const
{
  return vessel[static_cast<std::size_t>(j)] == vessel[static_cast<std::size_t>(i)] &&
         std::abs(arc[static_cast<std::size_t>(j)] - arc[static_cast<std::size_t>(i)]) <= w;
}

/// Anchors (rule 2): the clean points, and an end attached to another path (the junction stays).
bool PathRetracer::anchor(int i) const
{
  return sec[static_cast<std::size_t>(i)].clean || (i == 0 && path.head.junction >= 0) ||
         (i == n - 1 && path.tail.junction >= 0);
}

// Wider than the tube it left (radius r): the cut's blob criterion (below) on one section,
// s > r + max(1 voxel, r / 2), and as wide as clutter (s >= clutterMinimumWidth: not a thin
// vessel's noisy wall). Clutter only widens the section (a ball or blob swallowing the path
// lengthens every ray); a junction between two vessels lengthens the rays toward the other
// vessel only, and the median stays about the tube's radius (the Tree phantom: s 5.9-6.0
// beside a tube of r 5.9; the 384^3 phantom's blob: s 2.9-4.9 beside r 1.1). Compared with
// the tube's own radius, not in absolute voxels: a thick vessel's sections are all wider than
// clutterMinimumWidth. (Project rule, issue 16 item 5.)
bool PathRetracer::widerThanTube(double sv, double r) const
{
  return sv >= s.clutterMinimumWidth_voxels &&
         sv > r + std::max(s.radiusExcess_voxels, s.radiusExcessFraction * r);
}

// A lone clean point amid clutter: the judged points on both sides of it are not clean, in the
// range (s > 0: not a thin vessel's section whose centre fell on a noise hole, which says the
// point is on that vessel) and one of them is wider than the tube r the track comes from
// (widerThanTube; a thick vessel's own sections beside a lone clean one, where the vessel
// nears itself, are not: the Winding line phantom, s 6.5-6.9 beside r 7.1, was cut in two).
// It is the coder's centre pulled into a contact whose section happens to be round and narrow
// there, off the tube: a track from the tube before it cannot meet it, so it does not end a
// stretch that such a track enters (stretchEnd), as a lone round section is no vessel to follow.
// (Project rule, issue 16 item 5, "Past clutter".)
bool PathRetracer::lone(int i, double r) const
{
  if (i < 1 || i + 1 >= n || !sec[static_cast<std::size_t>(i)].clean)
  {
    return false;
  }
  const PointSection& before = sec[static_cast<std::size_t>(i - 1)];
  const PointSection& after = sec[static_cast<std::size_t>(i + 1)];
  return !before.zone && !after.zone && !before.clean && !after.clean && before.s > 0.0 &&
         after.s > 0.0 && (widerThanTube(before.s, r) || widerThanTube(after.s, r));
}

// The point of this path where another vessel joins it (both have clean runs: the coder's
// junction between two vessels) that the tube's track from `from` (toward `sign`) came within
// reach of, the farthest along the track: (point, centre index), or (-1, 0). A track that meets
// no clean point may still reach the junction where the vessel goes on as another path, when
// the coder's path ran onto clutter before it: a judged section between `from` and the
// junction is wider than the tube (widerThanTube). Where none is, the stretch holds only the
// junction's own elongated sections (a clean junction of thick vessels: the Tree phantom's
// path 2 was moved 1.7 voxels) and is left to the track from the other side, as before.
// (Project rule, issue 16 item 5, "Past clutter".)
std::pair<int, std::size_t> PathRetracer::junctionReached(const Track& tr,
  int from,
  int sign,
  double r) const
{
  const double reach = std::max(s.targetReach_voxels, 0.5 * r) * voxel;
  std::pair<int, std::size_t> best{ -1, 0 };
  std::vector<bool> ranOntoClutter; // per junction point of the path
  for (const int q : realJunctionPoints[pi])
  {
    bool wide = false;
    for (int i = std::min(from, q) + 1; i < std::max(from, q); ++i)
    {
      const PointSection& ps = sec[static_cast<std::size_t>(i)];
      wide = wide || (!ps.zone && widerThanTube(ps.s, r));
    }
    ranOntoClutter.push_back((q - from) * sign >= 2 && wide);
  }
  for (std::size_t c = 1; c < tr.centres.size(); ++c)
  {
    for (std::size_t jq = 0; jq < realJunctionPoints[pi].size(); ++jq)
    {
      const int q = realJunctionPoints[pi][jq];
      if (ranOntoClutter[jq] &&
          (tr.centres[c] - path.points[static_cast<std::size_t>(q)].position_World_mm).norm() <=
            reach)
      {
        best = { q, c };
      }
    }
  }
  return best;
}

// The tube's radius for a stretch (rule 2): median s of the clean points on one side, within
// the window, of the anchor's vessel (of any vessel when that has none); NaN (no track) when
// fewer than 3 are clean there: a lone round section amid clutter is no vessel to follow.
double PathRetracer::tubeRadius(int from, int towards) const
{
  const double w = window(from);
  for (const bool sameVessel : { true, false })
  {
    std::vector<double> x;
    for (int j = 0; j < n; ++j)
    {
      const bool side = towards > from ? j <= from : j >= from;
      const bool near =
        sameVessel
          ? inWindow(from, j, w)
          : std::abs(arc[static_cast<std::size_t>(j)] - arc[static_cast<std::size_t>(from)]) <= w;
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
}

// The direction a track leaves an anchor in (rule 3): the chord from the path's point about two
// voxels (or a radius) behind it, toward the stretch (`sign` +1: toward higher indices). The
// chord of the clean side, not the smoothed tangent: smoothing bends it toward the stretch.
Vec3 PathRetracer::heading(int from, int sign) const
{
  const double back = std::max(2.0, sec[static_cast<std::size_t>(from)].s);
  int q = from;
  while (q - sign >= 0 && q - sign < n &&
         std::abs(arc[static_cast<std::size_t>(q)] - arc[static_cast<std::size_t>(from)]) < back)
  {
    q -= sign;
  }
  const Vec3 chord = path.points[static_cast<std::size_t>(from)].position_World_mm -
                     path.points[static_cast<std::size_t>(q)].position_World_mm;
  const Vec3 tangent = path.points[static_cast<std::size_t>(from)].tangent_World * sign;
  return chord.norm() > 0.5 * voxel ? chord : tangent;
}

} // namespace tube_sections
} // namespace vtouch

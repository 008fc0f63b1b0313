// TubeSectionTracker's phase 2 (vtouchTubeSectionParts.h): a path's stretches re-traced along the
// tube, or planned as clutter to cut (the rules in vtouchTubeSectionTracker.h, 2-4).
#include "vtouchTubeSectionParts.h"

#include <algorithm>
#include <array>
#include <cmath>
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
struct Plan
{
  int first; ///< first point replaced
  int last;  ///< last point replaced (inclusive); may be n - 1 (a free tail) or first - 1
  std::vector<Vec3> positions;
  double radiusFrom_mm, radiusTo_mm;
  bool remove = false; ///< clutter: the points go (the path is split there or its end trimmed)
  std::vector<Vec3> before{}; ///< remove: the tube's track kept before the cut
  std::vector<Vec3> after{};  ///< remove: the tube's track kept after the cut
  /// A free end re-traced as far as the tube goes (+1 the tail, -1 the head; 0 not): paths
  /// joined to the stretch farther than `joinReach_mm` from the track are detached.
  int freeEnd = 0;
  double joinReach_mm = 0.0;
};
} // namespace

/// Phase 2 (the header's 2-4) on path `pi`: its stretches re-traced in place (paths joined inside
/// one moved onto the track); the clutter stretches to remove go to `clutterCuts[pi]`.
void retracePath(QSkeleton& skeleton,
  std::size_t pi,
  std::vector<PathJudgement>& judged,
  const std::vector<std::vector<int>>& realJunctionPoints,
  const std::vector<Zone>& zones,
  const SectionSampler& sampler,
  double largestSpacing,
  const TubeSectionTracker::Settings& s,
  TubeSectionTracker::Result& result,
  std::vector<std::vector<std::pair<int, int>>>& clutterCuts)
{
  using Section = TubeSectionTracker::Section;
  const double voxel = sampler.voxel_mm();
  SkeletonPath& path = skeleton.paths[pi];
  const int n = static_cast<int>(path.points.size());
  auto& status = result.sections[pi];
  status.assign(static_cast<std::size_t>(n), Section::Junction);
  if (n < 3)
  {
    return;
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
  // Wider than the tube it left (radius r): the cut's blob criterion (below) on one section,
  // s > r + max(1 voxel, r / 2), and as wide as clutter (s >= clutterMinimumWidth: not a thin
  // vessel's noisy wall). Clutter only widens the section (a ball or blob swallowing the path
  // lengthens every ray); a junction between two vessels lengthens the rays toward the other
  // vessel only, and the median stays about the tube's radius (the Tree phantom: s 5.9-6.0
  // beside a tube of r 5.9; the 384^3 phantom's blob: s 2.9-4.9 beside r 1.1). Compared with
  // the tube's own radius, not in absolute voxels: a thick vessel's sections are all wider than
  // clutterMinimumWidth. (Project rule, issue 16 item 5.)
  const auto widerThanTube = [&](double sv, double r)
  {
    return sv >= s.clutterMinimumWidth_voxels &&
           sv > r + std::max(s.radiusExcess_voxels, s.radiusExcessFraction * r);
  };
  // A lone clean point amid clutter: the judged points on both sides of it are not clean, in the
  // range (s > 0: not a thin vessel's section whose centre fell on a noise hole, which says the
  // point is on that vessel) and one of them is wider than the tube r the track comes from
  // (widerThanTube; a thick vessel's own sections beside a lone clean one, where the vessel
  // nears itself, are not: the Winding line phantom, s 6.5-6.9 beside r 7.1, was cut in two).
  // It is the coder's centre pulled into a contact whose section happens to be round and narrow
  // there, off the tube: a track from the tube before it cannot meet it, so it does not end a
  // stretch that such a track enters (below), as a lone round section is no vessel to follow.
  const auto lone = [&](int i, double r)
  {
    if (i < 1 || i + 1 >= n || !sec[static_cast<std::size_t>(i)].clean)
    {
      return false;
    }
    const PointSection& before = sec[static_cast<std::size_t>(i - 1)];
    const PointSection& after = sec[static_cast<std::size_t>(i + 1)];
    return !before.zone && !after.zone && !before.clean && !after.clean && before.s > 0.0 &&
           after.s > 0.0 && (widerThanTube(before.s, r) || widerThanTube(after.s, r));
  };
  // The point of this path where another vessel joins it (both have clean runs: the coder's
  // junction between two vessels) that the tube's track from `from` (toward `sign`) came within
  // reach of, the farthest along the track: (point, centre index), or (-1, 0). A track that meets
  // no clean point may still reach the junction where the vessel goes on as another path, when
  // the coder's path ran onto clutter before it: a judged section between `from` and the
  // junction is wider than the tube (widerThanTube). Where none is, the stretch holds only the
  // junction's own elongated sections (a clean junction of thick vessels: the Tree phantom's
  // path 2 was moved 1.7 voxels) and is left to the track from the other side, as before.
  const auto junctionReached = [&](const Track& tr, int from, int sign, double r)
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
  };
  // The direction a track leaves an anchor in: the chord from the path's point about two voxels
  // (or a radius) behind it, toward the stretch (`sign` +1: toward higher indices). The chord
  // of the clean side, not the smoothed tangent: smoothing bends it toward the stretch.
  const auto heading = [&](int from, int sign)
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
    // Across lone clean points, when a track from the tube before the stretch enters it.
    while (judgedNotClean && j >= 1 && k < n)
    {
      const double r = tubeRadius(j - 1, k);
      if (!std::isfinite(r) || !lone(k, r))
      {
        break;
      }
      ++result.loneSectionsCrossed;
      ++k;
      while (k < n && !anchor(k))
      {
        ++k;
      }
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
        forwardTrack = confirmedPart(tr); // kept beside a cut only as far as it is sure
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
        backwardTrack = confirmedPart(tr);
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
    else if (freeTail && j >= 1)
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
          stretchLength + voxel,
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
            resampled(
              path.points[static_cast<std::size_t>(a)].position_World_mm, via, nullptr, voxel),
            R,
            R });
          plans.back().freeEnd = +1;
          plans.back().joinReach_mm = 2.0 * (r + 1.0) * voxel;
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
        const Track full = follow(sampler,
          path.points[static_cast<std::size_t>(b)].position_World_mm,
          heading(b, -1),
          r,
          {},
          zones,
          stretchLength + voxel,
          s);
        const Track tr = confirmedPart(full);
        result.freeEndsEndedWhereTubeLost += tr.centres.size() < full.centres.size() ? 1 : 0;
        if (full.centres.size() > 1)
        {
          std::vector<Vec3> via(tr.centres.begin() + 1, tr.centres.end());
          std::vector<Vec3> pts = resampled(
            path.points[static_cast<std::size_t>(b)].position_World_mm, via, nullptr, voxel);
          std::reverse(pts.begin(), pts.end());
          const double R = path.points[static_cast<std::size_t>(b)].radius_mm;
          plans.push_back({ 0, b - 1, pts, R, R });
          plans.back().freeEnd = -1;
          plans.back().joinReach_mm = 2.0 * (r + 1.0) * voxel;
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
      // A free end re-traced as far as the tube goes: a path joined to the stretch beyond the
      // tube's end (farther than a junction's reach from the track) joined the clutter the
      // coder ran onto, not the tube; moved onto the track it would jump across the clutter.
      // It is detached (through a point past the track's end that goes, as in a cut); step 5
      // judges it as a path of its own.
      const auto nearestOnTrack = [&](const Vec3& x, double& distance)
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
      };
      if (!p.remove && p.freeEnd != 0)
      {
        bool far = false;
        for (const Junction& jn : skeleton.junctions)
        {
          double d = 0.0;
          far =
            far ||
            (jn.parentPath == static_cast<int>(pi) && jn.parentPoint >= p.first &&
              jn.parentPoint <= p.last &&
              (nearestOnTrack(
                 path.points[static_cast<std::size_t>(jn.parentPoint)].position_World_mm, d) < 0 ||
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
          int best = p.remove ? dummy : nearestOnTrack(old, bestDistance);
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

} // namespace tube_sections
} // namespace vtouch

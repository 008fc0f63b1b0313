// TubeSectionTracker where clutter touches a vessel next to a junction, on masks made in code
// with paths drawn by hand as the voxel coder draws them on the raw phantom (issue 16 item 5,
// "false vessels on the phantom's clutter"): a lone clean section inside the contact does not
// stop the tube's track, which may end at the junction where the vessel goes on as another
// path; a free end re-traced as far as the tube goes does not drag the paths joined to the
// clutter beyond it onto the tube.
#include "vtouchTubeSectionTracker.h"

#include "vtouchMaskSceneSupport.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <iostream>
#include <vector>

using namespace vtouch;

namespace
{
using Dims = std::array<std::int64_t, 3>;
using mask_scenes::coverage;
using mask_scenes::makeMask;
using mask_scenes::segmentDistance;

/// Points every voxel of arc length through `polyline`, tangents from neighbours.
std::vector<SkeletonPoint> drawn(const std::vector<Vec3>& polyline, double radius)
{
  std::vector<SkeletonPoint> points;
  for (std::size_t i = 0; i + 1 < polyline.size(); ++i)
  {
    const Vec3 d = polyline[i + 1] - polyline[i];
    const int steps = std::max(1, static_cast<int>(std::lround(d.norm())));
    for (int k = 0; k < steps; ++k)
    {
      SkeletonPoint q;
      q.position_World_mm = polyline[i] + d * (static_cast<double>(k) / steps);
      q.radius_mm = radius;
      points.push_back(q);
    }
  }
  SkeletonPoint last;
  last.position_World_mm = polyline.back();
  last.radius_mm = radius;
  points.push_back(last);
  const std::size_t n = points.size();
  for (std::size_t i = 0; i < n; ++i)
  {
    const Vec3 d = points[std::min(n - 1, i + 2)].position_World_mm -
                   points[i >= 2 ? i - 2 : 0].position_World_mm;
    points[i].tangent_World = d * (1.0 / d.norm());
  }
  return points;
}

/// Two paths: `parent` (free ends) and `child`, whose head is joined to the parent's point
/// nearest to the child's first point.
QSkeleton joined(const std::vector<Vec3>& parent,
  double parentRadius,
  const std::vector<Vec3>& child,
  double childRadius)
{
  QSkeleton s;
  SkeletonPath p;
  p.id = 0;
  p.points = drawn(parent, parentRadius);
  SkeletonPath c;
  c.id = 1;
  c.points = drawn(child, childRadius);
  int at = 0;
  for (int i = 0; i < static_cast<int>(p.points.size()); ++i)
  {
    if ((p.points[static_cast<std::size_t>(i)].position_World_mm - child.front()).norm() <
        (p.points[static_cast<std::size_t>(at)].position_World_mm - child.front()).norm())
    {
      at = i;
    }
  }
  c.points.front().position_World_mm = p.points[static_cast<std::size_t>(at)].position_World_mm;
  p.points.front().label = p.points.back().label = PointLabel::EndPoint;
  p.points[static_cast<std::size_t>(at)].label = PointLabel::Bifurcation;
  c.points.front().label = PointLabel::Bifurcation;
  c.points.back().label = PointLabel::EndPoint;
  Junction jn;
  jn.parentPath = 0;
  jn.parentPoint = at;
  jn.childPath = 1;
  jn.childEnd = Junction::End::Head;
  c.head.junction = 0;
  s.paths = { p, c };
  s.junctions = { jn };
  return s;
}

/// Number of the skeleton's points farther than `d` from every segment of `axes`.
int pointsOff(const QSkeleton& s, const std::vector<std::array<Vec3, 2>>& axes, double d)
{
  return static_cast<int>(mask_scenes::pointsOffAxes(s, axes, d).off);
}

void print(const char* what, const QSkeleton& s, const TubeSectionTracker::Result& r)
{
  std::cout << what << ": stretches " << r.stretches << ", re-traced " << r.stretchesTracked
            << ", ended at a junction " << r.stretchesEndedAtJunction << ", lone sections crossed "
            << r.loneSectionsCrossed << ", cut " << r.stretchesCut << ", junctions moved "
            << r.junctionsMoved << ", detached " << r.junctionsDetached << "\n";
  for (std::size_t pi = 0; pi < s.paths.size(); ++pi)
  {
    std::cout << "  path " << pi << ":";
    for (std::size_t i = 0; i < s.paths[pi].points.size(); ++i)
    {
      const Vec3& x = s.paths[pi].points[i].position_World_mm;
      std::cout << " (" << x.x << " " << x.y << " " << x.z << ")"
                << (i < r.sections[pi].size() ? int(r.sections[pi][i]) : -1);
    }
    std::cout << "\n";
  }
}

const SectionGeometry kUnit{};

} // namespace

TEST(TubeSectionTracker, TracksPastALoneCleanSectionInABallToTheJunctionAndKeepsTheThinBranch)
{
  // A vessel of radius 1.5 along x, touched by a ball of radius 3 (0.5 voxel overlap); just past
  // the ball a thin branch (radius 0.9) leaves it at right angles. The path drawn as the coder
  // draws it on the raw phantom (384^3 seed 1 noise 20): along the vessel, up into the ball and
  // round in it (two of its sections there, discs of the ball's, are round and no wider than the
  // vessel's + 1 voxel: lone clean sections between elongated ones), back to the junction, then
  // down the thin branch; the vessel goes on past the junction as the other path. No clean
  // point after the ball lies on the vessel's axis: only the junction can end the tube's track.
  const Dims dims{ 64, 48, 32 };
  const Vec3 a{ 3, 30, 16 }, b{ 60, 30, 16 }, ball{ 26, 34.5, 16 }, blob{ 33, 33.5, 16 },
    fork{ 38, 30, 16 }, tip{ 38, 6, 16 };
  const SparseVesselMask mask = makeMask(dims,
    [&](const Vec3& p)
    {
      return segmentDistance(p, a, b) <= 1.5 || (p - ball).norm() <= 3.0 ||
             (p - blob).norm() <= 2.5 || segmentDistance(p, fork, tip) <= 0.9;
    });
  QSkeleton s = joined({ Vec3{ 5, 30, 16 },
                         Vec3{ 22, 30, 16 },
                         Vec3{ 24, 31.5, 16 },
                         Vec3{ 26, 33.5, 16 },
                         Vec3{ 26, 36.5, 16 },
                         Vec3{ 27, 36, 16 },
                         Vec3{ 29, 34, 16 },
                         blob,
                         Vec3{ 36, 31.5, 16 },
                         fork,
                         Vec3{ 38, 8, 16 } },
    1.5,
    { fork, Vec3{ 58, 30, 16 } },
    1.5);
  ASSERT_EQ(s.validate(), "");
  const int offBefore = pointsOff(s, { { a, b }, { fork, tip } }, 2.0);
  const auto r = TubeSectionTracker::track(s, SectionForeground::of(mask), kUnit);
  print("lone clean section in a ball before a junction", s, r);
  EXPECT_EQ(s.validate(), "");
  // Both rules fired: the ball's sections are wider than the vessel (s > r + max(1, r / 2)).
  EXPECT_GE(r.loneSectionsCrossed, 1);
  EXPECT_EQ(r.stretchesEndedAtJunction, 1);
  EXPECT_GE(offBefore, 3);
  // Every point within 2 voxels of an axis (the vessel's radius + 0.5: none on the ball).
  EXPECT_EQ(pointsOff(s, { { a, b }, { fork, tip } }, 2.0), 0);
  EXPECT_GE(coverage(s, Vec3{ 5, 30, 16 }, Vec3{ 58, 30, 16 }, 1.0, 1.5), 0.99);
  // The thin branch stays, whole.
  EXPECT_GE(coverage(s, fork, Vec3{ 38, 8, 16 }, 2.0, 1.5), 0.99);
}

TEST(TubeSectionTracker, DetachesAPathJoinedToClutterPastAVesselsEndAndKeepsAThinBranchJoined)
{
  // A vessel of radius 1.5 along x ends against a plate 3 voxels thick at vessel intensity (256^3
  // seed 2 noise 50); a thin vessel (radius 0.9) leaves it 2 voxels before its end. The coder's
  // path runs on from the vessel's end along the plate's mid-sheet, and a short path it drew on
  // the plate joins it there, 10 voxels past the vessel's end. The free end is re-traced as far
  // as the tube goes; the path on the plate is not dragged onto the track's end (a segment
  // across the clutter), it is detached; the thin vessel stays joined where it leaves.
  const Dims dims{ 64, 48, 32 };
  const Vec3 a{ 3, 24, 16 }, end{ 30, 24, 16 }, fork{ 28, 24, 16 }, tip{ 28, 6, 16 };
  const auto onPlate = [](const Vec3& p)
  { return p.x >= 30 && p.x <= 52 && p.y >= 10 && p.y <= 38 && p.z >= 15 && p.z <= 17; };
  const SparseVesselMask mask = makeMask(dims,
    [&](const Vec3& p)
    {
      return segmentDistance(p, a, end) <= 1.5 || onPlate(p) ||
             segmentDistance(p, fork, tip) <= 0.9;
    });
  QSkeleton s =
    joined({ Vec3{ 5, 24, 16 }, end, Vec3{ 48, 24, 16 } }, 1.5, { fork, Vec3{ 28, 8, 16 } }, 0.9);
  // The path drawn on the plate, joined to the parent's point at x = 40: 3 points, too short to
  // be judged itself (as the coder's 3-point piece on a blob there).
  SkeletonPath onClutter;
  onClutter.id = 2;
  onClutter.points = drawn({ Vec3{ 40, 24, 16 }, Vec3{ 40, 26, 16 } }, 1.5);
  onClutter.points.front().label = PointLabel::Bifurcation;
  onClutter.points.back().label = PointLabel::EndPoint;
  int at = 0;
  while ((s.paths[0].points[static_cast<std::size_t>(at)].position_World_mm - Vec3{ 40, 24, 16 })
           .norm() > 0.5)
  {
    ++at;
  }
  s.paths[0].points[static_cast<std::size_t>(at)].label = PointLabel::Bifurcation;
  Junction jn;
  jn.parentPath = 0;
  jn.parentPoint = at;
  jn.childPath = 2;
  jn.childEnd = Junction::End::Head;
  onClutter.head.junction = 1;
  s.paths.push_back(onClutter);
  s.junctions.push_back(jn);
  ASSERT_EQ(s.validate(), "");
  const auto r = TubeSectionTracker::track(s, SectionForeground::of(mask), kUnit);
  print("a path joined to a plate past a vessel's end", s, r);
  EXPECT_EQ(s.validate(), "");
  // No path jumps across the plate: consecutive points at most 2 voxels apart.
  double longestStep = 0.0;
  for (const SkeletonPath& path : s.paths)
  {
    for (std::size_t i = 1; i < path.points.size(); ++i)
    {
      longestStep = std::max(longestStep,
        (path.points[i].position_World_mm - path.points[i - 1].position_World_mm).norm());
    }
  }
  EXPECT_LE(longestStep, 2.0);
  // The vessel's path ends at the vessel's end, within the plate's reach of it.
  EXPECT_EQ(pointsOff({ { s.paths[0] }, {} }, { { a, end } }, 2.0), 0);
  // The thin vessel stays joined, whole; the path on the plate is joined to nothing now (step 5
  // judges it alone).
  ASSERT_EQ(s.junctions.size(), 1u);
  for (const SkeletonPath& path : s.paths)
  {
    if (path.points.front().position_World_mm.x > 35.0)
    {
      EXPECT_LT(path.head.junction, 0);
    }
  }
  const SkeletonPath& thin = s.paths[static_cast<std::size_t>(s.junctions[0].childPath)];
  EXPECT_LE(pointsOff({ { thin }, {} }, { { fork, tip } }, 1.0), 0);
  EXPECT_GE(coverage(s, fork, Vec3{ 28, 8, 16 }, 2.0, 1.5), 0.99);
}

TEST(TubeSectionTracker, EndsAFreeEndAtTheVesselsTipNotOnTheEdgeOfAStripBeyondIt)
{
  // A thin vessel (radius 0.7: one voxel wide) along x ends at x = 30 against a strip (a ribbon
  // one voxel thick in the plane z = 16) that crosses its line at x = 31 and runs on from there
  // along x on one side of it, its edge on the vessel's line: as on the raw phantom (256^3 seed 1
  // noise 50, 256^3 seed 3 noise 50: a thin vessel ending against clutter at vessel intensity).
  // The coder's path runs on along the strip's edge. The free end's track from the tube loses
  // it where the strip crosses (two arcs touch the section: no tube's), coasts, then finds only
  // sections that the strip touches: a circle of the thin tube's radius fits the strip's edge
  // as well as the vessel. Kept, that track drew the end 10 voxels past the tip; now the end
  // stays at the tip (confirmedPart) and the vessel is covered to it.
  const Dims dims{ 56, 40, 32 };
  const Vec3 a{ 3, 16, 16 }, tip{ 30, 16, 16 };
  const SparseVesselMask mask = makeMask(dims,
    [&](const Vec3& p)
    {
      const bool vessel = segmentDistance(p, a, tip) <= 0.7;
      const bool across = p.x == 31.0 && p.y >= 6.0 && p.y <= 26.0;
      const bool along = p.x >= 32.0 && p.x <= 50.0 && p.y >= 16.0 && p.y <= 26.0;
      return vessel || (p.z == 16.0 && (across || along));
    });
  QSkeleton s;
  SkeletonPath path;
  path.id = 0;
  path.points = drawn({ Vec3{ 5, 16, 16 }, Vec3{ 42, 16, 16 } }, 0.7);
  path.points.front().label = path.points.back().label = PointLabel::EndPoint;
  s.paths = { path };
  ASSERT_EQ(s.validate(), "");
  const auto r = TubeSectionTracker::track(s, SectionForeground::of(mask), kUnit);
  print("a free end onto the edge of a strip beyond the tip", s, r);
  EXPECT_EQ(s.validate(), "");
  EXPECT_EQ(r.stretchesTracked, 1); // the free end was re-traced
  EXPECT_EQ(r.freeEndsEndedWhereTubeLost, 1);
  double farthest = 0.0;
  for (const SkeletonPath& q : s.paths)
  {
    for (const SkeletonPoint& p : q.points)
    {
      farthest = std::max(farthest, p.position_World_mm.x);
    }
  }
  EXPECT_LE(farthest, tip.x + 0.7 + 1.5); // at most 1.5 voxels outside the vessel
  EXPECT_GE(coverage(s, a, tip, 1.0, 1.5), 0.99);

  // The same vessel going on across the strip to x = 40, the strip only crossing it (a thin
  // vessel past a thin plate at right angles); the coder's points past the crossing drawn 1.5
  // voxels off its axis (no section of their own). The track loses the tube at the crossing as
  // before, and finds it again untouched: the end is re-traced on to the vessel's tip.
  const Vec3 farTip{ 40, 16, 16 };
  const SparseVesselMask crossed = makeMask(dims,
    [&](const Vec3& p)
    {
      return segmentDistance(p, a, farTip) <= 0.7 ||
             (p.z == 16.0 && p.x == 31.0 && p.y >= 6.0 && p.y <= 26.0);
    });
  QSkeleton t;
  path.points = drawn(
    { Vec3{ 5, 16, 16 }, Vec3{ 31, 16, 16 }, Vec3{ 32, 16, 17.5 }, Vec3{ 40, 16, 17.5 } }, 0.7);
  path.points.front().label = path.points.back().label = PointLabel::EndPoint;
  t.paths = { path };
  ASSERT_EQ(t.validate(), "");
  const auto rt = TubeSectionTracker::track(t, SectionForeground::of(crossed), kUnit);
  print("a free end across a strip crossing the vessel", t, rt);
  EXPECT_EQ(t.validate(), "");
  EXPECT_EQ(rt.stretchesTracked, 1);
  EXPECT_EQ(rt.freeEndsEndedWhereTubeLost, 0);
  EXPECT_GE(coverage(t, a, farTip, 1.0, 1.0), 0.99);
  EXPECT_EQ(pointsOff(t, { { a, farTip } }, 1.0), 0);
}

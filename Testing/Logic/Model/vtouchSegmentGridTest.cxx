// The stitcher's neighbour grids (h18s): the coverage check's SegmentGrid and the copy search's
// FragmentSegmentGrid size their cells by the reach, not by the longest segment, so one long
// junction link no longer makes every query visit most of the skeleton (the 128^3 raw phantom's
// stitch on 2 ranks spent 13.6 of 20.8 s in the coverage check's grid before). They must find
// every segment a brute-force search finds and, for the copy search, hand its candidates over in
// the old grid's order (its ties keep the first copy). The attachments' SkeletonPointIndex must
// give every point within the reach, and every moved one, in the scan's order.
#include "vtouchFragmentPointGrid.h"
#include "vtouchFragmentSegmentGrid.h"
#include "vtouchSegmentGrid.h"
#include "vtouchSkeletonPointIndex.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <random>
#include <set>
#include <utility>
#include <vector>

namespace
{
using namespace vtouch;

/// Project rule (the stitcher's copyReach_mm and coverageReach_mm defaults).
constexpr double kReach_mm = 1.5;
/// The scene's box side (mm): 64 voxels of 1 mm, the scale of the phantom's pieces.
constexpr double kBox_mm = 64.0;

double segmentDistance(const Vec3& p, const Vec3& a, const Vec3& b)
{
  const Vec3 ab = b - a;
  const double length2 = ab.dot(ab);
  const double t = length2 > 0.0 ? std::clamp((p - a).dot(ab) / length2, 0.0, 1.0) : 0.0;
  return (a + ab * t - p).norm();
}

/// Forty random walks of 60 points about 0.8 mm apart in the box, on two pieces (seeded), and
/// last a two-point fragment across the box's diagonal: a junction link 110 mm long.
std::vector<SkeletonFragment> walksAndOneLongLink()
{
  std::mt19937 random(18);
  std::uniform_real_distribution<double> inBox(0.0, kBox_mm);
  std::uniform_real_distribution<double> step(-0.8, 0.8);
  std::vector<SkeletonFragment> fragments;
  for (int w = 0; w < 40; ++w)
  {
    SkeletonFragment f;
    f.piece = w % 2;
    Vec3 p{ inBox(random), inBox(random), inBox(random) };
    for (int i = 0; i < 60; ++i)
    {
      SkeletonPoint q;
      q.position_World_mm = p;
      f.points.push_back(q);
      p = p + Vec3{ step(random), step(random), step(random) };
    }
    fragments.push_back(f);
  }
  SkeletonFragment link;
  link.piece = 0;
  for (const Vec3& p : { Vec3{ 0.0, 0.0, 0.0 }, Vec3{ kBox_mm, kBox_mm, kBox_mm } })
  {
    SkeletonPoint q;
    q.position_World_mm = p;
    link.points.push_back(q);
  }
  fragments.push_back(link);
  return fragments;
}

/// Queries: every tenth point of the walks, moved by up to a reach (seeded).
std::vector<Vec3> queries(const std::vector<SkeletonFragment>& fragments)
{
  std::mt19937 random(7);
  std::uniform_real_distribution<double> shift(-kReach_mm, kReach_mm);
  std::vector<Vec3> out;
  for (const SkeletonFragment& f : fragments)
  {
    for (std::size_t i = 0; i < f.points.size(); i += 10)
    {
      out.push_back(f.points[i].position_World_mm + Vec3{ shift(random), shift(random), 0.0 });
    }
  }
  return out;
}

/// Segment s of fragment g: points s to s + 1 (the point itself at the last one), as the copy
/// search measures them.
std::pair<Vec3, Vec3> segmentOf(const SkeletonFragment& f, std::size_t s)
{
  return { f.points[s].position_World_mm,
    f.points[std::min(s + 1, f.points.size() - 1)].position_World_mm };
}

double longestSegment_mm(const std::vector<SkeletonFragment>& fragments)
{
  double longest = 0.0;
  for (const SkeletonFragment& f : fragments)
  {
    for (std::size_t s = 0; s < f.points.size(); ++s)
    {
      const auto [a, b] = segmentOf(f, s);
      longest = std::max(longest, (b - a).norm());
    }
  }
  return longest;
}

TEST(SegmentGrid, VisitsEverySegmentWithinReachAndFewOthersDespiteALongLink)
{
  const std::vector<SkeletonFragment> fragments = walksAndOneLongLink();
  std::vector<std::pair<Vec3, Vec3>> segments;
  for (const SkeletonFragment& f : fragments)
  {
    for (std::size_t s = 0; s < f.points.size(); ++s)
    {
      segments.push_back(segmentOf(f, s));
    }
  }
  SegmentGrid grid(kReach_mm);
  EXPECT_DOUBLE_EQ(grid.cellSize_mm(), kReach_mm);
  for (std::size_t k = 0; k < segments.size(); ++k)
  {
    grid.add(segments[k].first, segments[k].second, k);
  }
  std::size_t visits = 0, found = 0, queried = 0;
  for (const Vec3& p : queries(fragments))
  {
    std::set<std::size_t> visited;
    grid.visitNear(p,
      [&](std::size_t k)
      {
        visited.insert(k);
        ++visits;
      });
    for (std::size_t k = 0; k < segments.size(); ++k)
    {
      if (segmentDistance(p, segments[k].first, segments[k].second) <= kReach_mm)
      {
        EXPECT_EQ(visited.count(k), 1u) << "segment " << k << " within reach, not visited";
        ++found;
      }
    }
    ++queried;
  }
  ASSERT_GT(found, queried); // the queries do meet segments
  // The point of the grid: a query visits a few dozen segments of 2401, not most of them (cells
  // of the reach plus half the longest segment, 56.6 mm here, hold the whole box in 27).
  EXPECT_LT(visits, queried * segments.size() / 20);
}

TEST(SegmentGrid, FindsTheLongLinkFromAnywhereAlongIt)
{
  SegmentGrid grid(kReach_mm);
  grid.add(Vec3{ 0.0, 0.0, 0.0 }, Vec3{ kBox_mm, kBox_mm, kBox_mm }, 7);
  for (double t = 0.0; t <= 1.0; t += 0.01)
  {
    // A reach away from the link, across it.
    const Vec3 p = Vec3{ kBox_mm, kBox_mm, kBox_mm } * t +
                   Vec3{ kReach_mm, -kReach_mm, 0.0 } * (1.0 / std::sqrt(2.0));
    int visits = 0;
    grid.visitNear(p, [&](std::size_t k) { visits += k == 7 ? 1 : 0; });
    EXPECT_GE(visits, 1) << "at t = " << t; // (a segment may sit in several cells)
  }
}

TEST(FragmentSegmentGrid, GivesTheOrderGridsCandidatesWithANearSegmentInItsOrder)
{
  const std::vector<SkeletonFragment> fragments = walksAndOneLongLink();
  const double orderCell_mm = kReach_mm + 0.5 * longestSegment_mm(fragments);
  ASSERT_GT(orderCell_mm, 50.0); // the long link sizes the old cells
  FragmentPointGrid old(orderCell_mm);
  for (std::size_t g = 0; g < fragments.size(); ++g)
  {
    for (std::size_t i = 0; i < fragments[g].points.size(); ++i)
    {
      old.add(fragments[g].points[i].position_World_mm, { g, i });
    }
  }
  const FragmentSegmentGrid grid(fragments, orderCell_mm, kReach_mm);
  // A point is a candidate when the segment before it or the one from it is within the reach.
  const auto near = [&](const FragmentPointGrid::Item& item, const Vec3& p)
  {
    const SkeletonFragment& f = fragments[item.fragment];
    for (std::size_t a = item.point == 0 ? 0 : item.point - 1; a <= item.point; ++a)
    {
      const auto [qa, qb] = segmentOf(f, a);
      if (segmentDistance(p, qa, qb) <= kReach_mm)
      {
        return true;
      }
    }
    return false;
  };
  std::size_t oldVisits = 0, newVisits = 0, candidates = 0;
  for (const Vec3& p : queries(fragments))
  {
    std::vector<std::pair<std::size_t, std::size_t>> expected, got;
    old.visitNear(p,
      [&](const FragmentPointGrid::Item& item)
      {
        ++oldVisits;
        if (near(item, p))
        {
          expected.emplace_back(item.fragment, item.point);
        }
      });
    grid.visitNear(p,
      [&](const FragmentPointGrid::Item& item)
      {
        ++newVisits;
        if (near(item, p))
        {
          got.emplace_back(item.fragment, item.point);
        }
      });
    EXPECT_EQ(got, expected);
    candidates += expected.size();
  }
  ASSERT_GT(candidates, 0u);
  // The old cells hold the whole box: every query visited every point; the new ones a few.
  EXPECT_LT(newVisits * 20, oldVisits);
}

} // namespace

namespace
{

/// The walks as the paths of a skeleton.
QSkeleton walksAsPaths()
{
  QSkeleton s;
  for (const SkeletonFragment& f : walksAndOneLongLink())
  {
    SkeletonPath path;
    path.id = static_cast<int>(s.paths.size());
    path.points = f.points;
    s.paths.push_back(path);
  }
  return s;
}

TEST(SkeletonPointIndex, GivesEveryPointWithinReachAndEveryMovedOneInScanOrder)
{
  QSkeleton s = walksAsPaths();
  SkeletonPointIndex index(s, 2.0);
  // Move two points far from where they were indexed (as the stitcher moves an attached end
  // onto its parent point), one of them next to the first query.
  const Vec3 query = s.paths[3].points[20].position_World_mm;
  s.paths[0].points[0].position_World_mm = query + Vec3{ 0.5, 0.0, 0.0 };
  index.moved(0, 0);
  s.paths[5].points.back().position_World_mm = Vec3{ -50.0, -50.0, -50.0 };
  index.moved(5, s.paths[5].points.size() - 1);
  std::size_t handed = 0, total = 0;
  for (const double reach_mm : { 2.0, 5.0 })
  {
    for (const Vec3& p : queries(walksAndOneLongLink()))
    {
      const Vec3 at = handed == 0 ? query : p;
      const std::vector<std::pair<std::size_t, std::size_t>>& got = index.near(at, reach_mm);
      EXPECT_TRUE(std::is_sorted(got.begin(), got.end()));
      EXPECT_TRUE(std::adjacent_find(got.begin(), got.end()) == got.end());
      const std::set<std::pair<std::size_t, std::size_t>> set(got.begin(), got.end());
      EXPECT_EQ(set.count({ 0, 0 }), 1u);
      EXPECT_EQ(set.count({ 5, s.paths[5].points.size() - 1 }), 1u);
      for (std::size_t k = 0; k < s.paths.size(); ++k)
      {
        for (std::size_t i = 0; i < s.paths[k].points.size(); ++i)
        {
          if ((s.paths[k].points[i].position_World_mm - at).norm() <= reach_mm)
          {
            EXPECT_EQ(set.count({ k, i }), 1u) << "path " << k << " point " << i;
          }
          ++total;
        }
      }
      handed += got.size();
    }
  }
  // A query hands over a few of the 2402 points, not all of them.
  EXPECT_LT(handed * 10, total);
}

} // namespace

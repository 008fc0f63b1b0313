// The stitcher joins what the pieces of a distributed volume kept (issue 19, item 2): skeletons
// in index = world coordinates (1 mm voxels), clipped per piece by SkeletonClipper, stitched,
// then compared with the skeleton before the split: same topology, the same points.
#include "vtouchStitchTestHelpers.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <utility>
#include <numeric>

namespace
{
using namespace vtouch;
using namespace vtouch_test;

/// One path of 19 points from x = `x0` in steps of `dx` (1 mm voxels) across the face x = 10,
/// with a small wave in y: a vessel that crosses the two pieces' face once.
QSkeleton wavyLineAlongX(double x0, double dx)
{
  QSkeleton whole;
  std::vector<SkeletonPoint> points;
  for (int i = 0; i < 19; ++i)
  {
    points.push_back(point(x0 + dx * i, 5.0 + 0.2 * std::sin(i), 5.0));
  }
  whole.paths.push_back(path(0, points));
  return whole;
}

TEST(SkeletonStitcher, APathCutByOneFaceComesBackWhole)
{
  const QSkeleton whole = wavyLineAlongX(1.0, 1.0);
  StitchReport report;
  const QSkeleton s = clipAndStitch({ whole, whole }, twoPieces(), report);
  EXPECT_EQ(s.validate(), "");
  ASSERT_EQ(s.paths.size(), 1u);
  EXPECT_EQ(s.paths[0].points.size(), 19u);
  EXPECT_EQ(report.cutEndsJoined, 1);
  EXPECT_EQ(report.cutEndsUnmatched, 0);
  EXPECT_EQ(freeEnds(s), 2);
  EXPECT_TRUE(allPointsNear(s, whole, 1e-12) && allPointsNear(whole, s, 1e-12));
  // Both ends are still free vessel ends, the join point ordinary.
  EXPECT_EQ(s.paths[0].points.front().label, PointLabel::EndPoint);
  EXPECT_EQ(s.paths[0].points[9].label, PointLabel::Ordinary);
}

TEST(SkeletonStitcher, AStitchedPathRunsAsItsFragmentsRun)
{
  // A path whose head lies in the upper piece and whose tail in the lower one: the lower piece's
  // fragment comes first and its free end is its tail. The stitched path runs head to tail as
  // the pieces' fragments (the coder's order) do, not from the first free end in the fragments'
  // order (h19r: the raw path's re-tracing runs forward along a path).
  const QSkeleton whole = wavyLineAlongX(19.0, -1.0);
  StitchReport report;
  const QSkeleton s = clipAndStitch({ whole, whole }, twoPieces(), report);
  EXPECT_EQ(s.validate(), "");
  ASSERT_EQ(s.paths.size(), 1u);
  ASSERT_EQ(s.paths[0].points.size(), 19u);
  for (std::size_t i = 0; i < 19; ++i)
  {
    EXPECT_EQ(
      s.paths[0].points[i].position_World_mm.x, whole.paths[0].points[i].position_World_mm.x)
      << "point " << i;
  }
}

TEST(SkeletonStitcher, AJunctionRightOnAFaceKeepsItsParentPoint)
{
  // A parent along x at y = 10 and a branch from its point on the face x = 10 into piece 0.
  QSkeleton whole;
  std::vector<SkeletonPoint> trunk, branch;
  for (int i = 0; i < 19; ++i)
  {
    trunk.push_back(point(1.0 + i, 10.0, 5.0));
  }
  for (int i = 0; i < 8; ++i)
  {
    branch.push_back(point(10.0 - 0.7 * i, 10.0 + 0.7 * i, 5.0));
  }
  whole.paths.push_back(path(0, trunk));
  whole.paths.push_back(path(1, branch));
  attach(whole, 1, Junction::End::Head, 0, 9); // trunk point 9 is (10, 10, 5): on the face
  ASSERT_EQ(whole.validate(), "");
  StitchReport report;
  const QSkeleton s = clipAndStitch({ whole, whole }, twoPieces(), report);
  EXPECT_EQ(s.validate(), "");
  EXPECT_EQ(s.paths.size(), 2u);
  ASSERT_EQ(s.junctions.size(), 1u);
  EXPECT_EQ(report.attachmentsResolved, 1);
  EXPECT_EQ(report.cutEndsUnmatched, 0);
  EXPECT_EQ(freeEnds(s), 3);
  EXPECT_EQ(cycleRank(s), 0);
  const Junction& j = s.junctions[0];
  const Vec3 at = s.paths[static_cast<std::size_t>(j.parentPath)]
                    .points[static_cast<std::size_t>(j.parentPoint)]
                    .position_World_mm;
  EXPECT_LT((at - Vec3{ 10.0, 10.0, 5.0 }).norm(), 1e-12);
  EXPECT_EQ(s.pointCount(), whole.pointCount());
  EXPECT_TRUE(allPointsNear(s, whole, 1e-12) && allPointsNear(whole, s, 1e-12));
}

TEST(SkeletonStitcher, AChildOnAPathsRepeatedLastPointHangsOnTheEnd)
{
  // The coder writes a path's last point twice where a child hangs on it (the 256^3 tree seeded
  // on 2 ranks): the child must hang on the end, as in the single run, not on the point before,
  // which left the end a free vessel end (one end more than the single run).
  QSkeleton whole;
  std::vector<SkeletonPoint> trunk, branch, child;
  for (int i = 0; i < 19; ++i)
  {
    trunk.push_back(point(1.0 + i, 10.0, 5.0)); // across the face x = 10
  }
  for (int i = 0; i < 7; ++i)
  {
    branch.push_back(point(5.0, 10.0 + i, 5.0));
  }
  branch.push_back(point(5.0, 16.0, 5.0)); // the repeated last point
  for (int i = 0; i < 7; ++i)
  {
    child.push_back(point(5.0 + 0.6 * i, 16.0 + 0.5 * i, 5.0));
  }
  whole.paths.push_back(path(0, trunk));
  whole.paths.push_back(path(1, branch));
  whole.paths.push_back(path(2, child));
  attach(whole, 1, Junction::End::Head, 0, 4);
  attach(whole, 2, Junction::End::Head, 1, 7);
  ASSERT_EQ(whole.validate(), "");
  ASSERT_EQ(freeEnds(whole), 3);
  StitchReport report;
  const QSkeleton s = clipAndStitch({ whole, whole }, twoPieces(), report);
  EXPECT_EQ(s.validate(), "");
  EXPECT_EQ(report.attachmentsResolved, 2);
  EXPECT_EQ(freeEnds(s), 3);
  EXPECT_EQ(cycleRank(s), 0);
}

/// The parent point of the junction whose child is path `child` (-1, -1 when none).
std::pair<int, int> parentOf(const QSkeleton& s, int child)
{
  for (const Junction& j : s.junctions)
  {
    if (j.childPath == child)
    {
      return { j.parentPath, j.parentPoint };
    }
  }
  return { -1, -1 };
}

TEST(SkeletonStitcher, BranchesOnOneOfTwoPointsWithOneCentreHangOnTheirOwnParentPoint)
{
  // The coder's centres, as a distributed run stitches them before smoothing the whole paths
  // (issue 19 item 2): consecutive voxels of one cluster share its centre, so a trunk has two
  // points at (6, 10, 5), radii 1 and 2, and two branches leave the second (their heads copies
  // of it, radius 2; the 256^3 and 512 x 512 x 256 scaling trees). Each branch must hang on that
  // trunk point, not on the other branch's head (an end at the same distance, which the end rule
  // preferred) nor on the trunk's other point with that centre (the first found).
  QSkeleton whole;
  std::vector<SkeletonPoint> trunk, up, down;
  for (int i = 0; i < 19; ++i)
  {
    const double x = i < 6 ? 1.0 + i : (i == 6 ? 6.0 : 0.0 + i); // points 5 and 6 share (6, 10)
    trunk.push_back(point(x, 10.0, 5.0, i == 5 ? 1.0 : 2.0));
  }
  for (int i = 0; i < 7; ++i)
  {
    up.push_back(point(6.0 - 0.5 * i, 10.0 + 0.8 * i, 5.0, i == 0 ? 2.0 : 1.0));
    down.push_back(point(6.0 - 0.5 * i, 10.0 - 0.8 * i, 5.0, i == 0 ? 2.0 : 1.0));
  }
  whole.paths.push_back(path(0, trunk));
  whole.paths.push_back(path(1, up));
  whole.paths.push_back(path(2, down));
  attach(whole, 1, Junction::End::Head, 0, 6);
  attach(whole, 2, Junction::End::Head, 0, 6);
  ASSERT_EQ(whole.validate(), "");
  StitchReport report;
  const QSkeleton s = clipAndStitch({ whole, whole }, twoPieces(), report);
  EXPECT_EQ(s.validate(), "");
  ASSERT_EQ(s.paths.size(), 3u);
  EXPECT_EQ(report.attachmentsResolved, 2);
  // The trunk is the stitched path of 19 points; both branches hang on its point 6 (12 when the
  // stitch runs it the other way).
  int trunkId = -1;
  for (const SkeletonPath& p : s.paths)
  {
    trunkId = p.points.size() == 19u ? p.id : trunkId;
  }
  ASSERT_GE(trunkId, 0);
  const bool reversed =
    s.paths[static_cast<std::size_t>(trunkId)].points.front().position_World_mm.x > 10.0;
  std::printf("trunk %s\n", reversed ? "reversed" : "as coded");
  const int expected = reversed ? 12 : 6;
  for (const SkeletonPath& p : s.paths)
  {
    if (p.id != trunkId)
    {
      EXPECT_EQ(parentOf(s, p.id), std::make_pair(trunkId, expected)) << "branch " << p.id;
    }
  }
  EXPECT_EQ(freeEnds(s), 4);
  EXPECT_EQ(cycleRank(s), 0);
}

TEST(SkeletonStitcher, ABranchOnTheSecondOfTwoIdenticalPointsHangsThereAsCoded)
{
  // Consecutive voxels of one cluster share its centre and may share its radius: the trunk's
  // points 5 and 6 are the same doubles, (6, 10, 5) with radius 2, and the coder hung the
  // branch on point 6 (the shared CTA thresholded, issue 19 item 2, h17f: the distributed run
  // hung it on the first found, one point off, and the smoothing's corner with it moved 15
  // points by up to 0.078 mm). Distance, end and radius tie: the parent point's neighbours
  // along the trunk (the clipper sends them with the attached end) tell which one it was.
  QSkeleton whole;
  std::vector<SkeletonPoint> trunk, branch;
  for (int i = 0; i < 19; ++i)
  {
    const double x = i < 6 ? 1.0 + i : (i == 6 ? 6.0 : 0.0 + i); // points 5 and 6 share (6, 10)
    trunk.push_back(point(x, 10.0, 5.0, 2.0));
  }
  for (int i = 0; i < 7; ++i)
  {
    branch.push_back(point(6.0 - 0.5 * i, 10.0 + 0.8 * i, 5.0, i == 0 ? 2.0 : 1.0));
  }
  whole.paths.push_back(path(0, trunk));
  whole.paths.push_back(path(1, branch));
  attach(whole, 1, Junction::End::Head, 0, 6);
  ASSERT_EQ(whole.validate(), "");
  StitchReport report;
  const QSkeleton s = clipAndStitch({ whole, whole }, twoPieces(), report);
  EXPECT_EQ(s.validate(), "");
  ASSERT_EQ(s.paths.size(), 2u);
  EXPECT_EQ(report.attachmentsResolved, 1);
  const int trunkId = s.paths[0].points.size() == 19u ? s.paths[0].id : s.paths[1].id;
  const int branchId = trunkId == s.paths[0].id ? s.paths[1].id : s.paths[0].id;
  const bool reversed =
    s.paths[static_cast<std::size_t>(trunkId)].points.front().position_World_mm.x > 10.0;
  EXPECT_EQ(parentOf(s, branchId), std::make_pair(trunkId, reversed ? 12 : 6));
  EXPECT_EQ(freeEnds(s), 3);
}

/// A ring of radius 7 around (10, 10, 5), from angle a0 to a1 (radians), 1 point per ~0.7 mm.
std::vector<SkeletonPoint> arc(double a0, double a1)
{
  std::vector<SkeletonPoint> points;
  const int n = static_cast<int>(std::ceil(std::abs(a1 - a0) * 7.0 / 0.7));
  for (int i = 0; i <= n; ++i)
  {
    const double a = a0 + (a1 - a0) * i / n;
    points.push_back(point(10.0 + 7.0 * std::cos(a), 10.0 + 7.0 * std::sin(a), 5.0));
  }
  return points;
}

TEST(SkeletonStitcher, ALoopSpanningTwoPiecesClosesAgain)
{
  // Neither piece sees the whole ring (their grown extents reach x = 13 and x = 7): each codes
  // an arc with two free ends in its ghost layer; the owned parts have two cut ends each.
  const double pi = std::acos(-1.0);
  QSkeleton left, right;
  left.paths.push_back(path(0, arc(0.4 * pi, 1.6 * pi)));     // x <= ~12.2
  right.paths.push_back(path(0, arc(-0.55 * pi, 0.55 * pi))); // x >= ~8.9
  StitchReport report;
  const QSkeleton s = clipAndStitch({ left, right }, twoPieces(), report);
  EXPECT_EQ(s.validate(), "");
  ASSERT_EQ(s.paths.size(), 1u);
  EXPECT_EQ(report.loopsClosed, 1);
  EXPECT_EQ(report.cutEndsJoined, 2);
  EXPECT_EQ(report.cutEndsUnmatched, 0);
  EXPECT_EQ(freeEnds(s), 0);
  EXPECT_EQ(cycleRank(s), 1);
  // Consecutive points stay neighbours all the way round (no jump at a join).
  const std::vector<SkeletonPoint>& p = s.paths[0].points;
  for (std::size_t i = 0; i < p.size(); ++i)
  {
    const SkeletonPoint& next = p[(i + 1) % p.size()];
    EXPECT_LT((next.position_World_mm - p[i].position_World_mm).norm(), 1.5) << i;
  }
}

TEST(SkeletonStitcher, ARingWhollySeenByOnePieceKeepsItsLoopJunction)
{
  // The ring as the coder writes it: one path whose tail attaches to its own point 0.
  const double pi = std::acos(-1.0);
  QSkeleton whole;
  std::vector<SkeletonPoint> ring = arc(0.0, 2.0 * pi);
  ring.pop_back(); // the last sample repeats point 0
  whole.paths.push_back(path(0, ring));
  attach(whole, 0, Junction::End::Tail, 0, 0);
  StitchReport report;
  const QSkeleton s = clipAndStitch({ whole, whole }, twoPieces(), report);
  EXPECT_EQ(s.validate(), "");
  EXPECT_EQ(cycleRank(s), 1);
  EXPECT_EQ(s.pointCount(), whole.pointCount());
  EXPECT_EQ(report.cutEndsUnmatched + report.attachmentsUnresolved, 0);
}

TEST(SkeletonStitcher, APathCrossingACornerOfFourPiecesComesBackWhole)
{
  const PieceOwnership four({ { 0, 10, 0, 10, 0, 10 },
                              { 10, 20, 0, 10, 0, 10 },
                              { 0, 10, 10, 20, 0, 10 },
                              { 10, 20, 10, 20, 0, 10 } },
    kWhole);
  QSkeleton whole;
  std::vector<SkeletonPoint> diagonal, nearCorner;
  for (int i = 0; i < 17; ++i)
  {
    diagonal.push_back(point(2.0 + i, 2.0 + i, 5.0));    // (10, 10) exactly on the corner
    nearCorner.push_back(point(2.0 + i, 18.3 - i, 3.0)); // across pieces 2 -> 0 / 3 -> 1
  }
  whole.paths.push_back(path(0, diagonal));
  whole.paths.push_back(path(1, nearCorner));
  StitchReport report;
  const QSkeleton s = clipAndStitch({ whole, whole, whole, whole }, four, report);
  EXPECT_EQ(s.validate(), "");
  ASSERT_EQ(s.paths.size(), 2u);
  EXPECT_EQ(report.cutEndsUnmatched, 0);
  EXPECT_EQ(freeEnds(s), 4);
  EXPECT_EQ(s.pointCount(), whole.pointCount());
  EXPECT_TRUE(allPointsNear(s, whole, 1e-12) && allPointsNear(whole, s, 1e-12));
}

TEST(SkeletonStitcher, UnmatchedCutEndsAreReportedAndBecomeFreeEnds)
{
  QSkeleton whole;
  std::vector<SkeletonPoint> points;
  for (int i = 0; i < 19; ++i)
  {
    points.push_back(point(1.0 + i, 5.0, 5.0));
  }
  whole.paths.push_back(path(0, points));
  // Piece 1 found nothing there (its run failed, or saw the vessel elsewhere).
  StitchReport report;
  const QSkeleton s = clipAndStitch({ whole, QSkeleton{} }, twoPieces(), report);
  EXPECT_EQ(s.validate(), "");
  ASSERT_EQ(s.paths.size(), 1u);
  EXPECT_EQ(report.cutEndsUnmatched, 1);
  ASSERT_EQ(report.notes.size(), 1u);
  EXPECT_NE(report.notes[0].find("unmatched cut end of piece 0"), std::string::npos);
  EXPECT_EQ(s.paths[0].points.back().label, PointLabel::EndPoint);
  // Two far-apart cut ends of different pieces are not joined.
  QSkeleton shifted;
  std::vector<SkeletonPoint> far;
  for (int i = 0; i < 19; ++i)
  {
    far.push_back(point(1.0 + i, 15.0, 5.0));
  }
  shifted.paths.push_back(path(0, far));
  const QSkeleton t = clipAndStitch({ whole, shifted }, twoPieces(), report);
  EXPECT_EQ(t.paths.size(), 2u);
  EXPECT_EQ(report.cutEndsUnmatched, 2);
  // A branch lost by both pieces (each placed it on the other's side): its bifurcation is named.
  QSkeleton branched;
  std::vector<SkeletonPoint> trunk, branch;
  for (int i = 0; i < 19; ++i)
  {
    trunk.push_back(point(1.0 + i, 10.0, 5.0));
  }
  for (int i = 0; i < 6; ++i)
  {
    branch.push_back(point(5.0, 10.0 + i, 5.0));
  }
  branched.paths.push_back(path(0, trunk));
  branched.paths.push_back(path(1, branch));
  attach(branched, 1, Junction::End::Head, 0, 4);
  branched.paths[0].points[4].label = PointLabel::Bifurcation;
  QSkeleton trunkOnly = branched;
  trunkOnly.paths.pop_back();
  trunkOnly.junctions.clear();
  clipAndStitch({ trunkOnly, trunkOnly }, twoPieces(), report);
  EXPECT_EQ(report.bifurcationsWithoutBranch, 1);
  clipAndStitch({ branched, branched }, twoPieces(), report);
  EXPECT_EQ(report.bifurcationsWithoutBranch, 0);
  // Nothing at all: an empty skeleton, no crash.
  const QSkeleton empty = SkeletonStitcher().stitch({}, report);
  EXPECT_TRUE(empty.empty());
}
} // namespace

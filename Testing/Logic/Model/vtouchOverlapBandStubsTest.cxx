// The overlap band's stubs (issue 19, item 2): a run a piece sent only as band points, whose cut
// end stitches to nothing, is dropped; the owner's geometry stays. Index = world coordinates
// (1 mm voxels); pieces split at x = 10 (piece 0 owns x < 10; piece 1 sends x >= 6).
#include "vtouchOverlapBandStubs.h"
#include "vtouchStitchTestHelpers.h"

#include <gtest/gtest.h>

namespace
{
using namespace vtouch;
using namespace vtouch_test;

/// A vessel along y at x = 8.5 (piece 0's, inside piece 1's band), y = 1 .. 19, and a branch
/// leaving it at `(8.5, branchY)`: along -x, or (`diagonal`) first at 45 degrees toward +y, then
/// along -x at y = branchY + 3, to x = 0.5.
QSkeleton vesselWithBranch(double branchY, bool diagonal)
{
  QSkeleton s;
  std::vector<SkeletonPoint> vessel;
  for (int i = 0; i < 19; ++i)
  {
    vessel.push_back(point(8.5, 1.0 + i, 5.0));
  }
  std::vector<SkeletonPoint> branch;
  for (int i = 0; i <= 8; ++i)
  {
    const double x = 8.5 - i;
    const double y = diagonal ? branchY + std::min(i, 3) : branchY;
    branch.push_back(point(x, y, 5.0));
  }
  s.paths.push_back(path(0, vessel));
  s.paths.push_back(path(1, branch));
  attach(s, 1, Junction::End::Head, 0, static_cast<int>(branchY) - 1);
  return s;
}

TEST(OverlapBandStubs, ABranchJoinedFartherAlongInTheBandIsTheOwnersOnly)
{
  // As measured on ClientServer.DistributedRawSeeded: the owner (piece 0, as the single run)
  // attaches the branch at y = 8 and leaves at 45 degrees; piece 1, coding from a root of its
  // own, attaches it 3 voxels farther along (y = 11) and leaves straight along -x. Piece 1's
  // three band points (x = 8.5, 7.5, 6.5) run 45 degrees off the owner's copy (no copy) and end
  // at the band's edge with no cut end to meet: a stub.
  const QSkeleton owner = vesselWithBranch(8.0, true);
  const QSkeleton other = vesselWithBranch(11.0, false);
  StitchReport report;
  const QSkeleton s = clipAndStitch({ owner, other }, twoPieces(), report);
  EXPECT_EQ(s.validate(), "");
  EXPECT_EQ(report.bandStubsDropped, 1);
  EXPECT_EQ(report.cutEndsUnmatched, 0);
  EXPECT_EQ(report.pointsDropped, 0);
  // The owner's topology: the vessel's two ends, the branch's end, one bifurcation.
  EXPECT_EQ(freeEnds(s), 3);
  ASSERT_EQ(s.junctions.size(), 1u);
  EXPECT_EQ(cycleRank(s), 0);
  EXPECT_TRUE(allPointsNear(s, owner, 1e-9)); // the owner's geometry
  const Junction& j = s.junctions[0];
  const Vec3 at = s.paths[static_cast<std::size_t>(j.parentPath)]
                    .points[static_cast<std::size_t>(j.parentPoint)]
                    .position_World_mm;
  EXPECT_LT((at - Vec3{ 8.5, 8.0, 5.0 }).norm(), 1e-12);
}

TEST(OverlapBandStubs, ARunWithOwnedPointsIsKeptUnmatched)
{
  // Piece 1 codes a vessel along -x from x = 18 that piece 0 did not code at all: its run holds
  // owned points, so it stays (the cut end at the band's edge is unmatched and said), never
  // dropped as a stub.
  QSkeleton other;
  std::vector<SkeletonPoint> vessel;
  for (int i = 0; i < 17; ++i)
  {
    vessel.push_back(point(18.0 - i, 10.0, 5.0));
  }
  other.paths.push_back(path(0, vessel));
  StitchReport report;
  const QSkeleton s = clipAndStitch({ QSkeleton{}, other }, twoPieces(), report);
  EXPECT_EQ(s.validate(), "");
  EXPECT_EQ(report.bandStubsDropped, 0);
  EXPECT_EQ(report.cutEndsUnmatched, 1);
  ASSERT_EQ(s.paths.size(), 1u);
  EXPECT_EQ(s.paths[0].points.size(), 13u); // x = 18 .. 6: owned and band points
}

TEST(OverlapBandStubs, FindsOnlyBandRunsWithAnUnmatchedCutEndAndNoJoinedOne)
{
  const PieceOwnership pieces = twoPieces();
  const OverlapBandStubs stubs(pieces, IndexFrame{});
  const auto run =
    [](int piece, double x0, double x1, FragmentEnd::Kind head, FragmentEnd::Kind tail)
  {
    SkeletonFragment f;
    f.piece = piece;
    f.points = { point(x0, 5.0, 5.0), point(0.5 * (x0 + x1), 5.0, 5.0), point(x1, 5.0, 5.0) };
    f.head.kind = head;
    f.tail.kind = tail;
    return f;
  };
  using K = FragmentEnd::Kind;
  const std::vector<SkeletonFragment> runs = {
    run(1, 8.0, 6.5, K::Attached, K::Cut), // band only, cut end unmatched: a stub
    run(1, 8.0, 6.5, K::Cut, K::Cut),      // band only, one cut end joined: kept
    run(1, 11.0, 6.5, K::Free, K::Cut),    // holds an owned point (x = 11): kept
    run(0, 8.0, 6.5, K::Free, K::Cut),     // piece 0 owns its points: kept
    run(1, 8.0, 6.5, K::Free, K::Attached) // no cut end: kept
  };
  const std::vector<long> partner = { -1, -1, 7, -1, -1, -1, -1, 2, -1, -1 };
  const std::vector<char> found = stubs.find(runs, partner);
  EXPECT_EQ(found, (std::vector<char>{ 1, 0, 0, 0, 0 }));
  // Without pieces (nothing was sent as a band), or with a partner list that is not the runs',
  // nothing is a stub.
  const PieceOwnership none;
  EXPECT_EQ(OverlapBandStubs(none, IndexFrame{}).find(runs, partner), (std::vector<char>(5, 0)));
  EXPECT_EQ(stubs.find(runs, {}), (std::vector<char>(5, 0)));
}
} // namespace

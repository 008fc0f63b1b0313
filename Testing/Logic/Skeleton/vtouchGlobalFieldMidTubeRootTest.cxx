// The coder's global-field mode near a root in the middle of a tube (issue 19 item 2, h19m): the
// diagnosis of why the root's rank moves a few points near the root away from the single run
// (Docs/CLIENT-SERVER.md, "A root in the middle of a tube"). Ranks as threads (InProcessWorld,
// onEveryRank), the field from DistributedSeedCode, 2 pieces split in z with the 128^3 test
// phantoms' ghost margin (26 voxels for their radius of 3.175).
//
// What holds, and is asserted: away from the root (more than kNearRoot_voxels) every rank's
// points in its owned box lie within 0.1 voxel of the single run's, both ways, with the single
// run's ends and junctions. What does not hold yet, and is printed, not asserted: within
// kNearRoot_voxels of an off-axis root the root's rank orders and joins the two sides leaving the
// root by what it sees (a side's tip at the shared face has the SS where the vessel leaves the
// piece, not the single run's tip beyond; a side the single run reaches only by closing a loop is
// a tip trace in the piece, joined along its branch axis), so the side that keeps the root end
// differs from the single run's (measured, both ways: 2.132 voxel on the ring, 1.054 on the tube).
#include "vtouchDistributedSeedCode.h"
#include "vtouchEveryRank.h"
#include "vtouchPieceGrid.h"
#include "vtouchSkeletonStageTestSupport.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <string>

namespace vtouch
{
namespace
{
using skeleton::Point_mm;
using skeleton::test::Dims;
using Index = std::array<std::int64_t, 3>;

constexpr double kTolerance_voxels = 0.1; // the 0.1 voxel
/// Points this close to the root are the departure under diagnosis (the two sides' first few
/// voxels and their centre adjustment: measured within 4 voxels, 0.507 voxel off at 3 to 4).
constexpr double kNearRoot_voxels = 4.0;

/// The built-in Circle phantom at 128^3 (ClientServer.DistributedExtraction's ring): radius
/// 0.3 N = 38.1 voxels (N = 127) about the volume's centre, in a plane tilted 60 deg about x,
/// tube 0.025 N = 3.175 (the phantom's intensity thresholded in the test; here the distance).
double distanceToRingAxis(const Point_mm& p)
{
  const double c = 63.5, R = 38.1;
  const Point_mm e2{ 0.0, 0.5, std::sqrt(3.0) / 2.0 };
  const Point_mm q{ p[0] - c, p[1] - c, p[2] - c };
  const double v = q[1] * e2[1] + q[2] * e2[2];
  const double w = q[1] * -e2[2] + q[2] * e2[1];
  const double inPlane = std::sqrt(q[0] * q[0] + v * v);
  return std::sqrt((inPlane - R) * (inPlane - R) + w * w);
}

/// A straight tube of radius 3.2 along z from z = 10 to 120, its axis at x = 60.3, y = 60.6.
bool inTube(const Point_mm& p)
{
  const double dx = p[0] - 60.3, dy = p[1] - 60.6;
  return p[2] >= 10.0 && p[2] <= 120.0 && dx * dx + dy * dy <= 3.2 * 3.2;
}

struct RankDeparture
{
  double awayFromRoot_voxels = 0.0; // farthest owned point beyond kNearRoot_voxels of the root
  double nearRoot_voxels = 0.0;     // farthest owned point within it
  bool sameEndsAndJunctions = false;
};

std::vector<Point_mm> pointsOf(const RawSkeleton& s, const Index& lo)
{
  std::vector<Point_mm> out;
  for (const RawSkeletonPath& p : s.paths)
  {
    for (const auto& c : p.center_mm)
    {
      out.push_back({ c[0] + lo[0], c[1] + lo[1], c[2] + lo[2] });
    }
  }
  return out;
}

/// Per rank: how far its owned points lie from the single run's and the single run's owned
/// points from its own (both ways), split at kNearRoot_voxels from the root.
std::vector<RankDeparture> departures(const Dims& dims,
  const std::function<bool(const Point_mm&)>& inside,
  const Index& root)
{
  const SparseVesselMask whole = skeleton::test::makeMask(dims, inside);
  VoxelCodingParameters seeded;
  seeded.hasSeed = true;
  seeded.seedIndex = root;
  const RawSkeleton single = VoxelCoder(whole, seeded).run();
  const std::vector<PieceLayout> pieces = test::layouts(dims, { 1, 1, 2 }, 26);
  const std::vector<RawSkeleton> coded = test::onEveryRank<RawSkeleton>(pieces,
    [&](const PieceLayout& l, RankCollectives& c, RawSkeleton& out)
    {
      const SparseVesselMask mask = test::pieceMask(whole, l);
      DistributedSeedCode code(l, mask, seeded.spacing_mm);
      code.run(c, { root });
      VoxelCodingParameters global;
      global.globalSs_mm = &code.ss();
      out = VoxelCoder(mask, global).run();
    });
  const Point_mm rootPoint{ double(root[0]), double(root[1]), double(root[2]) };
  const std::vector<Point_mm> reference = pointsOf(single, { 0, 0, 0 });
  std::vector<RankDeparture> result(pieces.size());
  for (std::size_t r = 0; r < pieces.size(); ++r)
  {
    const VoxelBox& owned = pieces[r].owned[r];
    const std::vector<Point_mm> mine = pointsOf(coded[r], pieces[r].mine().lo);
    const auto measure = [&](const std::vector<Point_mm>& from, const std::vector<Point_mm>& to)
    {
      for (const Point_mm& p : from)
      {
        if (!owned.contains(std::llround(p[0]), std::llround(p[1]), std::llround(p[2])))
        {
          continue;
        }
        double best = 1e300;
        for (const Point_mm& q : to)
        {
          best = std::min(best, skeleton::distance(p, q));
        }
        double& worst = skeleton::distance(p, rootPoint) <= kNearRoot_voxels
                          ? result[r].nearRoot_voxels
                          : result[r].awayFromRoot_voxels;
        worst = std::max(worst, best);
      }
    };
    measure(mine, reference);
    measure(reference, mine);
    result[r].sameEndsAndJunctions =
      test::endsAndJunctionsIn(coded[r], pieces[r].mine().lo, owned, dims, 3) ==
      test::endsAndJunctionsIn(single, { 0, 0, 0 }, owned, dims, 3);
  }
  return result;
}

void expectOnlyTheRootsNeighbourhoodDeparts(const char* scene,
  const std::function<bool(const Point_mm&)>& inside,
  const Index& root)
{
  SCOPED_TRACE(scene);
  const std::vector<RankDeparture> d = departures({ 128, 128, 128 }, inside, root);
  ASSERT_EQ(d.size(), 2U);
  for (std::size_t r = 0; r < d.size(); ++r)
  {
    SCOPED_TRACE("rank " + std::to_string(r));
    std::printf("%s, root (%lld, %lld, %lld), rank %zu: farthest owned point from the single run "
                "%.3f voxel beyond %.0f voxels of the root, %.3f within (not asserted)\n",
      scene,
      static_cast<long long>(root[0]),
      static_cast<long long>(root[1]),
      static_cast<long long>(root[2]),
      r,
      d[r].awayFromRoot_voxels,
      kNearRoot_voxels,
      d[r].nearRoot_voxels);
    EXPECT_TRUE(d[r].sameEndsAndJunctions);
    EXPECT_LE(d[r].awayFromRoot_voxels, kTolerance_voxels);
  }
}

TEST(VoxelCoderGlobalField, AMidTubeRootMovesPointsOnlyNearTheRoot)
{
  // The ring seeded off its axis near its top (rank 1; ClientServer.DistributedExtraction's
  // ring seeded there moves 15 of 202 points up to 2.101 voxels): the fronts meet at its bottom
  // in rank 0; the single run reaches the root's second side by closing the loop.
  expectOnlyTheRootsNeighbourhoodDeparts(
    "ring", [](const Point_mm& p) { return distanceToRingAxis(p) <= 3.175; }, { 68, 84, 98 });
  // A tube seeded off its axis where the side leaving the piece (65 voxels to its end, 38 in
  // rank 1's grown piece) is traced first by the single run and second by rank 1 (the other
  // side: 45 voxels).
  expectOnlyTheRootsNeighbourhoodDeparts("tube", inTube, { 62, 60, 75 });
}

TEST(VoxelCoderGlobalField, AMidTubeRootOnTheAxisGivesTheSingleRunsPoints)
{
  // The same tube and split, the root on the axis: both sides leave the root along one line, so
  // the order in which the root's rank traces them moves no point (the departure above needs an
  // off-axis root; the ring's automatic root or a clicked seed lies anywhere on the tube).
  const std::vector<RankDeparture> d = departures({ 128, 128, 128 }, inTube, { 60, 61, 75 });
  for (std::size_t r = 0; r < d.size(); ++r)
  {
    SCOPED_TRACE("rank " + std::to_string(r));
    EXPECT_TRUE(d[r].sameEndsAndJunctions);
    EXPECT_LE(std::max(d[r].awayFromRoot_voxels, d[r].nearRoot_voxels), kTolerance_voxels);
  }
}

} // namespace
} // namespace vtouch

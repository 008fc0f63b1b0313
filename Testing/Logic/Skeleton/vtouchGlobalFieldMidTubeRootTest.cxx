// The coder's global-field mode near a root in the middle of a tube (issue 19 item 2; diagnosed on
// h19m, fixed on h19n: Docs/CLIENT-SERVER.md, "A root in the middle of a tube"). Ranks as threads
// (InProcessWorld, onEveryRank), the field from DistributedSeedCode, the face tips' answers from
// DistributedFaceTips on the same collectives, pieces grown by the 128^3 test phantoms' ghost
// margin (26 voxels for their radius of 3.175).
//
// Asserted: every rank's points in its owned box lie within 0.1 voxel of the single run's, both
// ways, with the single run's ends and junctions, also next to an off-axis root, where the root's
// rank must order its two sides by the single run's tips beyond its faces and trace a side the
// single run reaches only by closing a loop as that loop's second side. Without the face tips'
// answers the root's rank departs by 2.1 voxels on the ring and 1.05 on the tube (asserted in
// WithoutTheFaceTipsTheRootsRankDeparts, so that the scenes keep exercising the fix).
#include "vtouchDistributedFaceTips.h"
#include "vtouchDistributedSeedCode.h"
#include "vtouchEveryRank.h"
#include "vtouchPhantomGenerator.h"
#include "vtouchPieceGrid.h"
#include "vtouchSkeletonStageTestSupport.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <memory>
#include <string>
#include <tuple>

namespace vtouch
{
namespace
{
using skeleton::Point_mm;
using skeleton::test::Dims;
using Index = std::array<std::int64_t, 3>;

constexpr double kTolerance_voxels = 0.1; // the 0.1 voxel
/// Points this close to the root are the ones the face tips' answers move (measured without
/// them: all departures within 4 voxels of the root); reported apart.
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
  int faceTipRounds = 0; // the face tips' rounds (the same on every rank), 0 without them
  double farthest() const { return std::max(awayFromRoot_voxels, nearRoot_voxels); }
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
  const Index& root,
  const std::array<int, 3>& split,
  bool withFaceTips)
{
  const SparseVesselMask whole = skeleton::test::makeMask(dims, inside);
  VoxelCodingParameters seeded;
  seeded.hasSeed = true;
  seeded.seedIndex = root;
  const RawSkeleton single = VoxelCoder(whole, seeded).run();
  const std::vector<PieceLayout> pieces = test::layouts(dims, split, 26);
  std::vector<int> rounds(pieces.size(), 0);
  const std::vector<RawSkeleton> coded = test::onEveryRank<RawSkeleton>(pieces,
    [&](const PieceLayout& l, RankCollectives& c, RawSkeleton& out)
    {
      const SparseVesselMask mask = test::pieceMask(whole, l);
      DistributedSeedCode code(l, mask, seeded.spacing_mm);
      code.run(c, { root });
      DistributedFaceTips faceTips(c, l);
      VoxelCodingParameters global;
      global.globalSs_mm = &code.ss();
      if (withFaceTips)
      {
        global.faceTipBands = [&faceTips](const skeleton::SkeletonTracer& t)
        { return faceTips.answer(t); };
      }
      out = VoxelCoder(mask, global).run();
      rounds[static_cast<std::size_t>(l.rank)] = faceTips.outcome().rounds;
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
    result[r].faceTipRounds = rounds[r];
    result[r].sameEndsAndJunctions =
      test::endsAndJunctionsIn(coded[r], pieces[r].mine().lo, owned, dims, 3) ==
      test::endsAndJunctionsIn(single, { 0, 0, 0 }, owned, dims, 3);
  }
  return result;
}

/// Codes `inside` seeded at `root` on the pieces of `split` with the face tips' answers; expects
/// every rank's owned points within 0.1 voxel of the single run's, with its ends and junctions.
/// Returns the face tips' rounds.
int expectTheSingleRunsPoints(const char* scene,
  const std::function<bool(const Point_mm&)>& inside,
  const Index& root,
  const std::array<int, 3>& split)
{
  SCOPED_TRACE(scene);
  const std::vector<RankDeparture> d = departures({ 128, 128, 128 }, inside, root, split, true);
  EXPECT_EQ(d.size(), static_cast<std::size_t>(split[0] * split[1] * split[2]));
  for (std::size_t r = 0; r < d.size(); ++r)
  {
    SCOPED_TRACE("rank " + std::to_string(r));
    std::printf("%s on %zu pieces, root (%lld, %lld, %lld), rank %zu: farthest owned point from "
                "the single run %.3f voxel within %.0f voxels of the root, %.3f beyond; face "
                "tips' rounds %d\n",
      scene,
      d.size(),
      static_cast<long long>(root[0]),
      static_cast<long long>(root[1]),
      static_cast<long long>(root[2]),
      r,
      d[r].nearRoot_voxels,
      kNearRoot_voxels,
      d[r].awayFromRoot_voxels,
      d[r].faceTipRounds);
    EXPECT_TRUE(d[r].sameEndsAndJunctions);
    EXPECT_LE(d[r].farthest(), kTolerance_voxels);
  }
  return d.empty() ? 0 : d[0].faceTipRounds;
}

/// The built-in Circle phantom's ring at 128^3 (ClientServer.DistributedExtraction's).
bool inRing(const Point_mm& p)
{
  return distanceToRingAxis(p) <= 3.175;
}

// The ring seeded off its axis near its top (in rank 1; ClientServer.DistributedExtraction's
// ring seeded there moved 15 of 202 points up to 2.101 voxels before the fix): the fronts meet at
// its bottom in rank 0, whose tip's trace climbs one side into rank 1; the single run reaches
// the root's other side only by closing the loop.
const Index kRingRoot{ 68, 84, 98 };
// A tube seeded off its axis where the side leaving the piece (65 voxels to its end, 38 in rank
// 1's grown piece) is traced first by the single run, while rank 1 sees its other side's end
// (45 voxels) as the farther tip.
const Index kTubeRoot{ 62, 60, 75 };

TEST(VoxelCoderGlobalField, AMidTubeRootGivesTheSingleRunsPointsOnTwoPieces)
{
  expectTheSingleRunsPoints("ring", inRing, kRingRoot, { 1, 1, 2 });
  expectTheSingleRunsPoints("tube", inTube, kTubeRoot, { 1, 1, 2 });
}

TEST(VoxelCoderGlobalField, AMidTubeRootGivesTheSingleRunsPointsOnFourPieces)
{
  // Split in y and z: the ring's two sides leave the root's piece through two faces.
  expectTheSingleRunsPoints("ring", inRing, kRingRoot, { 1, 2, 2 });
  expectTheSingleRunsPoints("ring", inRing, kRingRoot, { 1, 1, 4 });
}

TEST(VoxelCoderGlobalField, AMidTubeRootsFarTipTwoPiecesAwayCrossesThePieceBetween)
{
  // Four pieces along the tube (owned z 0-30, 31-62, 63-94, 95-127): the root (z 75) in piece 2,
  // the lower end (z 10) in piece 0; piece 1 only passes the vessel through, so the lower end's
  // band reaches piece 2's face tip (z 38) only through piece 1's rounds: piece 0 hands the
  // chain to piece 1 (round 1), piece 1 tells piece 2 (round 2), none reports (round 3).
  const int rounds = expectTheSingleRunsPoints("tube", inTube, kTubeRoot, { 1, 1, 4 });
  EXPECT_GE(rounds, 3);
}

TEST(VoxelCoderGlobalField, WithoutTheFaceTipsTheRootsRankDeparts)
{
  // The scenes above exercise the fix: without the face tips' answers the root's rank orders
  // and joins its two sides by what it sees (measured: 2.132 voxel on the ring, 1.054 on the
  // tube, both within kNearRoot_voxels of the root; 0.000 beyond).
  for (const auto& [scene, inside, root] :
    { std::make_tuple("ring", std::function<bool(const Point_mm&)>(inRing), kRingRoot),
      std::make_tuple("tube", std::function<bool(const Point_mm&)>(inTube), kTubeRoot) })
  {
    SCOPED_TRACE(scene);
    const std::vector<RankDeparture> d =
      departures({ 128, 128, 128 }, inside, root, { 1, 1, 2 }, false);
    ASSERT_EQ(d.size(), 2U);
    EXPECT_GT(std::max(d[0].nearRoot_voxels, d[1].nearRoot_voxels), 0.5);
    EXPECT_LE(std::max(d[0].awayFromRoot_voxels, d[1].awayFromRoot_voxels), kTolerance_voxels);
  }
}

/// ClientServer.DistributedExtraction's Y (the built-in phantom, 128^3, radius fraction 0.025,
/// thresholded at 550 as the test does).
std::function<bool(const Point_mm&)> testY()
{
  PhantomSpec spec;
  spec.shape = PhantomShape::YBifurcation;
  spec.dimensions = { 128, 128, 128 };
  spec.radiusFraction = 0.025;
  const PhantomGenerator generator(spec);
  auto voxels = std::make_shared<std::vector<float>>(std::size_t{ 128 } * 128 * 128);
  if (!generator.ok() || !generator.fill(voxels->data()))
  {
    ADD_FAILURE() << "the Y phantom: " << generator.error();
  }
  return [voxels](const Point_mm& p)
  {
    const auto i = static_cast<std::size_t>(p[0] + 128 * (p[1] + 128 * p[2]));
    return (*voxels)[i] >= 550.0F;
  };
}

TEST(VoxelCoderGlobalField, TheYOnFourPiecesGivesTheSingleRunsPoints)
{
  // The Y from its automatic root (24, 107, 79), a branch end, on 2 x 2 pieces in y and z: the
  // pvserver's 4 ranks moved 4 of its points by 0.581 voxel before the face tips' answers.
  expectTheSingleRunsPoints("Y", testY(), { 24, 107, 79 }, { 1, 2, 2 });
}

TEST(VoxelCoderGlobalField, AMidTubeRootOnTheAxisGivesTheSingleRunsPoints)
{
  // The same tube and split, the root on the axis: both sides leave the root along one line
  // (nothing moved even without the face tips' answers); with them, still the single run's.
  expectTheSingleRunsPoints("tube on the axis", inTube, { 60, 61, 75 }, { 1, 1, 2 });
}

} // namespace
} // namespace vtouch

// A junction centre every piece coded, on the edge where four pieces meet, is kept once (issue 19
// item 2, h17y): the Y phantom in the shared CTA's frame on `1 2 2` pieces lost it. The centres
// below are the coder's (the single run's, and every rank's bit for bit): the Y's parent path,
// its points 30-55 of 87, and the first 16 of the 52 points of the branch hung on its point 42.
// The junction centre is owned by rank 2, its two neighbours along the parent by rank 3.
#include "vtouchStitchTestHelpers.h"

#include <gtest/gtest.h>

namespace
{
using namespace vtouch;
using namespace vtouch_test;

/// The Y's frame in the test (vtouchDistributedWholeFrameTest): the shared CTA's spacing and an
/// origin of its kind, 128^3 voxels.
IndexFrame ctaLikeFrame()
{
  IndexFrame f;
  f.origin_mm = { -156.445, -24.6094, 17.3021 };
  f.spacing_mm = { 0.878906, 0.878906, 1.50009 };
  return f;
}

std::vector<SkeletonPoint> points(const std::vector<std::array<double, 4>>& c)
{
  std::vector<SkeletonPoint> out;
  for (const auto& q : c)
  {
    out.push_back(point(q[0], q[1], q[2], q[3]));
  }
  return out;
}

/// The parent path's points 30-55 (world mm, radius mm); the junction is point 12 here (42).
std::vector<SkeletonPoint> parentCentres()
{
  return points({
    { -110.91766920000001, 42.333940333333324, 119.70824399999999, 2.4723773002624512 },
    { -110.01451751724139, 41.581313931034494, 118.8944020689655, 2.4723773002624512 },
    { -109.17938844444443, 40.592404370370382, 118.53039555555554, 2.4723773002624512 },
    { -108.36884180000001, 39.785112933333345, 117.858133, 2.4723773002624512 },
    { -107.47737999999998, 38.954337500000008, 117.21880892857142, 2.4723773002624512 },
    { -106.71593148387097, 37.906333225806435, 116.84032999999999, 2.4723773002624512 },
    { -105.89162896296295, 37.044228296296296, 116.25248111111109, 2.4723773002624512 },
    { -105.11139643749999, 36.199908874999991, 115.55799499999999, 2.4723773002624512 },
    { -104.40770337931033, 35.186515103448272, 115.06658620689655, 2.4723773002624512 },
    { -103.55910448275861, 34.368223310344838, 114.44585931034482, 2.4723773002624512 },
    { -102.41002894667685, 33.14717757483983, 113.90247595934164, 2.4723773002624512 },
    { -101.11786661840145, 31.774083073236383, 113.29142866616493, 2.4723773002624512 },
    { -100.16233797246463, 30.758706675743383, 112.83957120222556, 2.7793447971343994 },
    { -99.842435825905795, 31.464726993843122, 112.60438424934348, 2.6367180347442627 },
    { -99.172030256166323, 32.619074348544551, 112.08114070037971, 2.4723773002624512 },
    { -98.437203999999994, 33.398395999999998, 111.80776999999999, 2.4723773002624512 },
    { -97.558297999999994, 34.277301999999999, 110.30767999999999, 2.4723773002624512 },
    { -97.23184719999999, 34.779533999999998, 110.39339942857141, 2.4723773002624512 },
    { -97.133020903225798, 35.042800774193559, 110.59801999999999, 2.4723773002624512 },
    { -95.419626733333331, 36.943316866666663, 109.057605, 2.4723773002624512 },
    { -94.694765548387096, 37.707870580645157, 108.13012999999999, 2.4723773002624512 },
    { -94.596059259259263, 37.955686370370373, 108.41867777777776, 2.4723773002624512 },
    { -92.900096199999979, 39.667925466666681, 107.10748799999999, 2.4723773002624512 },
    { -92.001343935483845, 40.656458451612913, 106.63003999999999, 2.4723773002624512 },
    { -91.405955999999989, 41.30854999999999, 107.30749999999999, 2.4723773002624512 },
    { -90.441994580645158, 42.38591864516129, 105.27511999999999, 2.4723773002624512 },
  });
}
constexpr int kJunction = 12;

/// The branch's first 16 points; point 0 is the junction centre (the coder's copy of it).
std::vector<SkeletonPoint> branchCentres()
{
  std::vector<std::array<double, 4>> c{
    { -100.16233797246463, 30.758706675743383, 112.83957120222556, 2.7793447971343994 },
    { -100.40204543011222, 30.12213386179149, 113.0057574037815, 2.7436881065368652 },
    { -100.60865988158864, 29.459081521462799, 113.13832076385125, 2.7080314159393311 },
    { -100.78218132689381, 28.769549654757313, 113.2372612824348, 2.6723747253417969 },
  };
  for (int k = 0; k < 12; ++k)
  {
    c.push_back(
      { -101.073922, 28.124959999999994 - 0.878906 * k, 113.30785999999999, 2.6367180347442627 });
  }
  return points(c);
}

TEST(SkeletonOverlap, AJunctionCentreEveryPieceCodedOnAnEdgeOfFourPiecesIsKeptOnce)
{
  // 128^3 voxels in 1 x 2 x 2 pieces sharing the layers y = 63 and z = 63 (x fastest in the
  // ranks), with the owners the Y phantom's run found (the junction rank 2's, its neighbours 3's).
  const VoxelExtent6 whole{ 0, 127, 0, 127, 0, 127 };
  const PieceOwnership ownership({ { 0, 127, 0, 63, 0, 63 },
                                   { 0, 127, 63, 127, 0, 63 },
                                   { 0, 127, 0, 63, 63, 127 },
                                   { 0, 127, 63, 127, 63, 127 } },
    whole);
  const IndexFrame frame = ctaLikeFrame();
  const std::vector<SkeletonPoint> parent = parentCentres();
  ASSERT_EQ(ownership.owner(frame.toIndex(parent[kJunction].position_World_mm)), 2);
  ASSERT_EQ(ownership.owner(frame.toIndex(parent[kJunction - 1].position_World_mm)), 3);
  ASSERT_EQ(ownership.owner(frame.toIndex(parent[kJunction + 1].position_World_mm)), 3);
  QSkeleton coded;
  coded.paths.push_back(path(0, parent));
  coded.paths.push_back(path(1, branchCentres()));
  attach(coded, 1, Junction::End::Head, 0, kJunction);
  // Every rank coded these centres; each sends its owned points and its overlap band, and the
  // first rank stitches them with the filter's settings (DistributedCenterline::gatherAndStitch).
  StitchReport report;
  const QSkeleton s = clipAndStitchAsTheFilter(coded, ownership, frame, 4, 1.50009, report);
  EXPECT_EQ(s.validate(), "");
  EXPECT_EQ(report.cutEndsUnmatched, 0);
  EXPECT_EQ(report.pointsDropped, 0);
  EXPECT_EQ(report.strayPointsDropped, 0);
  ASSERT_EQ(s.paths.size(), 2u);
  ASSERT_EQ(s.junctions.size(), 1u);
  const Junction& j = s.junctions[0];
  const SkeletonPath& stitchedParent = s.paths[static_cast<std::size_t>(j.parentPath)];
  // The parent path: every centre once, in order (before h17y: 25 points, the junction centre
  // kept by neither rank 2 nor rank 3, and the branch hung on point 43).
  ASSERT_EQ(stitchedParent.points.size(), parent.size());
  const bool reversed =
    stitchedParent.points.front().position_World_mm.x != parent.front().position_World_mm.x;
  for (std::size_t i = 0; i < parent.size(); ++i)
  {
    const Vec3& q = stitchedParent.points[reversed ? parent.size() - 1 - i : i].position_World_mm;
    EXPECT_EQ((q - parent[i].position_World_mm).norm(), 0.0) << i;
  }
  // The branch hangs on the junction centre, its own first point that centre.
  const Vec3& at = stitchedParent.points[static_cast<std::size_t>(j.parentPoint)].position_World_mm;
  EXPECT_EQ((at - parent[kJunction].position_World_mm).norm(), 0.0);
  const SkeletonPath& branch = s.paths[static_cast<std::size_t>(j.childPath)];
  EXPECT_EQ(branch.points.size(), branchCentres().size());
  const Vec3& end =
    (j.childEnd == Junction::End::Head ? branch.points.front() : branch.points.back())
      .position_World_mm;
  EXPECT_EQ((end - parent[kJunction].position_World_mm).norm(), 0.0);
}

} // namespace

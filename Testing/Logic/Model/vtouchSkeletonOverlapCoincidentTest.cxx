// A centre both pieces coded at one position is one point of one vessel (issue 19 item 2, h17c):
// the real CTA seeded on 4 ranks lost it. The centres below are the coder's, as ranks 0 and 1
// computed them (the same on both, and the single run's), on the branch from (-213.5, -116.7,
// 27.6) mm to the volume's top; the executive splits the CTA (157 x 393 x 34 voxels) into 4 slabs
// in y, and the path crosses the face y = 98 between ranks 0 and 1.
#include "vtouchStitchTestHelpers.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>

namespace
{
using namespace vtouch;
using namespace vtouch_test;

/// The shared CTA's frame (../shared/data/vmtk-aorta/aorta.mha: offset, spacing, the in-plane
/// axes flipped).
IndexFrame ctaFrame()
{
  IndexFrame f;
  f.origin_mm = { -156.445, -24.6094, 0.0 };
  f.spacing_mm = { 0.878906, 0.878906, 1.50009 };
  f.direction = { -1.0, 0.0, 0.0, 0.0, -1.0, 0.0, 0.0, 0.0, 1.0 };
  return f;
}

/// The branch's 25 centres (world mm, radius mm), in the coder's order. Points 10 and 11 are one
/// voxel coded twice (index y = 102.0, the edge of rank 0's overlap band); point 12, at index
/// (56.0, 100.25, 24.0) in rank 1's owned box, is the one the stitch lost: rank 0's fragment
/// starts there, its direction one-sided (12 -> 13), 44 degrees off rank 1's central difference
/// (11 -> 13) at the same position.
std::vector<SkeletonPoint> branchCentres()
{
  const double c[25][4] = {
    { -213.51184957647061, -116.59466795294128, 27.672248470588233, 4.0897235870361328 },
    { -213.30763318235296, -116.66963346470595, 27.879613852941176, 3.2870191931724548 },
    { -213.10341678823531, -116.74459897647063, 28.086979235294116, 2.4843147993087769 },
    { -212.89920039411766, -116.8195644882353, 28.294344617647056, 1.6816104054450989 },
    { -212.69498399999998, -116.89453, 28.501709999999999, 0.8789060115814209 },
    { -211.816078, -116.015624, 30.001799999999999, 0.8789060115814209 },
    { -210.40982839999998, -118.3007796, 35.102105999999999, 1.2429608106613159 },
    { -209.32584433333332, -117.04101433333335, 35.002099999999999, 0.8789060115814209 },
    { -208.08072749999999, -116.23535049999998, 35.252114999999996, 0.8789060115814209 },
    { -207.64127450000001, -115.35644450000001, 35.627137499999996, 1.2429608106613159 },
    { -206.76236849999998, -114.257812, 36.002159999999996, 0.8789060115814209 },
    { -206.76236849999998, -114.257812, 36.002159999999996, 0.8789060115814209 },
    { -205.663736, -112.71972650000001, 36.002159999999996, 0.8789060115814209 },
    { -205.95670466666667, -112.20703133333333, 37.502249999999997, 0.8789060115814209 },
    { -205.37076733333333, -110.44921933333333, 37.502249999999997, 0.8789060115814209 },
    { -204.78483, -109.863282, 38.627317499999997, 0.8789060115814209 },
    { -204.96061119999999, -108.984376, 39.902394000000001, 0.8789060115814209 },
    { -204.34537699999998, -108.984376, 42.002519999999997, 0.8789060115814209 },
    { -203.027018, -108.10547, 43.502609999999997, 1.2429608106613159 },
    { -203.027018, -108.10547, 43.502609999999997, 0.8789060115814209 },
    { -201.70865899999998, -107.66601700000001, 45.002699999999997, 0.8789060115814209 },
    { -200.82975299999998, -107.226564, 46.502789999999997, 0.8789060115814209 },
    { -199.95084699999998, -107.226564, 47.252834999999997, 0.8789060115814209 },
    { -199.33561279999998, -106.6992204, 48.002879999999998, 0.8789060115814209 },
    { -197.75358199999999, -105.46875199999999, 49.502969999999998, 0.8789060115814209 },
  };
  std::vector<SkeletonPoint> points;
  for (const auto& q : c)
  {
    points.push_back(point(q[0], q[1], q[2], q[3]));
  }
  return points;
}

TEST(SkeletonOverlap, ACentreBothPiecesCodedAtOnePositionIsKeptWhateverItsClippedDirection)
{
  const VoxelExtent6 whole{ 0, 156, 0, 392, 0, 33 };
  const PieceOwnership ownership({ { 0, 156, 0, 98, 0, 33 },
                                   { 0, 156, 98, 196, 0, 33 },
                                   { 0, 156, 196, 294, 0, 33 },
                                   { 0, 156, 294, 392, 0, 33 } },
    whole);
  const IndexFrame frame = ctaFrame();
  QSkeleton coded;
  coded.paths.push_back(path(0, branchCentres()));
  // Every rank sends its owned points and its overlap band (SkeletonClipper), and the first rank
  // stitches them with the filter's settings (DistributedCenterline::gatherAndStitch).
  StitchReport report;
  std::vector<std::size_t> sent;
  const QSkeleton s = clipAndStitchAsTheFilter(coded, ownership, frame, 4, 1.50009, report, &sent);
  ASSERT_EQ(sent.size(), 2u); // ranks 0 and 1
  EXPECT_EQ(s.validate(), "");
  ASSERT_EQ(s.paths.size(), 1u);
  EXPECT_EQ(report.cutEndsJoined, 1);
  EXPECT_EQ(report.cutEndsUnmatched, 0);
  EXPECT_EQ(report.pointsDropped, 0);
  EXPECT_EQ(report.strayPointsDropped, 0);
  // The single run's path: every centre once, in order (before h17c: 24 points, point 12 kept
  // by neither rank; rank 1's copy of it matched rank 0's point 13, 1.61 mm away, as its copy).
  const std::vector<SkeletonPoint> expected = branchCentres();
  const std::vector<SkeletonPoint>& got = s.paths[0].points;
  ASSERT_EQ(got.size(), expected.size());
  const bool reversed =
    (got.front().position_World_mm - expected.front().position_World_mm).norm() >
    (got.back().position_World_mm - expected.front().position_World_mm).norm();
  for (std::size_t i = 0; i < expected.size(); ++i)
  {
    const SkeletonPoint& q = got[reversed ? expected.size() - 1 - i : i];
    EXPECT_LE((q.position_World_mm - expected[i].position_World_mm).norm(), 1e-12) << i;
  }
  // Every point sent by both ranks was kept once: the band's copies are the duplicates.
  EXPECT_EQ(report.duplicatesRemoved,
    static_cast<int>(sent[0] + sent[1] - expected.size()));
}

} // namespace

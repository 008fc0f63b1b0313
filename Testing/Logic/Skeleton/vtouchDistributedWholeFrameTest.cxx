// Every rank computes positions in the whole volume's frame (issue 19 item 2, h17f): a rank
// that computed a point from its piece's origin (the whole origin plus its first voxel's offset,
// rounded once) plus its index in the piece got another double than the single run's whole
// origin plus the whole index (1e-13 to 6e-7 mm apart on the real angiograms), and such a last
// bit once decided an exact tie (the tube-likeness pruner's mid-line test on the TOF-MRA, h19m).
// With PieceInWhole the ranks compute the single run's numbers: on a volume whose origin and
// spacing are not round numbers (the shared CTA's, 0.878906 x 0.878906 x 1.50009 mm, origin
// (-156.445, -24.6094, 17.3021) mm) the stitched points are the single run's bit for bit.
// Docs/CLIENT-SERVER.md, "Departures and what is still to come" (positions).
#include "vtouchDistributedStitchRun.h"
#include "vtouchStitchRunExpectations.h"

#include "vtouchPhantomGenerator.h"
#include "vtouchPieceOwnership.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <vector>

namespace vtouch
{
namespace
{
/// The shared CTA's spacing (aorta.mha, ElementSpacing) and an origin of its kind.
IndexFrame ctaLikeFrame()
{
  IndexFrame frame;
  frame.origin_mm = { -156.445, -24.6094, 17.3021 };
  frame.spacing_mm = { 0.878906, 0.878906, 1.50009 };
  return frame;
}

/// ClientServer.DistributedExtraction's Y (128^3, radius 3.2 voxels), thresholded at 550, coded
/// on `counts` pieces in `frame`.
test::DistributedStitchRun runY(const std::array<int, 3>& counts, const IndexFrame& frame)
{
  PhantomSpec spec;
  spec.shape = PhantomShape::YBifurcation;
  spec.dimensions = { 128, 128, 128 };
  spec.radiusFraction = 0.025;
  const PhantomGenerator phantom(spec);
  if (!phantom.ok())
  {
    throw std::invalid_argument("phantom: " + phantom.error());
  }
  const std::array<std::int64_t, 3> dims{ 128, 128, 128 };
  std::vector<float> voxels(static_cast<std::size_t>(dims[0] * dims[1] * dims[2]));
  phantom.fill(voxels.data());
  GhostMarginRule rule;
  rule.largestRadius_mm = 3.2 * frame.spacing_mm[2]; // the largest radius the voxels allow
  const int ghost = rule.voxels(frame.spacing_mm);
  return test::runDistributedStitch(voxels, dims, 550.0, counts, ghost, false, {}, false, frame);
}

/// Every stitched point is a single-run point bit for bit, and the reverse (the nearest point's
/// distance is exactly 0, not within a rounding: the same operations on the same doubles).
void expectTheSingleRunsPointsExactly(const test::DistributedStitchRun& run)
{
  test::expectSameNetwork(run);
  std::size_t single = 0, stitched = 0;
  for (const SkeletonPath& p : run.single.paths)
  {
    single += p.points.size();
  }
  for (const SkeletonPath& p : run.stitched.paths)
  {
    stitched += p.points.size();
  }
  EXPECT_EQ(stitched, single);
  EXPECT_EQ(test::farthestPoint_mm(run.stitched, run.single), 0.0);
  EXPECT_EQ(test::farthestPoint_mm(run.single, run.stitched), 0.0);
}

TEST(DistributedWholeFrame, TheYOnTwoPiecesOfACtaLikeFrameIsTheSingleRunBitForBit)
{
  const test::DistributedStitchRun run = runY({ 1, 1, 2 }, ctaLikeFrame());
  EXPECT_GE(run.report.cutEndsJoined, 1); // a vessel crosses the face
  expectTheSingleRunsPointsExactly(run);
}

TEST(DistributedWholeFrame, TheYOnFourPiecesOfACtaLikeFrameIsTheSingleRunBitForBit)
{
  const test::DistributedStitchRun run = runY({ 2, 2, 1 }, ctaLikeFrame());
  EXPECT_GE(run.report.cutEndsJoined, 1);
  expectTheSingleRunsPointsExactly(run);
}

/// The single run's junction: its parent point and the first point of the branch hung there.
struct JunctionAt
{
  Vec3 parent_World_mm;
  Vec3 childEnd_World_mm;
};

std::vector<JunctionAt> junctionsOf(const QSkeleton& s)
{
  std::vector<JunctionAt> out;
  for (const Junction& j : s.junctions)
  {
    const SkeletonPath& child = s.paths[static_cast<std::size_t>(j.childPath)];
    out.push_back({ s.paths[static_cast<std::size_t>(j.parentPath)]
                      .points[static_cast<std::size_t>(j.parentPoint)]
                      .position_World_mm,
      (j.childEnd == Junction::End::Head ? child.points.front() : child.points.back())
        .position_World_mm });
  }
  return out;
}

bool samePosition(const Vec3& a, const Vec3& b)
{
  return a.x == b.x && a.y == b.y && a.z == b.z;
}

/// Issue 19 item 2 (h17y): on `1 2 2` pieces of the CTA's frame the Y's junction centre lies by
/// the edge where the four pieces meet (whole index (64.04, 63.00, 63.69)), owned by rank 2, its
/// two neighbours along the parent path by rank 3. Every rank codes it; rank 2 sent it in a band
/// fragment of 6 points and rank 3 dropped its copy for rank 2's. The lone point then swapped with
/// its nearest copy (the lowest piece's, a tie at 0 mm) or nothing, and was dropped as a copy of
/// rank 3's kept neighbours: the junction point lost, the branch hung one point on, 0.708 mm. It
/// now swaps back with rank 3's copy.
TEST(DistributedWholeFrame, TheYOnFourPiecesAcrossAnEdgeOfACtaLikeFrameKeepsItsJunctionPoint)
{
  const test::DistributedStitchRun run = runY({ 1, 2, 2 }, ctaLikeFrame());
  expectTheSingleRunsPointsExactly(run);
  const std::vector<JunctionAt> single = junctionsOf(run.single);
  const std::vector<JunctionAt> stitched = junctionsOf(run.stitched);
  ASSERT_EQ(single.size(), 1u);
  ASSERT_EQ(stitched.size(), 1u);
  EXPECT_TRUE(samePosition(stitched[0].parent_World_mm, single[0].parent_World_mm));
  EXPECT_TRUE(samePosition(stitched[0].childEnd_World_mm, single[0].childEnd_World_mm));
  EXPECT_EQ(run.report.pointsDropped, 0);
  EXPECT_EQ(run.report.strayPointsDropped, 0);
}

/// The same rule on every split of two to eight pieces the executive makes of the Y, in the
/// CTA's frame and a TOF-MRA-like one (0.52 x 0.52 x 0.65 mm): the single run's points exactly.
TEST(DistributedWholeFrame, TheYOnEverySplitOfCtaAndTofLikeFramesIsTheSingleRunBitForBit)
{
  IndexFrame tofLike = ctaLikeFrame();
  tofLike.spacing_mm = { 0.52, 0.52, 0.65 };
  for (const IndexFrame& frame : { ctaLikeFrame(), tofLike })
  {
    for (const std::array<int, 3>& counts : std::vector<std::array<int, 3>>{
           { 1, 1, 2 }, { 1, 2, 1 }, { 2, 1, 1 }, { 2, 2, 1 }, { 1, 2, 2 }, { 2, 2, 2 } })
    {
      SCOPED_TRACE(::testing::Message() << "spacing z " << frame.spacing_mm[2] << " mm, pieces "
                                        << counts[0] << " " << counts[1] << " " << counts[2]);
      expectTheSingleRunsPointsExactly(runY(counts, frame));
    }
  }
}

} // namespace
} // namespace vtouch

namespace vtouch
{
namespace
{
/// A diagnostic: VESSELTOUCH_WF_SPLIT="a b c", VESSELTOUCH_WF_SPACING="x y z" (mm).
TEST(DistributedWholeFrame, DISABLED_AnySplit)
{
  std::array<int, 3> counts{ 1, 1, 2 };
  IndexFrame frame = ctaLikeFrame();
  if (const char* s = std::getenv("VESSELTOUCH_WF_SPLIT"))
  {
    std::sscanf(s, "%d %d %d", &counts[0], &counts[1], &counts[2]);
  }
  if (const char* s = std::getenv("VESSELTOUCH_WF_SPACING"))
  {
    std::sscanf(s, "%lf %lf %lf", &frame.spacing_mm[0], &frame.spacing_mm[1], &frame.spacing_mm[2]);
  }
  const test::DistributedStitchRun run = runY(counts, frame);
  expectTheSingleRunsPointsExactly(run);
  // Where they depart: each run's points without an exact twin in the other (path, index).
  const auto departing = [](const QSkeleton& a, const QSkeleton& b, const char* name)
  {
    for (const SkeletonPath& p : a.paths)
    {
      for (std::size_t i = 0; i < p.points.size(); ++i)
      {
        QSkeleton one;
        one.paths.push_back(SkeletonPath{});
        one.paths[0].points.push_back(p.points[i]);
        const double d = test::farthestPoint_mm(one, b);
        if (d > 0.0)
        {
          const Vec3& q = p.points[i].position_World_mm;
          std::printf("%s path %d of %zu point %zu (%.3f, %.3f, %.3f) mm: %.3g mm\n",
            name,
            p.id,
            p.points.size(),
            i,
            q.x,
            q.y,
            q.z,
            d);
        }
      }
    }
  };
  departing(run.single, run.stitched, "single");
  departing(run.stitched, run.single, "stitched");
}
} // namespace
} // namespace vtouch

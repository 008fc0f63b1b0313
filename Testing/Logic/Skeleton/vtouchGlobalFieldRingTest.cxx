// The coder's global-field mode on a ring longer than a grown piece (issue 19 item 2, h19l): the
// ring is split in 2 pieces along z, seeded at its lowest point (rank 0), so its two SS fronts
// meet at its top, in rank 1's piece, where both legs enter from the shared face (each entry a
// local minimum of the field: a root band of its own for the trace stage). Rank 1 must keep the
// meeting as the single run does (the second leg, attached where the fronts met), so that the
// stitch closes the ring; ranks as threads (InProcessWorld, onEveryRank), the field from
// DistributedSeedCode.
#include "vtouchDistributedSeedCode.h"
#include "vtouchEveryRank.h"
#include "vtouchPieceGrid.h"
#include "vtouchSkeletonStageTestSupport.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

namespace vtouch
{
namespace
{
using skeleton::Point_mm;
using skeleton::test::Dims;

/// The test's ring (the built-in Circle phantom's shape, scaled): centre c, radius R, in the plane
/// spanned by x and a vector tilted 60 deg about x (so it spans z from c - 0.87 R to c + 0.87 R).
struct Ring
{
  Point_mm c{ 40.0, 40.0, 40.0 };
  double R = 24.0;
  double tube = 2.5; // voxels
  Point_mm e2{ 0.0, 0.5, std::sqrt(3.0) / 2.0 };

  Point_mm at(double t) const
  {
    return {
      c[0] + R * std::cos(t), c[1] + R * std::sin(t) * e2[1], c[2] + R * std::sin(t) * e2[2]
    };
  }

  double distanceToAxis(const Point_mm& p) const
  {
    const Point_mm q{ p[0] - c[0], p[1] - c[1], p[2] - c[2] };
    const double u = q[0];
    const double v = q[1] * e2[1] + q[2] * e2[2];
    const double w = q[1] * -e2[2] + q[2] * e2[1]; // along the plane's normal
    const double inPlane = std::sqrt(u * u + v * v);
    return std::sqrt((inPlane - R) * (inPlane - R) + w * w);
  }
};

/// The farthest distance (voxels) from a sample of the ring's axis inside `box` (whole index) to
/// the nearest voxel of `skeleton` (offset by `lo`): large when a leg of the ring is missing.
double farthestAxisGap(const Ring& ring,
  const RawSkeleton& skeleton,
  const std::array<std::int64_t, 3>& lo,
  const VoxelBox& box)
{
  double worst = 0.0;
  for (int s = 0; s < 720; ++s)
  {
    const Point_mm a = ring.at(2.0 * 3.14159265358979 * s / 720.0);
    if (!box.contains(std::llround(a[0]), std::llround(a[1]), std::llround(a[2])))
    {
      continue;
    }
    double best = 1e300;
    for (const RawSkeletonPath& p : skeleton.paths)
    {
      for (const auto& v : p.voxels)
      {
        best = std::min(best,
          skeleton::distance(
            a, { double(v[0] + lo[0]), double(v[1] + lo[1]), double(v[2] + lo[2]) }));
      }
    }
    worst = std::max(worst, best);
  }
  return worst;
}

TEST(VoxelCoderGlobalField, ARingsFrontsMeetingInAPieceKeepTheirMeeting)
{
  const Dims dims{ 80, 80, 80 };
  const Ring ring;
  const SparseVesselMask whole = skeleton::test::makeMask(
    dims, [&](const Point_mm& p) { return ring.distanceToAxis(p) <= ring.tube; });
  // The seed at the ring's lowest point: the fronts meet at its top (z ~ 61), which only rank 1
  // holds (2 pieces split at z = 39, ghost margin 8: rank 0 holds z <= 47, rank 1 z >= 31).
  const Point_mm low = ring.at(-0.5 * 3.14159265358979);
  const std::array<std::int64_t, 3> root{
    std::llround(low[0]), std::llround(low[1]), std::llround(low[2])
  };
  ASSERT_TRUE(
    whole.test(static_cast<std::uint64_t>(root[0] + dims[0] * (root[1] + dims[1] * root[2]))));
  VoxelCodingParameters seeded;
  seeded.hasSeed = true;
  seeded.seedIndex = root;
  const RawSkeleton single = VoxelCoder(whole, seeded).run();
  ASSERT_EQ(single.loops, 1);

  constexpr int kInset = 3;
  const std::vector<PieceLayout> pieces = test::layouts(dims, { 1, 1, 2 }, 8);
  ASSERT_EQ(pieces.size(), 2U);
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
  for (std::size_t r = 0; r < pieces.size(); ++r)
  {
    SCOPED_TRACE("rank " + std::to_string(r));
    const PieceLayout& l = pieces[r];
    const VoxelBox& owned = l.owned[r];
    const std::pair<int, int> expected =
      test::endsAndJunctionsIn(single, { 0, 0, 0 }, owned, dims, kInset);
    const std::pair<int, int> got =
      test::endsAndJunctionsIn(coded[r], l.mine().lo, owned, dims, kInset);
    const double gap = farthestAxisGap(ring, coded[r], l.mine().lo, owned);
    std::printf("rank %zu: %zu paths, %zu junctions; in its owned box %d ends / %d junctions "
                "(single run %d / %d), the ring's axis at most %.2f voxel from its skeleton\n",
      r,
      coded[r].paths.size(),
      coded[r].junctions.size(),
      got.first,
      got.second,
      expected.first,
      expected.second,
      gap);
    EXPECT_EQ(got, expected);
    EXPECT_LE(gap, 2.0); // both legs of the arc the piece owns are on its skeleton
  }
  // Where the fronts met (rank 1), the single run has a junction: the second leg attached there.
  EXPECT_EQ(
    test::endsAndJunctionsIn(single, { 0, 0, 0 }, pieces[1].owned[1], dims, kInset).second, 1);
}

} // namespace
} // namespace vtouch

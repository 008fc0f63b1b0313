// Private to Logic/Skeleton: the arithmetic of the automatic root's end cap (SeedCodeStage's
// double propagation), written once so that the single run and the distributed run
// (vtouch::DistributedRootChoice) compute the same numbers from the same integers.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

namespace vtouch
{
namespace skeleton
{

/// Project rule (issue 19 item 2, Docs/CLIENT-SERVER.md): the far end of a propagation is,
/// among the voxels of its last SS bucket (the largest farBucket(), buckets as wide as the
/// smallest voxel side, the SS queue's), the one with the largest whole-volume linear index. It
/// used to be the last voxel the bucket queue popped, an order inside the last bucket that no
/// distributed run reproduces. Not simply the largest SS: that moved the root of a noisy ring
/// (VoxelCodingSkeletonFilter.NoisyRingsKeepTheirLoopOverNoiseSeeds, noise 60, seed 2) to where
/// its loop is lost and changed the Y phantom's centerline; this rule changes neither.
inline std::uint64_t farBucket(float ss_mm, double bucketWidth_mm)
{
  return static_cast<std::uint64_t>(static_cast<double>(ss_mm) / bucketWidth_mm);
}

/// True when (bucketA, linA) is farther than (bucketB, linB) by the rule above.
inline bool fartherVoxel(std::uint64_t bucketA,
  std::uint64_t linA,
  std::uint64_t bucketB,
  std::uint64_t linB)
{
  return bucketA > bucketB || (bucketA == bucketB && linA > linB);
}

/// The centroid, in voxel indices, of `count` voxels whose indices sum to `sum` (exact integer
/// sums, one division: the same double on one rank as summed over many, in any order).
inline std::array<double, 3> indexCentroid(const std::array<std::int64_t, 3>& sum,
  std::uint64_t count)
{
  const auto n = static_cast<double>(count);
  return { static_cast<double>(sum[0]) / n,
    static_cast<double>(sum[1]) / n,
    static_cast<double>(sum[2]) / n };
}

/// The voxel whose centre is nearest `centroid` (voxel indices), clamped to `dims`.
inline std::array<std::int64_t, 3> nearestIndex(const std::array<double, 3>& centroid,
  const std::array<std::int64_t, 3>& dims)
{
  std::array<std::int64_t, 3> v{};
  for (int a = 0; a < 3; ++a)
  {
    v[a] = std::clamp<std::int64_t>(std::llround(centroid[a]), 0, dims[a] - 1);
  }
  return v;
}

/// A 2x2x2 block region's centre in fine voxel indices (block I covers voxels 2 I and 2 I + 1),
/// from the sum of its block indices.
inline std::array<double, 3> blockCentre(const std::array<std::int64_t, 3>& blockSum,
  std::uint64_t count)
{
  const std::array<double, 3> c = indexCentroid(blockSum, count);
  return { 2.0 * c[0] + 0.5, 2.0 * c[1] + 0.5, 2.0 * c[2] + 0.5 };
}

/// The fine voxels searched around a block region's centre for the nearest vessel voxel: the
/// blocks around it, [floor - 2, ceil + 2] per axis, clamped to `dims`.
struct CentreWindow
{
  std::array<std::int64_t, 3> lo{}, hi{};
  CentreWindow(const std::array<double, 3>& centre, const std::array<std::int64_t, 3>& dims)
  {
    for (int a = 0; a < 3; ++a)
    {
      lo[a] = std::max<std::int64_t>(0, static_cast<std::int64_t>(std::floor(centre[a])) - 2);
      hi[a] =
        std::min<std::int64_t>(dims[a] - 1, static_cast<std::int64_t>(std::ceil(centre[a])) + 2);
    }
  }
  /// Squared distance, mm^2, from voxel (i, j, k)'s centre to `centre`.
  static double distance2_mm2(const std::array<double, 3>& centre,
    const double sp[3],
    std::int64_t i,
    std::int64_t j,
    std::int64_t k)
  {
    return (i - centre[0]) * (i - centre[0]) * sp[0] * sp[0] +
           (j - centre[1]) * (j - centre[1]) * sp[1] * sp[1] +
           (k - centre[2]) * (k - centre[2]) * sp[2] * sp[2];
  }
};

} // namespace skeleton
} // namespace vtouch

// Private to Logic/Skeleton: the lattice every voxel-coding stage walks (vtouch::VoxelCoder).
//
// Frames: positions are in the *scaled index frame*, (i * sx, j * sy, k * sz) millimetres; voxels
// are named by their linear index `lin` (32 bits: checked by VoxelCoder) and, in the per-voxel
// arrays of the stages, by their rank among the vessel voxels (SparseVesselMask::rank).
#pragma once

#include "vtouchSparseVesselMask.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

namespace vtouch
{
namespace skeleton
{

using Point_mm = std::array<double, 3>;

inline double distance2(const Point_mm& a, const Point_mm& b)
{
  return (a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
         (a[2] - b[2]) * (a[2] - b[2]);
}

inline double distance(const Point_mm& a, const Point_mm& b)
{
  return std::sqrt(
    (a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

/// The vessel mask with its voxel size, the 26-neighbourhood and index <-> position conversions.
/// Immutable after construction: every stage reads it, none owns it.
struct VoxelGrid
{
  static constexpr int kHalf = 13; // the first 13 offsets precede the voxel: each pair visited once

  /// `spacing_mm`: voxel size per axis (> 0); `clusterWidth_mm`: thickness of the SS bands, 0 =
  /// the largest spacing; `first_Whole`: the whole volume's index of the mask's voxel (0, 0, 0)
  /// (a distributed run's piece, PieceInWhole; 0 for the single run): positions are whole-lattice
  /// mm, (whole index) * spacing, the single run's numbers on every rank.
  VoxelGrid(const SparseVesselMask& m,
    const std::array<double, 3>& spacing_mm,
    double clusterWidth_mm,
    const std::array<std::int64_t, 3>& first_Whole = { 0, 0, 0 });

  const SparseVesselMask& mask;
  std::int64_t nx, ny, nz;
  std::uint32_t nx32, ny32;
  double inverseNx, inverseNy;
  double sp[3]; // voxel size, mm
  double minSpacing, maxSpacing;
  double bandWidth; // SS band thickness (ClusterStage), mm
  float inverseBandWidth;
  int off[26][3];
  std::int64_t offLin[26];
  double offLen[26]; // mm
  float offLenF[26];
  double offMm[26][3];         // offsets in mm
  std::int64_t first_Whole[3]; // the whole index of voxel (0, 0, 0): positions are whole-lattice mm
  std::int64_t rowOffset[9];   // linear offset of the neighbour rows (dj, dk), di = 0

  /// a / d for d >= 1, with `inverse` = 1.0 / d (exact: the estimate is off by at most one).
  static std::uint32_t divide(std::uint32_t a, std::uint32_t d, double inverse)
  {
    auto q = static_cast<std::uint32_t>(static_cast<double>(a) * inverse);
    const std::uint64_t product = static_cast<std::uint64_t>(q) * d;
    if (product > a)
    {
      --q;
    }
    else if (product + d <= a)
    {
      ++q;
    }
    return q;
  }

  void coords(std::uint64_t lin, std::int64_t c[3]) const
  {
    // Linear indices fit 32 bits (checked by VoxelCoder): 32-bit division is much cheaper.
    // A multiplication by the reciprocal, corrected by one, is cheaper than a division.
    const auto l = static_cast<std::uint32_t>(lin);
    const std::uint32_t r = divide(l, nx32, inverseNx);
    c[0] = static_cast<std::int64_t>(l - r * nx32);
    const std::uint32_t k = divide(r, ny32, inverseNy);
    c[1] = static_cast<std::int64_t>(r - k * ny32);
    c[2] = static_cast<std::int64_t>(k);
  }

  /// Calls f(neighbourLin, neighbourIndex, neighbourRank) for every 26-neighbour that is vessel
  /// (`count` = kHalf: only the 13 that precede it in scan order). This is the inner loop of every
  /// pass: away from the volume border a row of three neighbours needs one 3-bit mask window and
  /// one rank computation (their ranks are consecutive), instead of three tests and three ranks.
  template<typename F>
  void forNeighbours(std::uint64_t lin, F&& f, int count = 26) const
  {
    std::int64_t c[3];
    coords(lin, c);
    const bool interior =
      c[0] > 0 && c[0] < nx - 1 && c[1] > 0 && c[1] < ny - 1 && c[2] > 0 && c[2] < nz - 1;
    if (!interior)
    {
      for (int n = 0; n < count; ++n)
      {
        const std::int64_t i = c[0] + off[n][0], j = c[1] + off[n][1], k = c[2] + off[n][2];
        if (i < 0 || j < 0 || k < 0 || i >= nx || j >= ny || k >= nz)
        {
          continue;
        }
        const auto u = static_cast<std::uint64_t>(static_cast<std::int64_t>(lin) + offLin[n]);
        if (mask.test(u))
        {
          f(u, n, mask.rank(u));
        }
      }
      return;
    }
    // Rows q = 0..8 of three neighbours (dk, dj fixed; di = -1, 0, 1); row 4 holds the voxel.
    const int rows = count == kHalf ? 5 : 9;
    for (int q = 0; q < rows; ++q)
    {
      const std::uint64_t first =
        static_cast<std::uint64_t>(static_cast<std::int64_t>(lin) + rowOffset[q] - 1);
      const unsigned bits = mask.window3(first);
      // The voxel itself is not its neighbour, but it counts in the ranks after it.
      const unsigned wanted = q != 4 ? bits : bits & (count == kHalf ? 1U : 5U);
      if (!wanted)
      {
        continue;
      }
      std::uint32_t rank = mask.rankBefore(first);
      for (int di = 0; di < 3; ++di)
      {
        if ((wanted >> di) & 1U)
        {
          const int idx = 3 * q + di;
          f(first + static_cast<std::uint64_t>(di), idx > 13 ? idx - 1 : idx, rank);
        }
        rank += (bits >> di) & 1U;
      }
    }
  }

  std::array<std::int64_t, 3> voxelArray(std::uint32_t lin) const
  {
    std::int64_t c[3];
    coords(lin, c);
    return { c[0], c[1], c[2] };
  }

  /// The centre of voxel `lin`, whole-lattice mm: (whole index) * spacing, as the single run
  /// computes it (the integer sum is exact, so the product is the single run's double).
  Point_mm centerOf(std::uint32_t lin) const
  {
    std::int64_t c[3];
    coords(lin, c);
    return { static_cast<double>(c[0] + first_Whole[0]) * sp[0],
      static_cast<double>(c[1] + first_Whole[1]) * sp[1],
      static_cast<double>(c[2] + first_Whole[2]) * sp[2] };
  }

  /// The linear index of voxel (i, j, k), which must lie in the volume.
  std::uint64_t linOf(std::int64_t i, std::int64_t j, std::int64_t k) const
  {
    return static_cast<std::uint64_t>(i + nx * (j + ny * k));
  }

  /// The voxel whose centre is nearest `p_mm` (whole-lattice mm), clamped to the mask's box.
  /// The rounding is the single run's (on the whole index), then the index is the mask's.
  std::uint64_t nearestVoxel(const Point_mm& p_mm) const
  {
    const std::int64_t size[3] = { nx, ny, nz };
    std::int64_t v[3];
    for (int a = 0; a < 3; ++a)
    {
      v[a] =
        std::clamp<std::int64_t>(std::llround(p_mm[a] / sp[a]) - first_Whole[a], 0, size[a] - 1);
    }
    return linOf(v[0], v[1], v[2]);
  }
};

} // namespace skeleton
} // namespace vtouch

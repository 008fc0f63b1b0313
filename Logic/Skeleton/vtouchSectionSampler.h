// Cross-sections of a vessel, sampled on the volume (issue 16, the raw-angiogram path): what the
// after-coding stages (TubeSectionTracker, TubeLikenessPruner) look at. A foreground (the volume in
// the vessel's intensity range, or a mask) on a grid with origin, spacing and direction; nearest-
// voxel lookups at world points; how far the foreground runs from a point along a direction; and
// the rays of the section through a point normal to a tangent.
#pragma once

#include "vtouchSparseVesselMask.h"
#include "vtouchVector.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <vector>

namespace vtouch
{

/// The grid: world = origin + direction * (index * spacing) (ITK's and VTK's frame).
struct SectionGeometry
{
  std::array<double, 3> origin_mm{ 0.0, 0.0, 0.0 };
  std::array<double, 3> spacing_mm{ 1.0, 1.0, 1.0 };
  std::array<double, 9> direction{ 1, 0, 0, 0, 1, 0, 0, 0, 1 }; ///< row-major
};

/// What the sections are taken of: inside(linear index, x fastest) over a grid of `dims`.
struct SectionForeground
{
  std::array<std::int64_t, 3> dims{ 0, 0, 0 };
  std::function<bool(std::uint64_t)> inside;

  /// A mask as the foreground (the mask must outlive the result).
  static SectionForeground of(const SparseVesselMask& mask)
  {
    return { mask.dims(), [&mask](std::uint64_t lin) { return mask.test(lin); } };
  }
};

/// Whether an intensity lies in the vessel's range [lower, upper] (NaN does not): the one test
/// of the single run's foreground (rangeForeground, Logic/VTK) and of the distributed run's
/// (DistributedVolumePages), so that both are the same predicate (project rule).
inline bool inIntensityRange(double value, double lower, double upper)
{
  return value >= lower && value <= upper;
}

/// The volume's intensities: value(linear index, x fastest) over a grid of `dims` (what the raw
/// path's tip rule reads, vtouchTurnedDimTipTrimmer.h).
struct SectionIntensity
{
  std::array<std::int64_t, 3> dims{ 0, 0, 0 };
  std::function<double(std::uint64_t)> value;
};

/// Nearest-voxel lookups of the foreground at world points (outside the grid is background).
class SectionSampler
{
public:
  SectionSampler(const SectionForeground& fg, const SectionGeometry& g)
    : Fg(fg)
  {
    const auto& d = g.direction;
    // Inverse of the direction matrix (general 3x3, by cofactors).
    const double det = d[0] * (d[4] * d[8] - d[5] * d[7]) - d[1] * (d[3] * d[8] - d[5] * d[6]) +
                       d[2] * (d[3] * d[7] - d[4] * d[6]);
    const double inv = std::abs(det) > 1e-12 ? 1.0 / det : 0.0;
    const double c[9] = { d[4] * d[8] - d[5] * d[7],
      d[2] * d[7] - d[1] * d[8],
      d[1] * d[5] - d[2] * d[4],
      d[5] * d[6] - d[3] * d[8],
      d[0] * d[8] - d[2] * d[6],
      d[2] * d[3] - d[0] * d[5],
      d[3] * d[7] - d[4] * d[6],
      d[1] * d[6] - d[0] * d[7],
      d[0] * d[4] - d[1] * d[3] };
    for (int r = 0; r < 3; ++r)
    {
      for (int k = 0; k < 3; ++k)
      {
        this->ToIndex[3 * r + k] = c[3 * r + k] * inv / g.spacing_mm[r];
      }
      this->Origin[r] = g.origin_mm[r];
    }
    this->Voxel_mm =
      std::max(1e-9, std::min({ g.spacing_mm[0], g.spacing_mm[1], g.spacing_mm[2] }));
  }

  /// The smallest spacing (mm): the unit of every length in voxels.
  double voxel_mm() const { return this->Voxel_mm; }

  /// The nearest voxel's index of world point `p`; false when `p` lies outside the grid.
  bool nearestVoxel(const Vec3& p, std::array<std::int64_t, 3>& idx) const
  {
    const double q[3] = { p.x - this->Origin[0], p.y - this->Origin[1], p.z - this->Origin[2] };
    const auto& dims = this->Fg.dims;
    for (int r = 0; r < 3; ++r)
    {
      const double c = this->ToIndex[3 * r] * q[0] + this->ToIndex[3 * r + 1] * q[1] +
                       this->ToIndex[3 * r + 2] * q[2];
      if (!(c > -0.5 && c < static_cast<double>(dims[r]) - 0.5))
      {
        return false;
      }
      idx[static_cast<std::size_t>(r)] = static_cast<std::int64_t>(std::lround(c));
    }
    return true;
  }

  bool inside(const Vec3& p) const
  {
    std::array<std::int64_t, 3> idx;
    if (!this->nearestVoxel(p, idx))
    {
      return false;
    }
    const auto& dims = this->Fg.dims;
    return this->Fg.inside(
      static_cast<std::uint64_t>(idx[0] + dims[0] * (idx[1] + dims[1] * idx[2])));
  }

  /// How far (mm) the foreground runs from `start` along unit `dir`, up to `limit_mm` (steps
  /// `step_mm`): the last inside sample's distance; 0 when `start` is outside.
  double runLength(const Vec3& start, const Vec3& dir, double limit_mm, double step_mm) const
  {
    if (!this->inside(start))
    {
      return 0.0;
    }
    double s = 0.0;
    while (s < limit_mm && this->inside(start + dir * (s + step_mm)))
    {
      s += step_mm;
    }
    return s;
  }

  /// A unit basis (u, v) of the plane normal to `tangent` (its smallest component picks the
  /// helper axis, so the basis is continuous along a smooth path).
  static void sectionBasis(const Vec3& tangent, Vec3& t, Vec3& u, Vec3& v)
  {
    const double tn = tangent.norm();
    t = tn > 1e-12 ? tangent * (1.0 / tn) : Vec3{ 0.0, 0.0, 1.0 };
    const double ax = std::abs(t.x), ay = std::abs(t.y), az = std::abs(t.z);
    const Vec3 e =
      ax <= ay && ax <= az ? Vec3{ 1, 0, 0 } : (ay <= az ? Vec3{ 0, 1, 0 } : Vec3{ 0, 0, 1 });
    u = e - t * t.dot(e);
    u = u * (1.0 / u.norm());
    v = t.cross(u);
  }

private:
  const SectionForeground& Fg;
  double ToIndex[9];
  double Origin[3];
  double Voxel_mm = 1.0;
};

} // namespace vtouch

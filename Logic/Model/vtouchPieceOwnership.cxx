#include "vtouchPieceOwnership.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace vtouch
{

Vec3 IndexFrame::toIndex(const Vec3& p) const
{
  const double d[3] = { p.x - origin_mm[0], p.y - origin_mm[1], p.z - origin_mm[2] };
  double index[3];
  for (int c = 0; c < 3; ++c)
  {
    // direction^T * d: the direction matrix is a rotation.
    const double along = direction[static_cast<std::size_t>(c)] * d[0] +
                         direction[static_cast<std::size_t>(3 + c)] * d[1] +
                         direction[static_cast<std::size_t>(6 + c)] * d[2];
    index[c] = along / spacing_mm[static_cast<std::size_t>(c)];
  }
  return { index[0], index[1], index[2] };
}

PieceOwnership::PieceOwnership(std::vector<VoxelExtent6> pieces, const VoxelExtent6& whole)
  : pieces_(std::move(pieces))
  , whole_(whole)
{
}

double PieceOwnership::distanceToBox(std::size_t r, const Vec3& index) const
{
  const VoxelExtent6& e = pieces_[r];
  const double x[3] = { index.x, index.y, index.z };
  const double inf = std::numeric_limits<double>::infinity();
  double sum = 0.0;
  for (std::size_t a = 0; a < 3; ++a)
  {
    // The whole extent's faces reach to infinity; a shared face belongs to the upper piece.
    const double lo = e[2 * a] <= whole_[2 * a] ? -inf : e[2 * a];
    const double hi = e[2 * a + 1] >= whole_[2 * a + 1] ? inf : e[2 * a + 1];
    if (x[a] < lo)
    {
      sum += (lo - x[a]) * (lo - x[a]);
    }
    else if (x[a] >= hi)
    {
      const double beyond = x[a] - hi + 1e-9; // on the upper face: outside, just
      sum += beyond * beyond;
    }
  }
  return std::sqrt(sum);
}

int PieceOwnership::owner(const Vec3& index) const
{
  int nearest = -1;
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t r = 0; r < pieces_.size(); ++r)
  {
    const VoxelExtent6& e = pieces_[r];
    if (e[1] < e[0] || e[3] < e[2] || e[5] < e[4])
    {
      continue; // an empty piece owns nothing
    }
    const double d = distanceToBox(r, index);
    if (d == 0.0)
    {
      return static_cast<int>(r);
    }
    if (d < best)
    {
      best = d;
      nearest = static_cast<int>(r);
    }
  }
  return nearest;
}

bool PieceOwnership::withinBand(std::size_t r, const Vec3& index, double band) const
{
  const VoxelExtent6& e = pieces_[r];
  if (e[1] < e[0] || e[3] < e[2] || e[5] < e[4])
  {
    return false;
  }
  return distanceToBox(r, index) <= band;
}

int GhostMarginRule::voxels(const std::array<double, 3>& spacing_mm) const
{
  const double voxel_mm = std::max(1e-12, *std::min_element(spacing_mm.begin(), spacing_mm.end()));
  const double r = std::max(largestRadius_mm, voxel_mm); // max(1 voxel, R), as the fits use
  double reach_mm = std::max({ 7.0 * r + voxel_mm, (minimumBranchLength + 1.0) * r, 2.5 * r });
  if (useVesselness)
  {
    reach_mm += 3.0 * std::max(0.0, vesselnessSigmaMaximum_mm);
  }
  return static_cast<int>(std::ceil(reach_mm / voxel_mm)) + 2;
}

VoxelExtent6 grownExtent(const VoxelExtent6& extent, const VoxelExtent6& whole, int margin)
{
  VoxelExtent6 grown = extent;
  if (extent[1] < extent[0] || extent[3] < extent[2] || extent[5] < extent[4])
  {
    return grown; // empty stays empty
  }
  for (std::size_t a = 0; a < 3; ++a)
  {
    grown[2 * a] = std::max(whole[2 * a], extent[2 * a] - margin);
    grown[2 * a + 1] = std::min(whole[2 * a + 1], extent[2 * a + 1] + margin);
  }
  return grown;
}

} // namespace vtouch

#include "vtouchTurnedDimTipTrimmer.h"

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <vector>

namespace vtouch
{

namespace
{
constexpr double kPi = 3.14159265358979323846;
using Index = std::array<std::int64_t, 3>;

std::uint64_t linear(const Index& i, const std::array<std::int64_t, 3>& dims)
{
  return static_cast<std::uint64_t>(i[0] + dims[0] * (i[1] + dims[1] * i[2]));
}

/// The bridge between 26-neighbours a and b: the other voxels of the block they span (none for
/// a face step). False when a and b are not 26-neighbours or the block leaves the grid.
bool bridgeVoxels(const Index& a,
  const Index& b,
  const std::array<std::int64_t, 3>& dims,
  std::vector<std::uint64_t>& bridge)
{
  bridge.clear();
  Index d{};
  for (std::size_t r = 0; r < 3; ++r)
  {
    d[r] = b[r] - a[r];
    if (std::llabs(d[r]) > 1)
    {
      return false;
    }
  }
  if (d[0] == 0 && d[1] == 0 && d[2] == 0)
  {
    return false;
  }
  for (std::int64_t x = 0; x <= std::llabs(d[0]); ++x)
    for (std::int64_t y = 0; y <= std::llabs(d[1]); ++y)
      for (std::int64_t z = 0; z <= std::llabs(d[2]); ++z)
      {
        const Index v{ a[0] + x * d[0], a[1] + y * d[1], a[2] + z * d[2] };
        if (v == a || v == b)
        {
          continue;
        }
        for (std::size_t r = 0; r < 3; ++r)
        {
          if (v[r] < 0 || v[r] >= dims[r])
          {
            return false;
          }
        }
        bridge.push_back(linear(v, dims));
      }
  return true;
}

/// The angle (degrees) between two directions; 0 when either is degenerate.
double turn_deg(const Vec3& a, const Vec3& b)
{
  const double n = a.norm() * b.norm();
  if (n <= 1e-12)
  {
    return 0.0;
  }
  return std::acos(std::max(-1.0, std::min(1.0, a.dot(b) / n))) * 180.0 / kPi;
}
} // namespace

bool TurnedDimTipTrimmer::isTurnedDimTip(const Evidence& e,
  const SectionGeometry& geometry,
  const Vec3& heading_World,
  const Vec3& p_World_mm,
  const Vec3& q_World_mm,
  const Settings& s)
{
  if (!e.intensity.value || !(e.backgroundNoise > 0.0))
  {
    return false;
  }
  const auto& dims = e.intensity.dims;
  const SectionForeground grid{ dims, [](std::uint64_t) { return true; } };
  const SectionSampler sampler(grid, geometry);
  Index p{}, q{};
  if (!sampler.nearestVoxel(p_World_mm, p) || !sampler.nearestVoxel(q_World_mm, q))
  {
    return false;
  }
  // 1. Dim: below the range (on the raw path the range runs to the volume's maximum).
  if (e.intensity.value(linear(q, dims)) >= e.lower)
  {
    return false;
  }
  // 2. Turned off the path's heading.
  if (turn_deg(heading_World, q_World_mm - p_World_mm) <= s.maximumTurn_deg)
  {
    return false;
  }
  // 3. Joined across background.
  std::vector<std::uint64_t> bridge;
  if (!bridgeVoxels(p, q, dims, bridge) || bridge.empty())
  {
    return false;
  }
  double sum = 0.0;
  for (const std::uint64_t v : bridge)
  {
    sum += e.intensity.value(v);
  }
  const double m = static_cast<double>(bridge.size());
  return sum / m < e.background + s.noiseMargin * e.backgroundNoise / std::sqrt(m);
}

TurnedDimTipTrimmer::Result TurnedDimTipTrimmer::trim(QSkeleton& skeleton,
  const Evidence& e,
  const SectionGeometry& geometry,
  const Settings& s)
{
  Result result;
  const int h = std::max(1, s.headingPoints);
  for (SkeletonPath& path : skeleton.paths)
  {
    int firstChildPoint = static_cast<int>(path.points.size()), lastChildPoint = -1;
    for (const Junction& j : skeleton.junctions)
    {
      if (j.parentPath == path.id)
      {
        firstChildPoint = std::min(firstChildPoint, j.parentPoint);
        lastChildPoint = std::max(lastChildPoint, j.parentPoint);
      }
    }
    const auto at = [&path](int k)
    { return path.points[static_cast<std::size_t>(k)].position_World_mm; };
    // Neither the dropped point nor the new end point may carry a junction.
    int n = static_cast<int>(path.points.size());
    if (path.tail.junction < 0 && n >= h + 2 && lastChildPoint < n - 2 &&
        isTurnedDimTip(e, geometry, at(n - 2) - at(n - 2 - h), at(n - 2), at(n - 1), s))
    {
      path.points.pop_back();
      path.points.back().label = PointLabel::EndPoint;
      ++result.tipsTrimmed;
      --n;
    }
    if (path.head.junction < 0 && n >= h + 2 && firstChildPoint > 1 &&
        isTurnedDimTip(e, geometry, at(1) - at(1 + h), at(1), at(0), s))
    {
      path.points.erase(path.points.begin());
      path.points.front().label = PointLabel::EndPoint;
      for (Junction& j : skeleton.junctions)
      {
        if (j.parentPath == path.id)
        {
          --j.parentPoint;
        }
      }
      ++result.tipsTrimmed;
    }
  }
  return result;
}

} // namespace vtouch

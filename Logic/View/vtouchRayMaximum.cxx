#include "vtouchRayMaximum.h"

#include <algorithm>
#include <cmath>

namespace vtouch
{

bool RayMaximum::clipSegmentToBox(const std::array<double, 3>& low,
  const std::array<double, 3>& high,
  const std::array<double, 3>& start,
  const std::array<double, 3>& end,
  double& t0,
  double& t1)
{
  t0 = 0.0;
  t1 = 1.0;
  for (int axis = 0; axis < 3; ++axis)
  {
    if (!std::isfinite(start[axis]) || !std::isfinite(end[axis]) || !(low[axis] <= high[axis]))
    {
      return false;
    }
    const double delta = end[axis] - start[axis];
    if (delta == 0.0)
    {
      if (start[axis] < low[axis] || start[axis] > high[axis])
      {
        return false;
      }
      continue;
    }
    double a = (low[axis] - start[axis]) / delta;
    double b = (high[axis] - start[axis]) / delta;
    if (a > b)
    {
      std::swap(a, b);
    }
    t0 = std::max(t0, a);
    t1 = std::min(t1, b);
    if (t0 > t1)
    {
      return false;
    }
  }
  return true;
}

bool RayMaximum::clipToVolume(const std::array<int, 3>& dimensions,
  const std::array<double, 3>& start_Index,
  const std::array<double, 3>& end_Index,
  double& t0,
  double& t1)
{
  std::array<double, 3> low{}, high{};
  for (int axis = 0; axis < 3; ++axis)
  {
    if (dimensions[axis] <= 0)
    {
      return false;
    }
    low[axis] = -0.5;
    high[axis] = dimensions[axis] - 0.5;
  }
  return clipSegmentToBox(low, high, start_Index, end_Index, t0, t1);
}

RayMaximumResult RayMaximum::find(const std::array<int, 3>& dimensions,
  const std::array<double, 3>& start_Index,
  const std::array<double, 3>& end_Index,
  const Sampler& sample,
  double step_voxels)
{
  RayMaximumResult result;
  double t0 = 0.0;
  double t1 = 0.0;
  if (!sample || !clipToVolume(dimensions, start_Index, end_Index, t0, t1))
  {
    return result;
  }
  if (!(step_voxels > 0.0) || !std::isfinite(step_voxels) || step_voxels > 1.0)
  {
    step_voxels = 0.25;
  }
  double length = 0.0;
  for (int axis = 0; axis < 3; ++axis)
  {
    const double d = end_Index[axis] - start_Index[axis];
    length += d * d;
  }
  length = std::sqrt(length) * (t1 - t0);
  const int steps = static_cast<int>(std::ceil(length / step_voxels));
  std::array<int, 3> last{ { -1, -1, -1 } };
  for (int s = 0; s <= steps; ++s)
  {
    const double t = steps > 0 ? t0 + (t1 - t0) * s / steps : t0;
    std::array<int, 3> ijk{};
    for (int axis = 0; axis < 3; ++axis)
    {
      const double x = start_Index[axis] + t * (end_Index[axis] - start_Index[axis]);
      ijk[axis] = std::clamp(static_cast<int>(std::lround(x)), 0, dimensions[axis] - 1);
    }
    if (ijk == last)
    {
      continue;
    }
    last = ijk;
    ++result.visited;
    const double value = sample(ijk[0], ijk[1], ijk[2]);
    if (!result.found || value > result.value)
    {
      result.found = true;
      result.index = ijk;
      result.value = value;
    }
  }
  return result;
}

} // namespace vtouch

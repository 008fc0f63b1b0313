// TubeLikenessPruner's bulge by reach (session 20; the product's rule, Docs/CENTERLINES.md "Raw
// angiograms", step 5; no paper gives one): a branch - one end joined, the other free - whose
// farthest point from its joined end is under bulgeFactor times its free end's section radius
// (the median of its last endPoints judged points) is a blob, not a vessel. The coder's path in a
// blob touching a vessel runs to the blob's centre and can hook about it (where the volume's face
// or a plate bends the distance map's ridge: 128^3 seeds 18, 32, session 20), so its length along
// the path clears the pruner's length rule (2.5 times its widest section) while its reach, about
// the parent's radius plus the blob's, does not. A thin branch ends at its thinnest section and
// reaches far beyond it; a vessel's entry into its parent (which measures the parent's sections)
// is never its free end.
#pragma once

#include "vtouchQSkeleton.h"

#include <algorithm>
#include <cstddef>
#include <vector>

namespace vtouch
{

/// `judged[k]`: point k's section was judged (outside every junction's zone); `width_voxels[k]`
/// its section radius (TubeLikenessPruner's). False for a path that is not a branch, or with
/// fewer than `endPoints` judged points, or `endPoints` <= 0.
inline bool isBulgeByReach(const SkeletonPath& path,
  const std::vector<char>& judged,
  const std::vector<double>& width_voxels,
  double bulgeFactor,
  int endPoints,
  double voxel_mm)
{
  const bool headJoined = path.head.junction >= 0;
  if (endPoints <= 0 || headJoined == (path.tail.junction >= 0))
  {
    return false;
  }
  const int n = static_cast<int>(path.points.size());
  const Vec3& joined = (headJoined ? path.points.front() : path.points.back()).position_World_mm;
  double reach_mm = 0.0;
  for (const SkeletonPoint& q : path.points)
  {
    reach_mm = std::max(reach_mm, (q.position_World_mm - joined).norm());
  }
  std::vector<double> end;
  for (int k = 0; k < n && static_cast<int>(end.size()) < endPoints; ++k)
  {
    const std::size_t q = static_cast<std::size_t>(headJoined ? n - 1 - k : k);
    if (judged[q])
    {
      end.push_back(width_voxels[q]);
    }
  }
  if (static_cast<int>(end.size()) < endPoints)
  {
    return false;
  }
  std::nth_element(
    end.begin(), end.begin() + static_cast<std::ptrdiff_t>(end.size() / 2), end.end());
  return reach_mm < bulgeFactor * end[end.size() / 2] * voxel_mm;
}

} // namespace vtouch

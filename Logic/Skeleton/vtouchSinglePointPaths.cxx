#include "vtouchSinglePointPaths.h"

#include <vector>

namespace vtouch
{
namespace
{
/// Appends `voxel` (with its centre and radius) to the `tail` or head end of `path` unless that
/// end is the voxel already.
void extendTo(RawSkeletonPath& path, bool tail, const RawSkeletonPath& single)
{
  const std::array<std::int64_t, 3>& v = single.voxels.front();
  if (path.voxels.empty() || (tail ? path.voxels.back() : path.voxels.front()) == v)
  {
    return;
  }
  if (tail)
  {
    path.voxels.push_back(v);
    path.center_mm.push_back(single.center_mm.front());
    path.radius_mm.push_back(single.radius_mm.front());
  }
  else
  {
    path.voxels.insert(path.voxels.begin(), v);
    path.center_mm.insert(path.center_mm.begin(), single.center_mm.front());
    path.radius_mm.insert(path.radius_mm.begin(), single.radius_mm.front());
  }
}
} // namespace

int dropSinglePointPaths(RawSkeleton& skeleton)
{
  const std::size_t n = skeleton.paths.size();
  const auto single = [&](int p)
  {
    return p >= 0 && static_cast<std::size_t>(p) < n &&
           skeleton.paths[static_cast<std::size_t>(p)].voxels.size() == 1;
  };
  // Each one-voxel path's own attachment (the junction whose child it is), or -1.
  std::vector<int> own(n, -1);
  for (std::size_t i = 0; i < skeleton.junctions.size(); ++i)
  {
    const RawJunction& j = skeleton.junctions[i];
    if (single(j.childPath) && own[static_cast<std::size_t>(j.childPath)] < 0)
    {
      own[static_cast<std::size_t>(j.childPath)] = static_cast<int>(i);
    }
  }
  // A child hanging on a one-voxel path hangs where that path hangs (followed through chains of
  // them), or, when it hangs nowhere, ends free on its voxel.
  std::vector<char> keepJunction(skeleton.junctions.size(), 1);
  for (std::size_t i = 0; i < skeleton.junctions.size(); ++i)
  {
    RawJunction& j = skeleton.junctions[i];
    if (single(j.childPath))
    {
      keepJunction[i] = 0; // the dropped path's own attachment
      continue;
    }
    for (std::size_t hops = 0; single(j.parentPath) && hops <= n; ++hops)
    {
      const int up = own[static_cast<std::size_t>(j.parentPath)];
      if (up < 0)
      {
        RawSkeletonPath& child = skeleton.paths[static_cast<std::size_t>(j.childPath)];
        extendTo(child, j.childTail, skeleton.paths[static_cast<std::size_t>(j.parentPath)]);
        keepJunction[i] = 0;
        break;
      }
      j.parentPath = skeleton.junctions[static_cast<std::size_t>(up)].parentPath;
      j.parentPoint = skeleton.junctions[static_cast<std::size_t>(up)].parentPoint;
    }
    if (single(j.parentPath))
    {
      keepJunction[i] = 0; // a cycle of one-voxel paths: nothing to hang on
    }
  }
  std::vector<int> pathIndex(n, -1);
  int kept = 0;
  for (std::size_t p = 0; p < n; ++p)
  {
    if (!single(static_cast<int>(p)) && !skeleton.paths[p].voxels.empty())
    {
      pathIndex[p] = kept++;
    }
  }
  const int dropped = static_cast<int>(n) - kept;
  if (dropped == 0)
  {
    return 0;
  }
  std::vector<int> junctionIndex(skeleton.junctions.size(), -1);
  std::vector<RawJunction> junctions;
  for (std::size_t i = 0; i < skeleton.junctions.size(); ++i)
  {
    RawJunction j = skeleton.junctions[i];
    if (!keepJunction[i] || j.childPath < 0 || j.parentPath < 0 ||
        pathIndex[static_cast<std::size_t>(j.childPath)] < 0 ||
        pathIndex[static_cast<std::size_t>(j.parentPath)] < 0)
    {
      continue;
    }
    j.childPath = pathIndex[static_cast<std::size_t>(j.childPath)];
    j.parentPath = pathIndex[static_cast<std::size_t>(j.parentPath)];
    junctionIndex[i] = static_cast<int>(junctions.size());
    junctions.push_back(j);
  }
  const auto junction = [&](int j)
  {
    return j >= 0 && static_cast<std::size_t>(j) < junctionIndex.size()
             ? junctionIndex[static_cast<std::size_t>(j)]
             : -1;
  };
  std::vector<RawSkeletonPath> paths;
  paths.reserve(static_cast<std::size_t>(kept));
  for (std::size_t p = 0; p < n; ++p)
  {
    if (pathIndex[p] < 0)
    {
      continue;
    }
    RawSkeletonPath path = std::move(skeleton.paths[p]);
    path.headJunction = junction(path.headJunction);
    path.tailJunction = junction(path.tailJunction);
    paths.push_back(std::move(path));
  }
  skeleton.paths = std::move(paths);
  skeleton.junctions = std::move(junctions);
  return dropped;
}

} // namespace vtouch

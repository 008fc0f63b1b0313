// Voxel coding stage 7: the paths' centres at junctions.
#include "vtouchSkeletonGeometryStage.h"

#include "vtouchJunctionRecentring.h"
#include "vtouchSkeletonPaths.h"

#include <algorithm>
#include <array>

namespace vtouch
{
namespace skeleton
{

GeometryStage::GeometryStage(RawSkeleton& skeleton, std::size_t first, double minSpacing)
  : out(skeleton)
  , firstPath(first)
  , minSpacing_mm(minSpacing)
{
}

void GeometryStage::run()
{
  // A vessel running through a junction gets its own axis back there (vtouchJunctionRecentring);
  // a path through a bifurcation is straightened beyond it.
  straightenThroughPaths(recentreJunctions(out, firstPath, minSpacing_mm));
}

void GeometryStage::straightenThroughPaths(const std::vector<bool>& recentred)
{
  const std::size_t nJunctions = out.junctions.size();
  for (std::size_t j = 0; j < nJunctions; ++j)
  {
    const RawJunction junction = out.junctions[j];
    if (junction.childTail || junction.parentPath < static_cast<int>(firstPath) ||
        (j < recentred.size() && recentred[j]))
    {
      continue;
    }
    RawSkeletonPath& path = out.paths[junction.parentPath];
    const int n = static_cast<int>(path.center_mm.size());
    const int at = junction.parentPoint;
    if (at <= 0 || at >= n - 1)
    {
      continue; // the parent ends here: not a through path
    }
    const double radius = nearbyRadius(path, at);
    const std::array<double, 3> c = path.center_mm[at];
    // The first point beyond one junction radius on the far (tail) side of the junction.
    int a = at + 1;
    while (a < n - 1 && distance(path.center_mm[a], c) <= kJoinNear * radius)
    {
      ++a;
    }
    if (distance(path.center_mm[a], c) <= kJoinNear * radius)
    {
      continue; // the path ends within the junction
    }
    bool pinned = false;
    for (const RawJunction& other : out.junctions)
    {
      pinned = pinned || (other.parentPath == junction.parentPath && other.parentPoint > at &&
                           other.parentPoint < a);
    }
    if (pinned)
    {
      continue;
    }
    const std::array<double, 3> e = path.center_mm[a];
    const double total = distance(e, c);
    for (int i = at + 1; i < a; ++i)
    {
      const double t = std::min(1.0, distance(path.center_mm[i], c) / total);
      path.center_mm[i] = {
        c[0] + t * (e[0] - c[0]), c[1] + t * (e[1] - c[1]), c[2] + t * (e[2] - c[2])
      };
    }
  }
}

} // namespace skeleton
} // namespace vtouch

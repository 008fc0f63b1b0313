#include "vtouchSkeletonPathSmoothing.h"

#include "vtouchCurveGeometry.h"

#include <algorithm>
#include <cstddef>
#include <vector>

namespace vtouch
{

void smoothSkeletonPaths(QSkeleton& skeleton, double largestSpacing_mm, double smoothingWindow_mm)
{
  // A path may turn into a branch where another path joins it (the trace runs from a vessel into
  // its branch): no smoothing window spans such a point, or the fit would cut the corner.
  std::vector<std::vector<std::size_t>> corners(skeleton.paths.size());
  for (const Junction& j : skeleton.junctions)
  {
    if (j.parentPath >= 0 && static_cast<std::size_t>(j.parentPath) < corners.size())
    {
      corners[static_cast<std::size_t>(j.parentPath)].push_back(
        static_cast<std::size_t>(j.parentPoint));
    }
  }
  for (std::size_t p = 0; p < skeleton.paths.size(); ++p)
  {
    SkeletonPath& path = skeleton.paths[p];
    if (path.points.empty())
    {
      continue;
    }
    std::vector<double> radii(path.points.size());
    std::transform(path.points.begin(),
      path.points.end(),
      radii.begin(),
      [](const SkeletonPoint& q) { return q.radius_mm; });
    std::nth_element(radii.begin(), radii.begin() + radii.size() / 2, radii.end());
    // The windows scale with the vessel (skeletonPathWindows, shared with the tube-section
    // tracker's re-smoothing).
    const double medianRadius = radii[radii.size() / 2];
    applyCurveGeometry(
      path, skeletonPathWindows(medianRadius, largestSpacing_mm, smoothingWindow_mm), corners[p]);
    path.points.front().label =
      path.head.junction >= 0 ? PointLabel::Bifurcation : PointLabel::EndPoint;
    path.points.back().label =
      path.tail.junction >= 0 ? PointLabel::Bifurcation : PointLabel::EndPoint;
  }
  for (const Junction& j : skeleton.junctions)
  {
    if (j.parentPath < 0 || j.childPath < 0 ||
        static_cast<std::size_t>(j.parentPath) >= skeleton.paths.size() ||
        static_cast<std::size_t>(j.childPath) >= skeleton.paths.size())
    {
      continue;
    }
    SkeletonPath& parentPath = skeleton.paths[static_cast<std::size_t>(j.parentPath)];
    SkeletonPath& child = skeleton.paths[static_cast<std::size_t>(j.childPath)];
    if (j.parentPoint < 0 || static_cast<std::size_t>(j.parentPoint) >= parentPath.points.size() ||
        child.points.empty())
    {
      continue;
    }
    SkeletonPoint& parent = parentPath.points[static_cast<std::size_t>(j.parentPoint)];
    parent.label = PointLabel::Bifurcation;
    // Each path is smoothed alone: make the attached end coincide with its parent point again.
    SkeletonPoint& end =
      j.childEnd == Junction::End::Tail ? child.points.back() : child.points.front();
    end.position_World_mm = parent.position_World_mm;
  }
}

} // namespace vtouch

#include "vtouchTubeSectionTracker.h"

#include "vtouchTubeSectionParts.h"
#include "vtouchTubeSectionRetracer.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

namespace vtouch
{

using namespace tube_sections;

TubeSectionTracker::Result TubeSectionTracker::track(QSkeleton& skeleton,
  const SectionForeground& foreground,
  const SectionGeometry& geometry,
  const Settings& s)
{
  Result result;
  const SectionSampler sampler(foreground, geometry);
  const double voxel = sampler.voxel_mm();
  const double largestSpacing =
    std::max({ geometry.spacing_mm[0], geometry.spacing_mm[1], geometry.spacing_mm[2] });

  // Junction zones (as TubeLikenessPruner's) and each path's attachment points.
  std::vector<Zone> zones;
  std::vector<std::vector<int>> attached(skeleton.paths.size());
  for (const Junction& j : skeleton.junctions)
  {
    const SkeletonPath& parent = skeleton.paths[static_cast<std::size_t>(j.parentPath)];
    const SkeletonPoint& q = parent.points[static_cast<std::size_t>(j.parentPoint)];
    const SkeletonPath& child = skeleton.paths[static_cast<std::size_t>(j.childPath)];
    const SkeletonPoint& end =
      j.childEnd == Junction::End::Head ? child.points.front() : child.points.back();
    zones.push_back({ q.position_World_mm,
      s.junctionZoneRadii * std::max(q.radius_mm, end.radius_mm) +
        s.junctionZoneMargin_voxels * voxel,
      std::max(q.radius_mm, end.radius_mm) });
    attached[static_cast<std::size_t>(j.parentPath)].push_back(j.parentPoint);
  }

  std::vector<std::vector<std::pair<int, int>>> clutterCuts(skeleton.paths.size());
  // Phase 1: every path's sections and which of them are clean.
  std::vector<PathJudgement> judged;
  judged.reserve(skeleton.paths.size());
  for (std::size_t pi = 0; pi < skeleton.paths.size(); ++pi)
  {
    judged.push_back(judgePath(skeleton.paths[pi], attached[pi], zones, sampler, s, result));
  }
  // Junctions between two vessels (both paths have clean runs: a real bifurcation, not a path
  // the coder drew on clutter joined to a vessel or to another such path), as the points of each
  // path where one is: a stretch that reaches one holds the junction's elongated sections (the
  // other vessel's lumen, over about a radius of the larger vessel) and is never clutter.
  std::vector<std::vector<int>> realJunctionPoints(skeleton.paths.size());
  for (const Junction& jn : skeleton.junctions)
  {
    if (judged[static_cast<std::size_t>(jn.parentPath)].tube &&
        judged[static_cast<std::size_t>(jn.childPath)].tube)
    {
      realJunctionPoints[static_cast<std::size_t>(jn.parentPath)].push_back(jn.parentPoint);
      const SkeletonPath& child = skeleton.paths[static_cast<std::size_t>(jn.childPath)];
      realJunctionPoints[static_cast<std::size_t>(jn.childPath)].push_back(
        jn.childEnd == Junction::End::Head ? 0 : static_cast<int>(child.points.size()) - 1);
    }
  }

  // Phase 2: the stretches of each path.
  result.sections.resize(skeleton.paths.size());
  for (std::size_t pi = 0; pi < skeleton.paths.size(); ++pi)
  {
    PathRetracer(skeleton,
      pi,
      judged[pi],
      realJunctionPoints,
      zones,
      sampler,
      largestSpacing,
      s,
      result,
      clutterCuts)
      .run();
  }
  result.junctionsDetached += cutStretches(skeleton, clutterCuts, result.sections);
  // Attached ends coincide with their parent points (as the filter leaves them).
  for (const Junction& jn : skeleton.junctions)
  {
    const SkeletonPoint& parent = skeleton.paths[static_cast<std::size_t>(jn.parentPath)]
                                    .points[static_cast<std::size_t>(jn.parentPoint)];
    SkeletonPath& child = skeleton.paths[static_cast<std::size_t>(jn.childPath)];
    SkeletonPoint& end =
      jn.childEnd == Junction::End::Head ? child.points.front() : child.points.back();
    end.position_World_mm = parent.position_World_mm;
  }
  return result;
}

} // namespace vtouch

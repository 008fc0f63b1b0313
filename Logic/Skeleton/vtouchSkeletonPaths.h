// Private to Logic/Skeleton: measures on the paths of a raw skeleton, shared by the stages after
// back-tracing (vtouch::VoxelCoder).
#pragma once

#include "vtouchSkeletonVoxelGrid.h"
#include "vtouchVoxelCoding.h"

#include <cstdint>
#include <optional>
#include <unordered_map>
#include <utility>
#include <vector>

namespace vtouch
{
namespace skeleton
{

// Joining a branch across a thick junction (TraceStage) and straightening a path through one
// (GeometryStage), in radii of the junction.
constexpr double kJoinNear = 1.0;    // trace voxels closer than this to the first touch are dropped
constexpr double kJoinFar = 2.0;     // the branch axis is taken between kJoinFar and kJoinNear
constexpr double kJoinOffAxis = 0.5; // the parent point must lie this close to the extended axis

/// Where a trace of `length` (mm) reaches path `path` at its free end (the root, usually), the
/// vessel it would leave from is the path's own within `length` of that end: its largest radius
/// there. A thin strand of noise voxels on an end cap can become the root; the other strands that
/// reach the root are spurs of the vessel, not branches of the strand. 0 elsewhere.
double endCapRadius(const RawSkeletonPath& path, int point, double length);

/// The radius of the vessel a path point lies in, also where the point is on a strand of noise
/// on the wall (whose own radius is about a voxel): the largest radius of the path within three
/// of them, plus `slack_mm`, of the point, grown three times.
double vesselRadiusNear(const RawSkeletonPath& path, int point, double slack_mm);

/// Distance (mm) from a point to the nearest point of the skeleton (brute force: used for a few
/// loop candidates only).
double distanceToSkeleton(const RawSkeleton& skeleton, const Point_mm& q);

/// A free end of a path, judged at its stem (freeEndStem).
struct FreeEnd
{
  int path = -1;
  int point = -1;         // the end point's index on its path
  Point_mm centre{};      // mm
  Point_mm outward{};     // unit: from a point about one radius in toward the end
  double radius_mm = 0.0; // the vessel's radius near the end
};

/// A free end judged where the vessel is: the traced tip can be a strand of noise on the wall
/// (radius about one voxel, pointing into the wall), so the end is taken at its stem, the first
/// point in from the tip whose radius reaches 0.7 of the vessel's (vesselRadiusNear), with the
/// outward direction over about one radius further in. Empty when the path is too short or a
/// junction's point (`attached`, per point of the path) comes first.
std::optional<FreeEnd> freeEndStem(const RawSkeletonPath& path,
  int id,
  bool tail,
  const std::vector<char>& attached,
  double voxel_mm);

/// The junctions as links between (path, point) places, both directions, keyed by placeKey().
using JunctionLinks = std::unordered_multimap<std::uint64_t, std::pair<int, int>>;

std::uint64_t placeKey(std::pair<int, int> place);

/// Adds junction `j` to `links` in both directions: the child's end -> the parent's place, and
/// back.
void linkJunction(const RawSkeleton& skeleton, const RawJunction& j, JunctionLinks& links);

/// Length (mm) of the shortest way along the skeleton between two (path, point) places, with the
/// junctions as `links`; infinity when it is longer than `cutoff` (the search stops there: its
/// cost follows the cutoff, not the skeleton).
double skeletonDistance(const RawSkeleton& skeleton,
  std::pair<int, int> from,
  std::pair<int, int> to,
  double cutoff,
  const JunctionLinks& links);

} // namespace skeleton
} // namespace vtouch

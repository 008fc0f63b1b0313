// Junction re-centring where a side branch leaves a vessel that runs on through the junction
// (a T, a branch off a ring or an arch): the junction goes where the branch's axis meets the
// through vessel's axis, instead of where the back-traces happened to meet.
//
// A back-trace that crosses a junction follows the ridge of the distance map of the merged lumen,
// which bulges toward the branch: the junction point lands off both axes (up to about one
// junction radius), and so do the points within a radius of it on every path that meets there,
// whether a path runs through, leaves as the branch, or turns from the vessel into the branch.
// Away from the junction the traces are on their axes, so each axis is measured where it is its
// own, between `zone` and `zone + reach` from the junction point, and carried into it:
//   - the through vessel is the pair of arms that continue each other (outward directions at
//     least 120 degrees apart) with the most similar calibre, within 10 %; one quadratic per
//     coordinate, fitted to both arms' outer points against the position along their chord,
//     interpolates its axis across the junction (a curved vessel stays curved, a ring round);
//   - every other arm is a branch, a straight line;
//   - the junction centre is the point of the through axis nearest to the branches' lines;
//   - the points within the zone are re-laid: on the through axis for the two through arms, on
//     the straight line from the centre to the arm's first outer point for a branch.
// At a bifurcation (both children thinner than the trunk) no vessel runs through; those
// junctions are left to the caller (the tracer straightens the path through them instead).
// Only centre positions move: voxels, indices, junction links and radii stay, so every path is
// still the 26-connected chain of traced voxels. A junction is also left as it is where the
// evidence is weak: an arm that ends or meets another junction within the zone plus half the
// reach, a branch line that misses the centre by more than half a junction radius, or a centre
// that would move by more than the zone.
#pragma once

#include "vtouchVoxelCoding.h"

#include <cstddef>
#include <vector>

namespace vtouch
{

struct JunctionRecentringParameters
{
  /// Points closer than this many junction radii to the junction point are re-laid. The junction
  /// radius is the largest radius of the paths within one radius of the junction.
  double zoneRadii = 1.0;
  /// The axes are measured over this many junction radii beyond the zone.
  double reachRadii = 1.5;
  /// The zone is at least this many voxels (of the smallest spacing) wide.
  double minimumZone_vox = 1.5;
};

/// Re-centres the junctions whose parent path index is >= `firstPath` (the paths of one
/// component) where a vessel runs through. `minSpacing_mm` is the smallest voxel side. Returns,
/// per junction of `skeleton`, whether it was re-centred.
std::vector<bool> recentreJunctions(RawSkeleton& skeleton,
  std::size_t firstPath,
  double minSpacing_mm,
  const JunctionRecentringParameters& parameters = {});

} // namespace vtouch

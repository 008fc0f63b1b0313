// TubeSectionTracker's parts (internal to Logic/Skeleton; see vtouchTubeSectionTracker.h for the
// rules): the section rays, the tube's centre in a section, following a tube across a contact
// (vtouchTubeSectionFollower.cxx), a path's sections judged (phase 1,
// vtouchTubeSectionJudgement.cxx) and its stretches re-traced (phase 2: a PathRetracer,
// vtouchTubeSectionRetracer.h), and removing clutter stretches from a skeleton
// (vtouchTubeSectionCutting.cxx).
#pragma once

#include "vtouchQSkeleton.h"
#include "vtouchSectionSampler.h"
#include "vtouchTubeSectionTracker.h"

#include <cstddef>
#include <utility>
#include <vector>

namespace vtouch
{
namespace tube_sections
{
using Settings = TubeSectionTracker::Settings;

/// A junction's zone: sections within it are legitimately not a single tube's.
struct Zone
{
  Vec3 centre;
  double radius;
  double vesselRadius = 0.0; ///< the larger radius there (mm)
};

struct Target
{
  int index;
  Vec3 position;
};

struct Track
{
  std::vector<Vec3> centres; ///< from the start's centre on (the start itself first)
  int hit = -1;              ///< the target reached, or -1
  /// How many of the first centres are the tube's for sure (all of them unless the track lost
  /// the tube outside a junction's zone and found only touched sections after it: see
  /// confirmedPart).
  std::size_t confirmed = 1;
};

/// Ray lengths (voxels) of the section through `c` in the plane (u, v): the foreground's run from
/// c along u cos a + v sin a, + half a step; 0 when c is outside. Capped at cap_voxels.
void sectionRays(const SectionSampler& sampler,
  const Vec3& c,
  const Vec3& u,
  const Vec3& v,
  double cap_voxels,
  const Settings& s,
  std::vector<double>& rho);

double median(std::vector<double> x);
double lowerQuartile(std::vector<double> x);

/// The centre of the tube of radius r (voxels) in the section through p normal to t: the circle of
/// radius r fitted to the ends of the wall rays (ending within r + margin), re-taken from the new
/// centre up to four times. False when the section from the centre is not a tube touched at most
/// on one side (see vtouchTubeSectionTracker.h).
/// `touched` (optional): whether, from the centre, rays run on beyond the wall (one thing touches
/// the tube).
bool centreOnTube(const SectionSampler& sampler,
  const Vec3& p,
  const Vec3& tangent,
  double r,
  const Settings& s,
  Vec3& centre,
  bool* touched = nullptr);

bool inZone(const std::vector<Zone>& zones, const Vec3& p);

/// Follows the tube of radius r (voxels) from `start` along `direction` (see
/// vtouchTubeSectionTracker.h, 3).
Track follow(const SectionSampler& sampler,
  const Vec3& start,
  const Vec3& direction,
  double r,
  const std::vector<Target>& targets,
  const std::vector<Zone>& zones,
  double maximumLength_mm,
  const Settings& s);

/// The part of a track that is the tube's for sure, where the track is kept as the tube's end (a
/// free end re-traced, a track kept beside a cut): up to the last centre before the track lost
/// the tube outside a junction's zone (coasted across a gap, or a section no tube's), when after
/// that it re-centred only on sections that something touches. Past a vessel's end a circle of
/// the thin tube's radius fits the edge of the clutter beyond (a strip, a plate) as well as the
/// vessel; only a section that nothing touches says the tube goes on across the gap (a thin
/// vessel's gap of one voxel). Project rule, issue 16 item 5 (Docs/CENTERLINES.md, step 4).
Track confirmedPart(const Track& track);

/// Points every voxel along the polyline from `from` through `via` to `to` (both ends excluded;
/// `to` may be omitted: then up to the polyline's last point, included).
std::vector<Vec3> resampled(const Vec3& from,
  const std::vector<Vec3>& via,
  const Vec3* to,
  double spacing_mm);

/// Removes the point ranges `cuts[path]` (sorted, disjoint, inclusive) from the paths: each path
/// is split into the pieces between them (the first piece keeps the path's id and head, the last
/// its tail; pieces of fewer than 2 points go); paths joined to a removed point, or to a piece
/// that goes, are detached (that end becomes free). Returns the number of junctions detached.
int cutStretches(QSkeleton& skeleton,
  const std::vector<std::vector<std::pair<int, int>>>& cuts,
  std::vector<std::vector<TubeSectionTracker::Section>>& sections);

/// One point's section as phase 1 judges it.
struct PointSection
{
  double s = 0.0;     ///< median ray (voxels)
  bool round = false; ///< longest ray within the round-shape bound
  bool zone = false;  ///< near a junction: not judged
  bool clean = false;
};

/// Phase 1's verdict on one path: its sections, its pieces between cuts and whether it is a tube.
struct PathJudgement
{
  std::vector<PointSection> sec;
  std::vector<double> arc;          ///< arc length from the head (voxels)
  std::vector<int> cuts;            ///< the path's ends and the points where others join
  std::vector<int> vessel;          ///< piece between two cuts each point lies in
  std::vector<double> vesselMedian; ///< per piece: the median s of its round sections
  bool tube = false;                ///< has a clean run of >= 3 points: a vessel
};

/// Phase 1 (the header's 1-2): the sections of `path` and which of them are clean; the points
/// judged and not clean are counted into `counts`.
PathJudgement judgePath(const SkeletonPath& path,
  const std::vector<int>& attachedPoints,
  const std::vector<Zone>& zones,
  const SectionSampler& sampler,
  const TubeSectionTracker::Settings& s,
  TubeSectionTracker::Result& counts);

} // namespace tube_sections
} // namespace vtouch

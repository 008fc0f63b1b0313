// Issue 16, item 2 ("where a vessel touches bone, venous sinuses, fat or other tissue at vessel
// intensities, the network stops at the tube"): after the voxel coder has coded the raw-angiogram
// candidate region, each path is judged by its cross-sections on the volume (the vessel's
// intensity range), and where they are not those of its own tube (a plate, a blob, bone or
// another vessel touches it, and the coder's centre - the ridge of the merged region's distance
// map - leans into the contact, or the coder ran the path onto the clutter itself) the stretch is
// re-traced along the tube's own cross-section, or cut out. A departure from Yi & Hayward §3.1,
// whose centre adjustment is the distance map's ridge of a segmented vessel ("center-adjusted
// shortest lines"): in a raw angiogram the region at vessel intensity holds more than the vessel,
// and where something touches it only the part of the section away from the contact shows the
// tube's wall. The rules and numbers are the product's (Docs/CENTERLINES.md, "Raw angiograms",
// step 4); no paper gives them.
//
// 1. Sections. Per skeleton point p (tangent t; the coder's radius R): rays in 32 directions of the
//    plane normal to t follow the foreground from p in steps of 0.25 voxel, up to 2 R + 4 voxels;
//    rho_k = the run + half a step (the wall lies between the last sample in and the first out),
//    s = the median of rho (the section's radius). Round: the longest ray is at most
//    s + max(1.5 voxels, s / 2). Clean (the tube's own section): round and s <= tau +
//    max(1 voxel, tau / 2), tau the lower quartile of the round sections' s within
//    max(12 voxels, 3 x the vessel's median s) of arc length along the path (a blob swallowing
//    the path is round too, but wider than the vessel on either side of it: clutter only widens;
//    the window crosses the points where other paths join, because the coder joins the paths it
//    ran on the clutter to the vessel there). Points within R/2 + 1 voxel of a junction (R the
//    larger radius there) are not judged, as in TubeLikenessPruner.
// 2. Stretches: runs of points between clean points that hold a judged point that is not clean
//    (junction zones inside one are crossed: the paths joined there are re-attached). A vessel on
//    a path has a clean run of >= 3 points; a track starts only from an anchor with >= 3 clean
//    points on its side within the window, whose median s is the tube's radius r.
// 3. Re-tracing (middle stretches: forward from the clean point A before, else backward from the
//    clean point B after). The track starts along the chord of A's last two voxels (or radius),
//    steps 0.5 voxel and re-centres: the section's wall rays are those ending within r + 1 voxel,
//    the centre is the circle of radius r fitted to their ends (Gauss-Newton in the section
//    plane; the section re-taken from the new centre, four times at most). A step is accepted
//    when, from the centre, >= 40 % of the rays end within r +- 1 voxel, the rays running on
//    beyond the wall form one arc (one thing touches the tube; a plate's mid-sheet has two; arcs
//    and gaps of one ray are noise), the centre is in the foreground, it lies within
//    r / 2 + 0.75 voxel of the prediction and the direction turned less than 60 degrees over the
//    last 2 voxels. Where a step is not accepted the track coasts straight, through a junction's
//    zone and for max(1 voxel, r) beyond, and re-centres after it; it ends where it cannot, back
//    at its last centred point. The stretch is replaced when the track comes within
//    max(1.5 voxels, r / 2) of a clean point of the path (within 2 x the stretch + 4 voxels of
//    track): points every voxel along the track, radius interpolated between the ends, the path
//    re-smoothed there with the filter's windows (skeletonPathWindows). At a free end the track
//    from the clean side replaces the stretch as far as the tube goes (at most the stretch's
//    length + 1 voxel); a path joined to that stretch farther than 2 (r + 1) voxels from the
//    track joined the clutter beyond the tube's end and is detached, not moved onto the track.
//    Where such a track (or one kept beside a cut, 4) lost the tube outside a junction's zone
//    (coasted) and then re-centred only on sections that something touches, what it followed
//    after the coast is not kept: past a vessel's tip a circle of the thin tube's radius fits the
//    edge of the clutter beyond as well as the vessel; only an untouched section says the tube
//    goes on (the free end is trimmed back to the last centre before the coast).
//    Clutter widens a section: s wider than the tube r the track comes from, s > r + max(1 voxel,
//    r / 2) and s >= 1.5 voxels (the cut's blob criterion, relative to the tube: a thick
//    vessel's own sections are all wider than 1.5 voxels). A lone clean point (its judged
//    neighbours both not clean with s > 0, one wider than the tube: the coder's centre pulled
//    into a contact) does not end a stretch that a track from the tube before it can enter. A
//    track that meets no clean point but comes within reach of a point where another vessel
//    joins the path (both with clean runs), with a section wider than the tube between its
//    start and that junction (the path ran onto clutter; a clean junction's sections are only
//    elongated), replaces the stretch up to that junction (the vessel goes on as the other
//    path; the path turned onto a branch). Counted in Result::loneSectionsCrossed and
//    Result::stretchesEndedAtJunction. (Issue 16 item 5; project rules, Docs/CENTERLINES.md
//    step 4, "Past clutter".)
// 4. Cutting. A stretch that no track crossed is clutter when it has >= 3 points, its sections
//    are wide (median s >= 1.5 voxels: not a thin vessel's noisy wall), mostly not round (a
//    plate's band) or wider than the tube it left (s > r + max(1, r / 2): a blob), longer than
//    its median s + 2 voxels, it does not reach a junction between two vessels (both paths
//    have clean runs), where the other vessel's lumen legitimately elongates the sections, and it
//    is not a vessel between vessels of at most its calibre (not wider than its tube, every ray
//    ending on background inside the volume within 3 r + 1 voxel: h16p). It is removed: the path is
//    split there (the tube's tracks from either side, when they followed the tube on for more than
//    2 (r + 1) voxels, stay as the pieces' ends), paths joined to it are detached (their end
//    becomes free), and pieces left joined to nothing without a clean run of 3 points go.
#pragma once

#include "vtouchCurveGeometry.h"
#include "vtouchQSkeleton.h"
#include "vtouchSectionSampler.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace vtouch
{

class TubeSectionTracker
{
public:
  struct Settings
  {
    int rays = 32;                     ///< directions in the section plane
    double rayStep_voxels = 0.25;      ///< sampling step along a ray
    double roundExcess_voxels = 1.5;   ///< clean shape: longest ray <= s + max(this, s * ...)
    double roundExcessFraction = 0.5;  ///< ... fraction)
    double radiusExcess_voxels = 1.0;  ///< clean size: s <= tau + max(this, tau * ...)
    double radiusExcessFraction = 0.5; ///< ... fraction)
    double radiusWindow_voxels = 12.0; ///< tau's window: +- max(this, radiusWindowRadii tau')
    double radiusWindowRadii = 3.0;
    double wallMargin_voxels = 1.0;    ///< a wall ray ends within r +- this
    double minimumWallFraction = 0.4;  ///< of the rays, from an accepted centre
    double trackStep_voxels = 0.5;     ///< the tracker's step along its tangent
    double maximumShift_voxels = 0.75; ///< a step's centre within r/2 + this of the prediction
    double targetReach_voxels = 1.5;   ///< the track meets a clean point within max(this, r/2)
    double maximumTurnCosine = 0.5;    ///< over the last 2 voxels (60 degrees)
    double junctionZoneRadii = 0.5;    ///< points within zoneRadii R + margin of a junction
    double junctionZoneMargin_voxels = 1.0;
    double maximumTrackFactor = 2.0; ///< a track may be this many times the stretch + 4 voxels
    int minimumAnchorPoints = 3;     ///< clean points on an anchor's side for a track from it
    double clutterMinimumWidth_voxels = 1.5; ///< a clutter stretch's median section radius
    int clutterMinimumPoints = 3;            ///< a clutter stretch's sections (a run, not a gap)
    /// A stretch not wider than its tube whose every section stays within this many tube radii
    /// (+ 1 voxel) of the path is a vessel between vessels of at most its calibre (their far
    /// walls lie within r + 2 r of its axis), not a plate's band, and is not cut; 0 = off.
    double betweenVesselsReach_radii = 3.0;
    double smoothingWindow_mm = 0.0; ///< the filter's SmoothingWindow (skeletonPathWindows)
  };

  /// What the tracker found at each point of the result.
  enum class Section : std::uint8_t
  {
    Clean,    ///< the tube's own section, as the coder centred it
    Junction, ///< within a junction's zone (not judged)
    Retraced, ///< a point of a re-traced stretch (the tube's own centre beside a contact)
    NotClean  ///< not the tube's own section, and no track through it
  };

  struct Result
  {
    std::vector<std::vector<Section>> sections; ///< per path and point of the result
    int stretches = 0;        ///< stretches of points whose sections were not clean
    int stretchesTracked = 0; ///< replaced by the tube's own track
    int junctionsMoved = 0;   ///< paths joined inside a re-traced stretch, moved onto the track
    int stretchesCut = 0;     ///< clutter stretches removed (a path split, or its free end trimmed)
    int junctionsDetached = 0;   ///< paths joined inside a removed stretch (their end is free now)
    int loneSectionsCrossed = 0; ///< lone clean sections amid clutter a stretch ran on across
    int stretchesEndedAtJunction = 0; ///< re-traced up to a junction (no clean point was met)
    /// Free ends whose track was cut back to where it lost the tube (only touched sections after)
    int freeEndsEndedWhereTubeLost = 0;
    std::size_t pointsJudged = 0;
    std::size_t pointsNotClean = 0;
  };

  /// Re-traces, in place, the stretches of `skeleton` whose cross-sections are not those of their
  /// own tube (ids, junctions and labels kept consistent: QSkeleton::validate() stays empty).
  static Result track(QSkeleton& skeleton,
    const SectionForeground& foreground,
    const SectionGeometry& geometry,
    const Settings& settings);
  static Result track(QSkeleton& skeleton,
    const SectionForeground& foreground,
    const SectionGeometry& geometry)
  {
    return track(skeleton, foreground, geometry, Settings{});
  }
};

} // namespace vtouch

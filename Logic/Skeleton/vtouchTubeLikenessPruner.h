// Issue 16, item 2, "remove skeleton branches whose cross-sections are not tube-like": after the
// voxel coder has coded the raw-angiogram candidate region, the paths that run inside a plate
// (bone-like clutter at vessel intensity, thin at the scale of its own thickness, so the neck
// cutter keeps it) are removed, and the free ends that run onto one are trimmed. The product's own
// rule (Docs/CENTERLINES.md, "Raw angiograms", step 5); no paper gives one.
//
// The rule, per skeleton point p with tangent t and radius r (the coder's radius, in voxels of the
// smallest spacing): in the plane through p normal to t, rays in 32 directions follow the
// foreground from p (nearest voxel, steps of 0.25 voxel) until they leave it. The foreground is
// the volume in the intensity range (the filter's choice), not the candidate region: the neck cut
// keeps a plate's rims, bars of their own, and only the image shows the plate around them. The
// section is NOT tube-like when one ray runs on for more than r + L (L = max(2 r, 4 voxels))
// inside a band whose mid-line passes through p: at (2 r + L)/2 along the ray, the thinnest chord
// of the section (16 directions) is at most 2 (r + max(2, r)) voxels long, and its mid-point lies
// within 1.25 voxels of p along that chord. That is a plate seen in section (a path in a plate's
// mid-sheet, or on its rim, where the band runs one way). A tube's section stops near r on every
// ray; a tube touching a plate reaches the plate across its thickness, and that band's mid-line
// lies beyond the tube's wall (d + w/2 from the axis); a wide structure (bone, a blob) is no band.
// Points within R/2 + 1 voxel of a junction (R the larger radius there) are not judged: sections
// there are legitimately elongated. A path whose judged points (>= 2) are mostly (>= 1/2) not
// tube-like is removed when no other path hangs on it; a path with fewer judged points goes with
// such a path it hangs on (the bridges of a loop around a plate); repeated until none goes. A free
// end is trimmed back to its last two consecutive tube-like points when at least 3 points beyond
// them are judged and mostly not tube-like (only the part on the clutter goes). A path with a free
// end that carries no other path and is shorter than 2.5 times its own largest section radius
// (the median of 32 rays in the section plane, beyond the junction's zone) is a bulge - a blob or
// a knob on a vessel - and goes too (the coder's spur rule on the branch's own calibre); a piece
// joined to nothing, unless it is the longest path, must clear twice that (a spur at each end).
// A free end whose last points are all much wider than the tube just before them (a thin vessel
// run into a blob) is trimmed back to that tube. A stretch wider than the tube on both sides of it
// (a thin vessel through a blob) goes straight between them (BlobCrossingBridge).
#pragma once

#include "vtouchBlobCrossingBridge.h"
#include "vtouchQSkeleton.h"
#include "vtouchSectionSampler.h"
#include "vtouchSparseVesselMask.h"
#include "vtouchVector.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>

namespace vtouch
{

class TubeLikenessPruner
{
public:
  /// The mask's grid (vtouchSectionSampler.h).
  using Geometry = SectionGeometry;

  struct Settings
  {
    int rays = 32;                         ///< directions in the section plane
    double longFactor = 2.0;               ///< L = max(longFactor r, longMinimum_voxels)
    double longMinimum_voxels = 4.0;       ///< a plate's band: longer than a thin vessel's wall
    double bandMargin_voxels = 2.0;        ///< band half-width bound r + max(margin, r)
    int bandDirections = 16;               ///< chords through the run's middle (half a turn)
    double midLineTolerance_voxels = 1.25; ///< p this close to the band's mid-line: in the plate
    double junctionZoneRadii = 0.5; ///< points within zoneRadii R + margin of a junction: unjudged
    double junctionZoneMargin_voxels = 1.0;
    double notTubeFraction = 0.5; ///< a path goes when this share of its judged points is not tube
    int minimumJudgedPoints = 2;  ///< fewer judged points: unjudged (goes with a plate parent)
    int minimumTrimPoints = 3;    ///< a free end is trimmed when this many end points are not tube
    /// A free end onto a plate goes back to the last run of this many consecutive tube-like
    /// points (step 4's "a vessel on a path has a clean run of >= 3 points"): two tube-like
    /// points inside the clutter, where the path runs along the plate's face, do not anchor it
    /// (u128 seed 9 noise 20, session 18: 9 points up to 7.6 voxels off the vessel). Was 2.
    int endAnchorTubePoints = 3;
    /// A branch ending free that is shorter than this many of its own largest section radii
    /// (beyond the junction's zone) is a bulge (a blob, a knob) and goes; 0 = off. The coder's
    /// spur length (MinimumBranchLength, 2.5 radii of the vessel joined) on the branch's own. A
    /// path free at both ends (not the longest) must clear twice this.
    double bulgeFactor = 2.5;
    /// A branch whose farthest point from its junction is under bulgeFactor times its free
    /// end's section radius (the median of this many judged points at that end) is a bulge too:
    /// the coder's path hooked about a blob's centre (session 20). 0 = off.
    int bulgeEndPoints = 3;
    /// A free end that runs into a blob: the end's last points (>= minimumTrimPoints judged) all
    /// wider than the tube just before them, s > t + max(blobExcess_voxels, blobExcessFraction
    /// t) and s >= blobMinimumWidth_voxels, t the median section radius of the blobTubePoints
    /// judged points before the run, are trimmed. The tube-section tracker's clutter criteria
    /// (step 4: "wider than the tube it left", "not a thin vessel's noisy wall"), here for ends
    /// that no track replaced (a vessel under a voxel in radius gives no 3 clean sections under
    /// noise). 0 points = off.
    int blobTubePoints = 5;
    double blobExcess_voxels = 1.0;
    double blobExcessFraction = 0.5;
    double blobMinimumWidth_voxels = 1.5;
    /// A thin vessel through a blob: the stretch wider than the tube on both sides goes straight
    /// between them (vtouchBlobCrossingBridge.h; session 19); off: left as coded.
    bool bridgeBlobCrossings = true;
    BlobCrossingBridge::Settings blobCrossing;
  };

  struct Result
  {
    int pathsRemoved = 0;
    int bulgesRemoved = 0; ///< of pathsRemoved: bulges
    int endsTrimmed = 0;
    int blobEndsTrimmed = 0; ///< of endsTrimmed: ends run into a blob
    int blobsBridged = 0;    ///< stretches through a blob replaced by the tube's chord
    std::size_t pointsRemoved = 0;
  };

  /// What the sections are taken of (vtouchSectionSampler.h).
  using Foreground = SectionForeground;
  /// A mask as the foreground (the mask must outlive the result).
  static Foreground foreground(const SparseVesselMask& mask) { return SectionForeground::of(mask); }

  /// True when the foreground's section at position_World_mm normal to tangent_World is tube-like.
  static bool isTubeLikeSection(const Foreground& foreground,
    const Geometry& geometry,
    const Vec3& position_World_mm,
    const Vec3& tangent_World,
    double radius_mm,
    const Settings& settings);

  /// Removes the non-tube-like paths and trims non-tube-like free ends of `skeleton` in place
  /// (ids, junctions and labels kept consistent: QSkeleton::validate() stays empty).
  static Result prune(QSkeleton& skeleton,
    const Foreground& foreground,
    const Geometry& geometry,
    const Settings& settings);
  static Result prune(QSkeleton& skeleton, const Foreground& foreground, const Geometry& geometry)
  {
    return prune(skeleton, foreground, geometry, Settings{});
  }
};

} // namespace vtouch

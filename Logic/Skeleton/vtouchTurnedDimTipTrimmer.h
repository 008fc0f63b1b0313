// Issue 16, item 2 ("no extracted point more than 1.5 voxels outside a true vessel"): the last
// point of a free end that the coder ran sideways onto one dim noise voxel beside a thin vessel's
// tip. Under noise the growth's ridge rule (step 2) admits a noise voxel 3-5 sigmas above the
// background that touches the tip of a thin vessel whose own last voxels are dim too (partial
// volume); the dim dead-end rule keeps the whole strand (its summed contrast passes Rose's
// criterion), and the coder runs the path to the strand's farthest voxel: the noise voxel. Nothing
// after coding sees it by sections (a point out of the range has an empty section, as a thin
// vessel's often has). Found on the phantom family (128^3 seed 2 noise 50: a vessel of radius 0.5,
// its last point 1.7 voxels outside it, turned 81 degrees, written out by Docs' `falsepoints`).
//
// The rule (the product's; Docs/CENTERLINES.md, "Raw angiograms", step 5, "Turned dim tips"):
// the last point q of a free end goes when
//  1. q's voxel is dim: below the range's lower bound (only the ridge rule admitted it);
//  2. the step from the point before, p, turns more than maximumTurn_deg = 60 degrees off the
//     path's heading (the chord from the point two before p to p): the tube-section tracker's
//     limit for a tube's direction over 2 voxels (step 4; a tube's axis does not turn that fast);
//  3. q's voxel touches p's voxel only across background: the voxels that bridge the two (the
//     other voxels of the 2 x 2 x 2 block they span: 2 across an edge, 6 across a corner; a face
//     step has none and never goes) average below B + k S / sqrt(m), m bridge voxels, B and S the
//     background and its noise sigma that the range estimator measured (step 1), k = 3 its noise
//     margin on the mean of m voxels. Along a tube toward its tip the partial-volume profile falls
//     off through the voxels its axis crosses (they hold part of the tube); a voxel joined to the
//     path's voxel across background is a bump of its own, not the tube's fall-off.
// One point per end: the dim dead-end rule has cleared longer dead ends that are noise. A real tip
// that runs on along the path (a face step, or a turn under 60 degrees), or whose bridge holds
// part of the tube, stays.
#pragma once

#include "vtouchQSkeleton.h"
#include "vtouchSectionSampler.h"

namespace vtouch
{

class TurnedDimTipTrimmer
{
public:
  struct Settings
  {
    /// The step onto the last point turns more than this (degrees) off the heading: the tube-
    /// section tracker's limit on a tube's turn over 2 voxels (TubeSectionTracker::Settings).
    double maximumTurn_deg = 60.0;
    /// The heading: the chord from `headingPoints` points before the last-but-one point to it.
    int headingPoints = 2;
    /// k: the bridge is background when its mean is below B + k S / sqrt(m) (the range
    /// estimator's noise margin, IntensityRangeParameters::noiseMargin).
    double noiseMargin = 3.0;
  };

  /// What the rule reads of the volume: its intensities, the range's lower bound (the vessel's
  /// range is [lower, the volume's maximum] on the raw path) and the background B and its noise
  /// sigma S the range estimator measured (same units as the intensities).
  struct Evidence
  {
    SectionIntensity intensity;
    double lower = 0.0;
    double background = 0.0;
    double backgroundNoise = 0.0;
  };

  struct Result
  {
    int tipsTrimmed = 0;
  };

  /// True when q (the last point of a free end) is a turned dim tip: the three conditions above,
  /// with p the point before it and `heading_World` the path's direction at p (any length).
  static bool isTurnedDimTip(const Evidence& evidence,
    const SectionGeometry& geometry,
    const Vec3& heading_World,
    const Vec3& p_World_mm,
    const Vec3& q_World_mm,
    const Settings& settings);

  /// Drops the turned dim tip of every free end of `skeleton` in place (paths of at least
  /// headingPoints + 2 points; not where a junction sits on the dropped point or the new end;
  /// QSkeleton::validate() stays empty). Evidence without intensities or with S <= 0 changes
  /// nothing.
  static Result trim(QSkeleton& skeleton,
    const Evidence& evidence,
    const SectionGeometry& geometry,
    const Settings& settings);
  static Result trim(QSkeleton& skeleton, const Evidence& evidence, const SectionGeometry& geometry)
  {
    return trim(skeleton, evidence, geometry, Settings{});
  }
};

} // namespace vtouch

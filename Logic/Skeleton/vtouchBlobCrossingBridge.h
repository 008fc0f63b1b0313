// A thin vessel that runs through (or along) a blob at vessel intensity: the coder's path leaves
// the vessel's axis for the merged region's distance-map ridge, which runs through the blob's
// centre (up to 4.5 voxels off the vessel on unseen phantoms, session 19: 128^3 seeds 24 and 26).
// The tube-section tracker (step 4) cannot re-trace it: inside the blob every ray runs on, so no
// step re-centres on the tube's wall, and the stretch joins the vessel on both sides, so it is no
// clutter to cut. Here such a stretch is replaced by the chord between the tube's points on
// either side of it.
//
// The rule (the product's, Docs/CENTERLINES.md "Raw angiograms", step 5; no paper gives one; a
// departure from Yi & Hayward §3.1, whose centre adjustment is the distance map's ridge): a run
// of >= minimumRunPoints consecutive judged points of a path, all wider than the tube on both
// sides - section radius s > t + max(excess_voxels, excessFraction t) and s >= minimumWidth_voxels
// (TubeLikenessPruner's blob criterion), t the larger of the median section radii of the
// >= minimumTubePoints (at most tubePoints) consecutive tube-like points just before and just
// after the run (a junction's zone after the first of them stepped over: a branch leaving the
// tube does not end it), the points next to the run not wider than the tube - with under
// plateFraction of its sections in a plate's band (TubeLikenessPruner) unless both sides are
// the tube (a thin vessel through or along a plate), no other path joined inside it, and its
// chord (between the points just before and just after it) no longer than maximumLengthWidths
// times its widest section + 2 voxels (a blob's size, not a plate's length), is replaced by
// points every voxel on that chord, with the tube's radius. At a path's end joined to another path
// whose junction zone (unjudged points) reaches the run, the zone's last point is that side's
// anchor and the tube's radius is the other side's alone (the vessel enters the blob where it
// leaves its parent).
#pragma once

#include "vtouchQSkeleton.h"

#include <cstdint>
#include <vector>

namespace vtouch
{

class BlobCrossingBridge
{
public:
  struct Settings
  {
    int tubePoints = 5; ///< the tube's section radius: median of at most this many points
    /// A tube side: this many consecutive tube-like points (step 4's clean run; a plate's face
    /// shows one or two tube-like sections among not tube-like ones, session 18).
    int minimumTubePoints = 3;
    int minimumRunPoints = 3;   ///< a blob: this many judged sections (a run, not noise)
    double excess_voxels = 1.0; ///< s > t + max(excess_voxels, excessFraction t)
    double excessFraction = 0.5;
    double minimumWidth_voxels = 1.5;
    /// The chord between the run's anchors <= this x its widest section + 2 voxels.
    double maximumLengthWidths = 3.0;
    /// A run with at least this share of not tube-like sections is a plate (the pruner's rules
    /// remove or trim it), not a blob - unless the tube goes on on both sides of it (a thin
    /// vessel through or along a plate: bridged too, session 20).
    double plateFraction = 0.5;
  };

  /// A point's section as TubeLikenessPruner judged it.
  enum class Section : std::uint8_t
  {
    Unjudged,   ///< within a junction's zone
    TubeLike,   ///< no plate's band through it
    NotTubeLike ///< in a plate's band
  };
  /// Per path and point: its section's judgement and radius in voxels (TubeLikenessPruner's
  /// sectionRadius). Updated with the skeleton: bridged points are tube-like, with the tube's
  /// section radius.
  struct Sections
  {
    std::vector<std::vector<Section>> judged;
    std::vector<std::vector<double>> width_voxels;
  };

  /// Replaces every blob crossing of `skeleton` in place (junction indices shifted; paths,
  /// junctions and labels otherwise unchanged); returns how many stretches were bridged.
  /// `onReplace(path, first, count, inserted)`: called for each replacement (points
  /// first..first+count-1 became `inserted` points), for the caller's own per-point data.
  template<typename OnReplace>
  static int bridge(QSkeleton& skeleton,
    Sections& sections,
    double voxel_mm,
    const Settings& settings,
    OnReplace&& onReplace)
  {
    int bridged = 0;
    for (std::size_t i = 0; i < skeleton.paths.size(); ++i)
    {
      int from = 0;
      for (;;)
      {
        const Crossing c = findCrossing(skeleton, sections, i, from, voxel_mm, settings);
        if (c.first < 0)
        {
          break;
        }
        const int inserted = replace(skeleton, sections, i, c, voxel_mm);
        onReplace(i, c.first, c.last - c.first + 1, inserted);
        ++bridged;
        from = c.first + inserted + 1;
      }
    }
    return bridged;
  }

  static int bridge(QSkeleton& skeleton,
    Sections& sections,
    double voxel_mm,
    const Settings& settings)
  {
    return bridge(skeleton, sections, voxel_mm, settings, [](std::size_t, int, int, int) {});
  }

private:
  struct Crossing
  {
    int first = -1, last = -1; ///< the run's points (replaced)
    double tube_voxels = 0.0;  ///< the tube's section radius
    double radius_mm = 0.0;    ///< the tube's radius (the coder's, on the tube's side(s))
  };
  static Crossing findCrossing(const QSkeleton& skeleton,
    const Sections& sections,
    std::size_t path,
    int from,
    double voxel_mm,
    const Settings& s);
  static int replace(QSkeleton& skeleton,
    Sections& sections,
    std::size_t path,
    const Crossing& c,
    double voxel_mm);
};

} // namespace vtouch

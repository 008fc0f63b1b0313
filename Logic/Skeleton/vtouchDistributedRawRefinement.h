// The raw path's refinement over the whole stitched paths on a parallel pvserver (issue 19 item 2,
// h19r): the first rank runs RawSkeletonRefinement (TubeSectionTracker, TubeLikenessPruner,
// TurnedDimTipTrimmer) once on the whole stitched skeleton, as the single run does on its one
// skeleton, reading the volume from pages fetched from their owners (DistributedVolumePages).
// Each rank refining its own smoothed part of a path (before h19r) made the stages' whole-path
// decisions (the radius window of the clean test, a path's share of tube-like points, a
// stretch's track) and the re-traced stretches' smoothing windows differ from the single run's.
// Collective: every rank calls run() once, the first rank with the stitched skeleton, the others
// serving their owned voxels' intensities.
#pragma once

#include "vtouchDistributedVolumePages.h"
#include "vtouchRawSkeletonRefinement.h"

#include <cstdint>
#include <string>
#include <vector>

namespace vtouch
{

class DistributedRawRefinement
{
public:
  /// The single run's arguments of RawSkeletonRefinement::apply (the first rank's count).
  struct Settings
  {
    double smoothingWindow_mm = 0.0; ///< the filter's SmoothingWindow
    double lower = 0.0;              ///< the vessel's intensity range (the range's lower bound)
    double upper = 0.0;              ///< ... and upper bound
    double background = 0.0;         ///< the range estimator's B (the turned dim tips)
    double backgroundNoise = 0.0;    ///< ... and S
    /// The pages fetched before the first run: those within prefetchRadii R + prefetchMargin
    /// voxels of every stitched point (R its radius in voxels, at least 0.5). Project rule, from
    /// the stages' reach: the tracker's section rays run 2 R + 4 voxels; the pruner's band test
    /// looks farthest, from a run's middle (r + max(r, 2) out) along chords of 2 (r + max(2, r)),
    /// at most sqrt(5) (r + 2) <= 4.5 r + 4.5 voxels away, 0.25 voxel of a ray's last step and
    /// half a voxel of the nearest voxel more: 4.5 R + 6 covers every read at a stitched point.
    /// Reads beyond (a re-traced track leaving the path) are misses, fetched in the next round.
    /// 0 and 0: only the points' own pages (the tests' miss-and-re-run case).
    double prefetchRadii = 4.5;
    double prefetchMargin_voxels = 6.0;
  };

  struct Result
  {
    bool refined = false; ///< first rank: the skeleton is the whole-path refinement's
    std::string message;  ///< first rank: why not ("" when refined or nothing to refine)
    RawSkeletonRefinement refinement;      ///< the whole-path run's (first rank)
    DistributedVolumePages::Outcome pages; ///< the rounds
    std::int64_t pagesPrefetched = 0;      ///< asked for before the first run (first rank)
    double seconds = 0.0;                  ///< the whole hook on this rank (steady clock)
  };

  /// Collective. `skeleton`: the first rank's stitched skeleton (replaced by its refinement when
  /// the rounds complete; left as it was otherwise); null on the other ranks, or on the first
  /// when there is nothing to refine (the rounds then end at once). `geometry`: the whole
  /// volume's (index 0 at its first voxel); `settings`: the first rank's count.
  static Result run(RankCollectives& collectives,
    const PieceLayout& layout,
    DistributedVolumePages::OwnedIntensity mine,
    QSkeleton* skeleton,
    const SectionGeometry& geometry,
    const Settings& settings);

  /// The pages within the prefetch bound of every point of `skeleton` (points outside the volume
  /// are skipped: their reads are misses).
  static std::vector<std::int64_t> prefetchPages(const QSkeleton& skeleton,
    const SectionGeometry& geometry,
    const DistributedVolumePages& pages,
    const std::array<std::int64_t, 3>& wholeDims,
    const Settings& settings);
};

} // namespace vtouch

// The raw-angiogram path's stages after the voxel coder (issue 16), in their order: the tube's own
// cross-sections re-trace or cut the stretches where clutter touches a vessel or the coder ran
// onto it (TubeSectionTracker), then paths and ends that are not tube-like go (TubeLikenessPruner),
// then free ends that turn onto one dim noise voxel lose it (TurnedDimTipTrimmer). The first two
// look at the volume in the vessel's intensity range, the last at its intensities. Shared by
// VesselCenterline and the tests, so that they judge what the user gets. Binary masks and the typed
// range do not run it.
#pragma once

#include "vtouchTubeLikenessPruner.h"
#include "vtouchTubeSectionTracker.h"
#include "vtouchTurnedDimTipTrimmer.h"

#include <chrono>

namespace vtouch
{

struct RawSkeletonRefinement
{
  TubeSectionTracker::Result tracked;
  TubeLikenessPruner::Result pruned;
  TurnedDimTipTrimmer::Result tips;
  double trackSeconds = 0.0;
  double pruneSeconds = 0.0;

  /// `smoothingWindow_mm`: the filter's SmoothingWindow (re-traced stretches are re-smoothed with
  /// the filter's windows). `tips`: the volume's intensities and the range's statistics for the
  /// turned dim tips (none: that rule is off; the time counts in pruneSeconds).
  static RawSkeletonRefinement apply(QSkeleton& skeleton,
    const SectionForeground& inRange,
    const SectionGeometry& geometry,
    double smoothingWindow_mm,
    const TurnedDimTipTrimmer::Evidence* tips = nullptr)
  {
    using Clock = std::chrono::steady_clock;
    RawSkeletonRefinement r;
    auto t0 = Clock::now();
    TubeSectionTracker::Settings track;
    track.smoothingWindow_mm = smoothingWindow_mm;
    r.tracked = TubeSectionTracker::track(skeleton, inRange, geometry, track);
    auto t1 = Clock::now();
    r.trackSeconds = std::chrono::duration<double>(t1 - t0).count();
    r.pruned = TubeLikenessPruner::prune(skeleton, inRange, geometry);
    if (tips)
    {
      r.tips = TurnedDimTipTrimmer::trim(skeleton, *tips, geometry);
    }
    r.pruneSeconds = std::chrono::duration<double>(Clock::now() - t1).count();
    return r;
  }
};

} // namespace vtouch

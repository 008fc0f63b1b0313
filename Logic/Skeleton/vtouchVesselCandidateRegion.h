// The candidate vessel region of a raw angiogram: what the voxel coder codes. One click (or none)
// and no threshold typed:
//   1. IntensityRangeEstimator: the vessel's range from the seed's neighbourhood (or the volume);
//   2. SeededRegionGrower: the network reachable from the seed (or every voxel in range);
//   3. RestrictedTubularity on the region only, scales up to the region's largest depth;
//   4. TubeNeckCutter: non-tubular parts cut off at their necks, the seed's component kept.
// A binary mask (two values) skips 3-4: it is coded as drawn, as before. When `automatic` is off
// the caller's range is used (the override) and the same stages run on it.
// Every failure is a user-facing message and an empty region; nothing throws for bad input.
// Settings::progress, when set, receives the fraction done at every stage's check points and
// stops the run when it returns false: extract() then throws vtouch::Cancelled.
#pragma once

#include "vtouchIntensityRangeEstimator.h"
#include "vtouchProgress.h"
#include "vtouchRegionDepth.h"
#include "vtouchRestrictedTubularity.h"
#include "vtouchSeededRegionGrower.h"
#include "vtouchTubeNeckCutter.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <string>
#include <utility>
#include <vector>

namespace vtouch
{

class VesselCandidateRegion
{
public:
  struct Settings
  {
    bool automatic = true;
    double lower = 0.5, upper = 1e300; ///< used when !automatic
    bool useSeed = false;
    std::array<std::int64_t, 3> seed{ 0, 0, 0 }; ///< voxel index (may be outside the volume)
    bool cutNonTubular = true;
    /// Frangi's c as a fraction of the vessel contrast (V - B); tube cores from this tubularity.
    double structurenessFraction = 0.1;
    float coreTubularity = 0.3F;
    float thinCoreTubularity = 0.1F;
    int maximumDepth_voxels = 48; ///< caps the largest scale (time), in voxels of the grid
    /// Fraction done in [0, 1] at the stages' check points; returning false cancels (extract()
    /// throws Cancelled). Empty: no progress, no cancel.
    ProgressCallback progress;
  };
  struct Result
  {
    bool ok = false;
    std::string message; ///< empty when ok
    IntensityRange range;
    SparseVesselMask mask;                          ///< finalized; empty when !ok
    std::array<std::int64_t, 3> seed{ -1, -1, -1 }; ///< the seed voxel in `mask`
    std::uint64_t grownVoxels = 0, coreVoxels = 0;
    std::vector<std::pair<std::string, double>> stageSeconds;
  };

  template<typename T>
  static Result extract(const VolumeView<T>& volume, const Settings& s);

  /// The tubularity's parameters: scales up to the largest expected radius, the region's deepest
  /// voxel (`deepest_voxels`, at least 1, times the coarsest spacing); Frangi's c as
  /// `structurenessFraction` of the vessel contrast (of the range's width when the contrast is not
  /// positive; 1 when neither is). Shared by the single run and the distributed one.
  static RestrictedTubularity::Parameters tubularityParameters(const Settings& s,
    const IntensityRange& range,
    int deepest_voxels,
    const std::array<double, 3>& spacing_mm)
  {
    RestrictedTubularity::Parameters tp;
    const double maxSpacing = std::max({ spacing_mm[0], spacing_mm[1], spacing_mm[2] });
    tp.sigmaMaximum_mm = std::max(1.0, static_cast<double>(deepest_voxels)) * maxSpacing;
    const double contrast = range.vessel - range.background;
    tp.structureness = contrast > 0.0 ? s.structurenessFraction * contrast
                                      : s.structurenessFraction * (range.upper - range.lower);
    if (!(tp.structureness > 0.0))
    {
      tp.structureness = 1.0;
    }
    return tp;
  }
};

template<typename T>
VesselCandidateRegion::Result VesselCandidateRegion::extract(const VolumeView<T>& volume,
  const Settings& s)
{
  using Clock = std::chrono::steady_clock;
  auto t0 = Clock::now();
  const auto lap = [&t0](Result& r, const char* name)
  {
    const auto now = Clock::now();
    r.stageSeconds.emplace_back(name, std::chrono::duration<double>(now - t0).count());
    t0 = now;
  };
  Result r;
  r.mask = SparseVesselMask(volume.dims);
  r.mask.finalize();
  // Shares of the run by stage, from their times on raw angiograms (Docs/PERFORMANCE.md): the
  // tubularity takes most of it.
  const ProgressSpan all(&s.progress);
  const ProgressSpan rangeProgress = all.part(0.0, 0.1);
  const ProgressSpan growProgress = all.part(0.1, 0.2);
  const ProgressSpan depthProgress = all.part(0.2, 0.25);
  const ProgressSpan tubularityProgress = all.part(0.25, 0.9);
  const ProgressSpan necksProgress = all.part(0.9, 1.0);
  if (s.useSeed && !volume.inside(s.seed[0], s.seed[1], s.seed[2]))
  {
    r.message = IntensityRangeEstimator::outsideMessage();
    return r;
  }
  if (s.automatic)
  {
    r.range = s.useSeed ? IntensityRangeEstimator::fromSeed(
                            volume, s.seed, IntensityRangeEstimator::Parameters{}, rangeProgress)
                        : IntensityRangeEstimator::fromVolume(
                            volume, IntensityRangeEstimator::Parameters{}, rangeProgress);
  }
  else
  {
    r.range.ok = s.lower <= s.upper;
    r.range.lower = r.range.weakLower = s.lower;
    r.range.upper = s.upper;
    r.range.seedIndex = s.seed;
    if (!r.range.ok)
    {
      r.range.message = "The lower threshold exceeds the upper threshold.";
    }
  }
  lap(r, "range");
  if (!r.range.ok)
  {
    r.message = r.range.message;
    return r;
  }
  SparseVesselMask region;
  if (s.useSeed)
  {
    const auto& q = r.range.seedIndex;
    const double value = volume.at(q[0], q[1], q[2]);
    if (!(value >= r.range.lower && value <= r.range.upper))
    {
      r.message =
        IntensityRangeEstimator::backgroundMessage(volume.at(s.seed[0], s.seed[1], s.seed[2]));
      return r;
    }
    region = SeededRegionGrower::grow(volume, r.range, q, growProgress);
  }
  else
  {
    region = SeededRegionGrower::threshold(volume, r.range, growProgress);
  }
  r.grownVoxels = region.vesselCount();
  lap(r, "grow");
  if (region.vesselCount() == 0)
  {
    r.message = "No voxel lies in the vessel range: the volume has no vessel-like structure.";
    return r;
  }
  // An automatic binary mask is coded as drawn (as before the raw path existed).
  const bool tubes = s.cutNonTubular && !(s.automatic && r.range.binary);
  if (!tubes)
  {
    r.mask = std::move(region);
    r.seed = r.range.seedIndex;
    r.ok = true;
    return r;
  }
  const std::vector<std::uint16_t> depth = RegionDepth::layers(region, depthProgress);
  lap(r, "depth");
  const int deepest = std::min<int>(
    s.maximumDepth_voxels, depth.empty() ? 1 : *std::max_element(depth.begin(), depth.end()));
  const RestrictedTubularity::Parameters tp =
    tubularityParameters(s, r.range, deepest, volume.spacing_mm);
  const RestrictedTubularity::Result tube =
    RestrictedTubularity::compute(volume, region, depth, tp, tubularityProgress);
  lap(r, "tubularity");
  TubeNeckCutter::Result cut = TubeNeckCutter::cut(region,
    depth,
    tube.tubularity,
    s.coreTubularity,
    s.thinCoreTubularity,
    s.useSeed ? &r.range.seedIndex : nullptr,
    necksProgress);
  lap(r, "necks");
  all.report(1.0);
  r.coreVoxels = cut.coreVoxels;
  if (cut.coreVoxels == 0)
  {
    r.message = s.useSeed ? "The seed's region has no vessel-like (tube-shaped) part: pick a point "
                            "on a vessel in the MIP."
                          : "The volume has no vessel-like (tube-shaped) structure in the vessel "
                            "range.";
    return r;
  }
  if (s.useSeed && !cut.seedKept)
  {
    r.message = "The seed is on a structure that is not a vessel (bone, a blob or tissue at vessel "
                "intensity): pick a point on a vessel in the MIP.";
    return r;
  }
  r.mask = std::move(cut.mask);
  r.seed = cut.seed;
  r.ok = true;
  return r;
}

} // namespace vtouch

// The vessel's intensity range of a raw bright-on-dark angiogram (CTA, TOF-MRA, contrast micro-CT,
// rotational angiography), estimated by robust statistics: from the neighbourhood of a seed the
// user clicked on a vessel, or from the whole volume without a seed.
//
// Yi & Hayward §3.1 extract the Q-skeleton "from raw intensity volume images with linear
// operations" from a seed picked on the MIP; they give no rule for the range. The rules here are
// the product's (named departures, Docs/CENTERLINES.md "Raw angiograms"):
//  - background level B = median of the neighbourhood (vessels fill well under half of a cube a
//    few vessel diameters wide), its noise S = P50 - P15.87 (one Gaussian sigma from the lower
//    half only, so the bright vessel tail does not inflate it);
//  - vessel level V = median of the voxels around the brightest voxel near the seed that are above
//    the half way to it (the lumen plateau, not one noisy maximum);
//  - the seed is on background unless V - B >= 5 S (Rose's criterion for a detectable object);
//  - lower = max((B + V) / 2, B + 3 S): half maximum, the wall of a partial-volume profile (and
//    the phantoms' wall); never inside the background noise;
//  - upper = the volume's maximum: calcified plaque and brighter inflow vessels are vessel; bright
//    non-vessel structures (bone) are cut by tubularity, not by intensity;
//  - weakLower = max(B + 0.25 (V - B), B + 3 S): thin vessels (radius 0.5-1 voxel) lose contrast
//    to partial volume; a ridge voxel above it bridges a one-voxel gap (SeededRegionGrower).
//  - without a seed, lower is Otsu's threshold of the voxels above B + 3 S (Otsu 1979, eq. 18).
// A volume of two values (a binary mask) gives [midpoint, maximum]: the mask as drawn.
#pragma once

#include "vtouchProgress.h"
#include "vtouchVolumeView.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

namespace vtouch
{

struct IntensityRange
{
  bool ok = false;     ///< false: `message` says why (and what to do)
  bool binary = false; ///< the volume holds two values: a mask
  double lower = 0.0;  ///< vessel: lower <= value <= upper
  double upper = 0.0;
  double weakLower = 0.0; ///< ridge voxels from here bridge gaps of thin vessels
  double background = 0.0;
  double backgroundNoise = 0.0; ///< robust sigma of the background
  double vessel = 0.0;
  /// Seeded runs: the brightest voxel within two voxels of the seed (the click may land beside a
  /// thin vessel); the grower starts there.
  std::array<std::int64_t, 3> seedIndex{ -1, -1, -1 };
  std::string message; ///< empty when ok
};

/// Order statistics of a sample (the sample is reordered).
struct RobustStatistics
{
  double median = 0.0;
  double sigma = 0.0; ///< P50 - P15.87
  double minimum = 0.0;
  double maximum = 0.0;
  static RobustStatistics of(std::vector<double>& values);
  /// Otsu's threshold (between-class variance maximum) of the sample over 256 bins.
  static double otsu(const std::vector<double>& values);
};

struct IntensityRangeParameters
{
  int neighbourhoodHalfSize_voxels = 24; ///< the seed's cube is 49^3 voxels (clamped)
  int peakSearchHalfSize_voxels = 2;
  double minimumContrastToNoise = 5.0; ///< Rose criterion
  double noiseMargin = 3.0;            ///< sigmas above the background
  double weakContrastFraction = 0.25;
  std::uint64_t wholeVolumeSamples = std::uint64_t{ 1 } << 21;
};

class IntensityRangeEstimator
{
public:
  using Parameters = IntensityRangeParameters;

  /// `progress`: the whole-volume scan's check points (may throw Cancelled).
  template<typename T>
  static IntensityRange fromSeed(const VolumeView<T>& volume,
    const std::array<std::int64_t, 3>& seed,
    const Parameters& p = Parameters{},
    const ProgressSpan& progress = ProgressSpan());

  template<typename T>
  static IntensityRange fromVolume(const VolumeView<T>& volume,
    const Parameters& p = Parameters{},
    const ProgressSpan& progress = ProgressSpan());

  static std::string backgroundMessage(double intensity);
  static std::string outsideMessage();

  /// The whole volume's extremes and whether it holds at most two values (fromSeed's one pass
  /// over the volume). Public for the distributed run (DistributedCandidateRegion), whose ranks
  /// combine their pieces' scans before the seed's rank estimates the range.
  struct Scan
  {
    double minimum = 0.0, maximum = 0.0;
    bool twoValued = true; ///< at most two distinct values
    /// The (at most two) distinct values met while twoValued: first, and second when haveSecond.
    double first = 0.0, second = 0.0;
    bool haveSecond = false;
  };
  template<typename T>
  static Scan scan(const VolumeView<T>& volume, const ProgressSpan& progress = ProgressSpan());
  /// fromVolume's sample: every stride-th voxel of the volume in its linear index order, from
  /// index 0, with this stride for a volume of `voxels` (at most about
  /// Parameters::wholeVolumeSamples values). Public for the distributed run
  /// (DistributedVolumeRange): each rank samples the owned voxels on that lattice.
  static std::uint64_t sampleStride(std::uint64_t voxels, const Parameters& p = Parameters{})
  {
    return std::max<std::uint64_t>(1, voxels / p.wholeVolumeSamples);
  }
  /// Whether fromVolume samples the volume after its scan (not for a single intensity or a
  /// two-valued mask: the scan decides those).
  static bool needsSample(const Scan& wholeScan)
  {
    return !(wholeScan.minimum == wholeScan.maximum) && !wholeScan.twoValued;
  }
  /// fromVolume given the whole volume's scan and its sample (sampleStride; empty when
  /// !needsSample). Only order statistics and histogram counts of the sample are used, so the
  /// order of the values does not change the range (the distributed run gathers the ranks'
  /// samples rank by rank).
  static IntensityRange fromVolumeSample(const Scan& wholeScan,
    const std::vector<double>& sample,
    const Parameters& p = Parameters{});

  /// fromSeed with the whole volume's scan given (`volume` may be a piece of it that holds the
  /// seed's neighbourhood: the cube of neighbourhoodHalfSize_voxels and the peak search).
  template<typename T>
  static IntensityRange fromSeedScanned(const VolumeView<T>& volume,
    const std::array<std::int64_t, 3>& seed,
    const Scan& wholeScan,
    const Parameters& p = Parameters{});
};

template<typename T>
IntensityRangeEstimator::Scan IntensityRangeEstimator::scan(const VolumeView<T>& volume,
  const ProgressSpan& progress)
{
  Scan s;
  const std::uint64_t n = volume.size();
  const T* v = volume.voxels;
  T lo = v[0], hi = v[0];
  T first = v[0], second = v[0];
  bool haveSecond = false, two = true;
  // In chunks: a check point per chunk, the inner loop left as tight as it was.
  constexpr std::uint64_t kChunk = std::uint64_t{ 1 } << 20;
  for (std::uint64_t begin = 0; begin < n; begin += kChunk)
  {
    progress.report(static_cast<double>(begin) / static_cast<double>(n));
    const std::uint64_t end = std::min(n, begin + kChunk);
    for (std::uint64_t i = begin; i < end; ++i)
    {
      const T x = v[i];
      lo = std::min(lo, x);
      hi = std::max(hi, x);
      if (two && !(x == first))
      {
        if (!haveSecond)
        {
          second = x;
          haveSecond = true;
        }
        else if (!(x == second))
        {
          two = false;
        }
      }
    }
  }
  s.minimum = static_cast<double>(lo);
  s.maximum = static_cast<double>(hi);
  s.twoValued = two;
  s.first = static_cast<double>(first);
  s.second = static_cast<double>(second);
  s.haveSecond = haveSecond;
  return s;
}

template<typename T>
IntensityRange IntensityRangeEstimator::fromSeed(const VolumeView<T>& volume,
  const std::array<std::int64_t, 3>& seed,
  const Parameters& p,
  const ProgressSpan& progress)
{
  if (volume.size() == 0 || !volume.inside(seed[0], seed[1], seed[2]))
  {
    IntensityRange r;
    r.message = outsideMessage();
    return r;
  }
  return fromSeedScanned(volume, seed, scan(volume, progress), p);
}

template<typename T>
IntensityRange IntensityRangeEstimator::fromSeedScanned(const VolumeView<T>& volume,
  const std::array<std::int64_t, 3>& seed,
  const Scan& s,
  const Parameters& p)
{
  IntensityRange r;
  if (volume.size() == 0 || !volume.inside(seed[0], seed[1], seed[2]))
  {
    r.message = outsideMessage();
    return r;
  }
  r.upper = s.maximum;
  // The brightest voxel near the click.
  double peak = volume.at(seed[0], seed[1], seed[2]);
  r.seedIndex = seed;
  const int h = p.peakSearchHalfSize_voxels;
  for (std::int64_t k = seed[2] - h; k <= seed[2] + h; ++k)
    for (std::int64_t j = seed[1] - h; j <= seed[1] + h; ++j)
      for (std::int64_t i = seed[0] - h; i <= seed[0] + h; ++i)
      {
        if (volume.inside(i, j, k) && volume.at(i, j, k) > peak)
        {
          peak = volume.at(i, j, k);
          r.seedIndex = { i, j, k };
        }
      }
  if (s.twoValued)
  {
    r.binary = true;
    r.lower = r.weakLower = 0.5 * (s.minimum + s.maximum);
    r.background = s.minimum;
    r.vessel = s.maximum;
    if (s.minimum == s.maximum)
    {
      r.message = "The volume holds a single intensity: it has no vessel-like structure.";
      return r;
    }
    if (peak < r.lower)
    {
      r.message = backgroundMessage(volume.at(seed[0], seed[1], seed[2]));
      return r;
    }
    r.ok = true;
    return r;
  }
  // Background statistics over the seed's cube.
  std::vector<double> cube;
  const int c = p.neighbourhoodHalfSize_voxels;
  for (std::int64_t k = std::max<std::int64_t>(0, seed[2] - c);
       k <= std::min(volume.dims[2] - 1, seed[2] + c);
       ++k)
    for (std::int64_t j = std::max<std::int64_t>(0, seed[1] - c);
         j <= std::min(volume.dims[1] - 1, seed[1] + c);
         ++j)
      for (std::int64_t i = std::max<std::int64_t>(0, seed[0] - c);
           i <= std::min(volume.dims[0] - 1, seed[0] + c);
           ++i)
      {
        cube.push_back(volume.at(i, j, k));
      }
  const RobustStatistics bg = RobustStatistics::of(cube);
  r.background = bg.median;
  // A noise floor for noiseless or quantised backgrounds: 0.1 % of the local span.
  r.backgroundNoise = std::max(bg.sigma, 1e-3 * (bg.maximum - bg.minimum));
  // The vessel's plateau around the peak.
  std::vector<double> lumen;
  const double half = 0.5 * (r.background + peak);
  const auto& q = r.seedIndex;
  for (std::int64_t k = q[2] - h; k <= q[2] + h; ++k)
    for (std::int64_t j = q[1] - h; j <= q[1] + h; ++j)
      for (std::int64_t i = q[0] - h; i <= q[0] + h; ++i)
      {
        if (volume.inside(i, j, k) && volume.at(i, j, k) >= half)
        {
          lumen.push_back(volume.at(i, j, k));
        }
      }
  r.vessel = lumen.empty() ? peak : RobustStatistics::of(lumen).median;
  const double contrast = r.vessel - r.background;
  if (!(contrast >= p.minimumContrastToNoise * r.backgroundNoise) || !(contrast > 0.0))
  {
    r.message = backgroundMessage(volume.at(seed[0], seed[1], seed[2]));
    return r;
  }
  const double floor = r.background + p.noiseMargin * r.backgroundNoise;
  r.lower = std::max(0.5 * (r.background + r.vessel), floor);
  r.weakLower =
    std::min(r.lower, std::max(r.background + p.weakContrastFraction * contrast, floor));
  r.ok = true;
  return r;
}

template<typename T>
IntensityRange IntensityRangeEstimator::fromVolume(const VolumeView<T>& volume,
  const Parameters& p,
  const ProgressSpan& progress)
{
  if (volume.size() == 0)
  {
    IntensityRange r;
    r.message = "The volume is empty.";
    return r;
  }
  const Scan s = scan(volume, progress);
  std::vector<double> sample;
  if (needsSample(s))
  {
    const std::uint64_t n = volume.size();
    const std::uint64_t stride = sampleStride(n, p);
    sample.reserve(static_cast<std::size_t>(n / stride + 1));
    for (std::uint64_t i = 0; i < n; i += stride)
    {
      sample.push_back(static_cast<double>(volume.voxels[i]));
    }
  }
  return fromVolumeSample(s, sample, p);
}

} // namespace vtouch

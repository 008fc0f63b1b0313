// The vessel network reachable from a seed: 26-connected region growing over the voxels of an
// IntensityRange (Yi & Hayward §3.1: "forward propagation" from a seed picked on the MIP).
//
// A voxel joins when lower <= value <= upper (a "strong" voxel), or when it is a dim ridge of a
// thin vessel: weakLower <= value <= upper, at least as bright as both its neighbours along two of
// the three axes (the cross-section of a bright tube peaks there), and at most
// kMaximumStrongNeighbours of its 26 neighbours strong (a one-voxel gap of a thin vessel has
// vessel on two sides; the partial-volume shell of a thick vessel faces a whole 3x3 face of it).
// These two rules are the product's (no paper gives them): they keep thin partial-volume vessels
// connected across a dim voxel without thickening the thick ones. Dim dead ends that are not
// detectable objects (noise beside a vessel or past a thin vessel's tip) are cleared afterwards
// (DimStrandPruner).
#pragma once

#include "vtouchDimStrandPruner.h"
#include "vtouchIntensityRangeEstimator.h"
#include "vtouchProgress.h"
#include "vtouchSparseVesselMask.h"
#include "vtouchVolumeView.h"

#include <vector>

namespace vtouch
{

class SeededRegionGrower
{
public:
  static constexpr int kMaximumStrongNeighbours = 6;

  /// The region of `seed` (must be a voxel of the range: IntensityRange::seedIndex).
  /// `progress`: check points every 2^16 voxels joined (the fraction is of the volume, an upper
  /// bound of the region); may throw Cancelled.
  template<typename T>
  static SparseVesselMask grow(const VolumeView<T>& volume,
    const IntensityRange& range,
    const std::array<std::int64_t, 3>& seed,
    const ProgressSpan& progress = ProgressSpan());

  /// Without a seed: every voxel in [lower, upper] (the coder keeps the large components).
  template<typename T>
  static SparseVesselMask threshold(const VolumeView<T>& volume,
    const IntensityRange& range,
    const ProgressSpan& progress = ProgressSpan());

  /// Whether voxel (i, j, k) joins a region that touches it: a strong voxel or a dim ridge
  /// (the grower's rule, for the distributed growth: DistributedRegionGrowth).
  template<typename T>
  static bool joins(const VolumeView<T>& v,
    const IntensityRange& r,
    std::int64_t i,
    std::int64_t j,
    std::int64_t k)
  {
    return strong(v, r, v.linear(i, j, k)) || ridge(v, r, i, j, k);
  }
  template<typename T>
  static bool strong(const VolumeView<T>& v, const IntensityRange& r, std::uint64_t lin)
  {
    const double x = static_cast<double>(v.voxels[lin]);
    return x >= r.lower && x <= r.upper;
  }

private:
  template<typename T>
  static bool ridge(const VolumeView<T>& v,
    const IntensityRange& r,
    std::int64_t i,
    std::int64_t j,
    std::int64_t k);
};

template<typename T>
bool SeededRegionGrower::ridge(const VolumeView<T>& v,
  const IntensityRange& r,
  std::int64_t i,
  std::int64_t j,
  std::int64_t k)
{
  const double x = v.at(i, j, k);
  if (!(x >= r.weakLower && x <= r.upper))
  {
    return false;
  }
  int peaks = 0;
  const std::int64_t c[3] = { i, j, k };
  for (int a = 0; a < 3; ++a)
  {
    bool peak = true;
    for (int s = -1; s <= 1; s += 2)
    {
      std::int64_t n[3] = { c[0], c[1], c[2] };
      n[a] += s;
      if (v.inside(n[0], n[1], n[2]) && v.at(n[0], n[1], n[2]) > x)
      {
        peak = false;
      }
    }
    peaks += peak ? 1 : 0;
  }
  if (peaks < 2)
  {
    return false;
  }
  int strongNeighbours = 0;
  for (std::int64_t dk = -1; dk <= 1; ++dk)
    for (std::int64_t dj = -1; dj <= 1; ++dj)
      for (std::int64_t di = -1; di <= 1; ++di)
      {
        if ((di || dj || dk) && v.inside(i + di, j + dj, k + dk) &&
            strong(v, r, v.linear(i + di, j + dj, k + dk)))
        {
          ++strongNeighbours;
        }
      }
  return strongNeighbours <= kMaximumStrongNeighbours;
}

template<typename T>
SparseVesselMask SeededRegionGrower::grow(const VolumeView<T>& volume,
  const IntensityRange& range,
  const std::array<std::int64_t, 3>& seed,
  const ProgressSpan& progress)
{
  SparseVesselMask mask(volume.dims);
  if (!volume.inside(seed[0], seed[1], seed[2]))
  {
    mask.finalize();
    return mask;
  }
  std::vector<std::uint64_t> stack{ volume.linear(seed[0], seed[1], seed[2]) };
  mask.set(stack.back());
  std::vector<std::uint64_t> dim; // the ridge voxels below range.lower that joined
  ProgressCounter counter(progress, volume.size());
  while (!stack.empty())
  {
    counter.tick();
    const std::uint64_t lin = stack.back();
    stack.pop_back();
    const auto c = volume.index(lin);
    for (std::int64_t dk = -1; dk <= 1; ++dk)
      for (std::int64_t dj = -1; dj <= 1; ++dj)
        for (std::int64_t di = -1; di <= 1; ++di)
        {
          const std::int64_t i = c[0] + di, j = c[1] + dj, k = c[2] + dk;
          if (!volume.inside(i, j, k))
          {
            continue;
          }
          const std::uint64_t n = volume.linear(i, j, k);
          if (mask.test(n) || !(strong(volume, range, n) || ridge(volume, range, i, j, k)))
          {
            continue;
          }
          mask.set(n);
          stack.push_back(n);
          if (!strong(volume, range, n))
          {
            dim.push_back(n);
          }
        }
  }
  DimStrandPruner::prune(volume, range, dim, mask);
  mask.finalize();
  return mask;
}

template<typename T>
SparseVesselMask SeededRegionGrower::threshold(const VolumeView<T>& volume,
  const IntensityRange& range,
  const ProgressSpan& progress)
{
  SparseVesselMask mask(volume.dims);
  const std::uint64_t n = volume.size();
  ProgressCounter counter(progress, (n + 63) / 64, ProgressCounter::kVoxelPeriod / 64);
  for (std::uint64_t w = 0; w < (n + 63) / 64; ++w)
  {
    counter.tick();
    std::uint64_t bits = 0;
    const std::uint64_t last = std::min(n, w * 64 + 64);
    for (std::uint64_t i = w * 64; i < last; ++i)
    {
      bits |= static_cast<std::uint64_t>(strong(volume, range, i)) << (i - w * 64);
    }
    mask.setWord(w, bits);
  }
  mask.finalize();
  return mask;
}

} // namespace vtouch

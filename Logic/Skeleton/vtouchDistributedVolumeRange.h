// IntensityRangeEstimator::fromVolume (the automatic range without a seed) on a distributed
// volume, exactly the single run's (issue 19 item 2, issue 16 item 1 "Without a seed the
// automatic range applies to the whole volume"; Docs/CLIENT-SERVER.md, "The raw mode without a
// seed, distributed"). No rank reads the whole volume:
//  1. the whole volume's scan (extremes, two-valued): the ranks' scans combined
//     (DistributedCandidateRegion::combine, the caller's step);
//  2. the sample: fromVolume takes every stride-th voxel of the whole volume in its linear index
//     order (IntensityRangeEstimator::sampleStride of the whole volume's size); each rank takes
//     the voxels it owns on that lattice (owned boxes tile the volume: every lattice voxel once),
//     and one AllGather gives every rank the whole sample;
//  3. the statistics: IntensityRangeEstimator::fromVolumeSample, the single run's own code, on
//     every rank. They read only order statistics and histogram counts of the sample, so the
//     ranks' order of the values (rank by rank, not the linear order) gives the same range, bit
//     for bit (vtouchDistributedVolumeRangeTest asserts it on 2, 4 and 8 pieces).
// The sample is at most about IntensityRangeParameters::wholeVolumeSamples (2^21) doubles on
// every rank (16 MiB): the single run's sample, not the volume.
#pragma once

#include "vtouchIntensityRangeEstimator.h"
#include "vtouchPieceLayout.h"
#include "vtouchRankCollectives.h"
#include "vtouchVolumeView.h"

#include <cstdint>
#include <vector>

namespace vtouch
{

class DistributedVolumeRange
{
public:
  /// This rank's part of fromVolume's sample: the voxels of its owned box whose whole-volume
  /// linear index is a multiple of the stride, in linear order. `piece` is the rank's held box
  /// (layout.mine()); empty when it owns nothing.
  template<typename T>
  static std::vector<double> ownedSample(const VolumeView<T>& piece,
    const PieceLayout& layout,
    const IntensityRangeParameters& p = IntensityRangeParameters{})
  {
    std::vector<double> sample;
    const VoxelBox& o = layout.owned[static_cast<std::size_t>(layout.rank)];
    if (o.empty() || piece.size() == 0)
    {
      return sample;
    }
    const auto& w = layout.wholeDims;
    const auto stride = static_cast<std::int64_t>(
      IntensityRangeEstimator::sampleStride(static_cast<std::uint64_t>(w[0] * w[1] * w[2]), p));
    for (std::int64_t k = o.lo[2]; k <= o.hi[2]; ++k)
      for (std::int64_t j = o.lo[1]; j <= o.hi[1]; ++j)
      {
        const std::int64_t rowStart = layout.wholeLinear({ o.lo[0], j, k });
        // The row's first lattice voxel: the next multiple of the stride from rowStart.
        std::int64_t i = o.lo[0] + (stride - rowStart % stride) % stride;
        for (; i <= o.hi[0]; i += stride)
        {
          const auto q = layout.toLocal({ i, j, k });
          sample.push_back(piece.at(q[0], q[1], q[2]));
        }
      }
    return sample;
  }

  /// Collective (one AllGather when the scan needs a sample, none otherwise: `wholeScan` is the
  /// same on every rank, so is that choice): fromVolume's range of the whole volume, the same on
  /// every rank, message included.
  template<typename T>
  static IntensityRange estimate(const VolumeView<T>& piece,
    const PieceLayout& layout,
    const IntensityRangeEstimator::Scan& wholeScan,
    RankCollectives& collectives,
    const IntensityRangeParameters& p = IntensityRangeParameters{})
  {
    std::vector<double> sample;
    if (IntensityRangeEstimator::needsSample(wholeScan))
    {
      for (const std::vector<double>& part : collectives.allGather(ownedSample(piece, layout, p)))
      {
        sample.insert(sample.end(), part.begin(), part.end());
      }
    }
    return IntensityRangeEstimator::fromVolumeSample(wholeScan, sample, p);
  }
};

} // namespace vtouch

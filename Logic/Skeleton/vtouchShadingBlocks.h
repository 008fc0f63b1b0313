// ShadingField's evidence (Docs/CENTERLINES.md, "Raw angiograms", step 0): the background level
// of blocks of the volume, each the median of the sample lattice's voxels in the block. Vessels
// fill well under half of a block, as of the seed's cube (IntensityRangeEstimator). A block at
// the image's zero (padding, air outside the body) holds no evidence; one under a quarter of the
// typical block's level (air, lung) is another tissue and starts out of the fit.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

namespace vtouch
{

struct ShadingBlock
{
  std::array<double, 3> centre{}; ///< whole-volume voxel coordinates
  double logLevel = 0.0;          ///< log of the block's median
  double weight = 0.0;            ///< its samples
  bool kept = true;               ///< in the fit (ShadingField::fit drops and takes back)
  bool eligible = true;           ///< not air or lung: the fit may take it back
};

class ShadingBlocks
{
public:
  struct Sample
  {
    std::uint64_t linear = 0;
    double value = 0.0;
  };
  /// The blocks of a volume of `wholeDims` from its lattice sample of `stride` (finite values,
  /// none negative): edges of `minimumEdge_voxels` or more, so that a whole block holds at least
  /// `minimumSamples`; blocks with fewer (a thin remainder at a face) or at zero are left out.
  static std::vector<ShadingBlock> levels(const std::array<std::int64_t, 3>& wholeDims,
    std::uint64_t stride,
    const std::vector<Sample>& samples,
    std::int64_t minimumEdge_voxels,
    std::uint64_t minimumSamples);

  /// Value at fraction q of the sample by nearest rank (the sample is reordered).
  static double quantile(std::vector<double>& v, double q);
};

} // namespace vtouch

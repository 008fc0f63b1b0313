// The scale at which the voxel coding of a large mask of thick vessels runs: a coarse grid that
// still resolves every vessel by several voxels across ("model no more than the scene needs").
// The coarse skeleton is then moved back onto the full-resolution mask (CoarseSkeletonRefiner).
#pragma once

#include "vtouchSparseVesselMask.h"
#include "vtouchVoxelCoding.h"

#include <array>
#include <cstdint>

namespace vtouch
{

class AutomaticDownsampling
{
public:
  /// Below this many vessel voxels full resolution is cheap (well under a second): it is kept.
  static constexpr std::uint64_t kMinimumVesselVoxels = std::uint64_t{ 1 } << 18;
  /// The typical vessel radius must span at least this many coarse voxels.
  static constexpr double kCoarseRadius_vox = 6.0;
  /// Every traced branch of the coarse skeleton must keep at least this median radius, in coarse
  /// voxels, or the full resolution is used after all.
  static constexpr double kBranchRadius_vox = 2.0;
  static constexpr unsigned int kMaximumFactor = 2;

  /// Typical vessel radius of a mask, in voxels: 2 V / S, with V the vessel voxels and S those with
  /// a 6-neighbour outside the vessel (or the volume). A long cylinder of radius r voxels gives r
  /// divided by its digital surface factor (1 to about 1.3), so the estimate errs low.
  static double typicalRadius_vox(const SparseVesselMask& mask);

  /// The downsampling factor for `mask` with voxels of `spacing_mm`: 1 for small masks, else the
  /// largest factor (at most kMaximumFactor) that leaves kCoarseRadius_vox coarse voxels, measured
  /// along the coarse voxel's longest side, in the typical radius (the radius in voxels times the
  /// geometric mean spacing: anisotropic volumes are coarsened less).
  static unsigned int factorFor(const SparseVesselMask& mask,
    const std::array<double, 3>& spacing_mm);

  /// True when every path of a skeleton coded at `coarseVoxel_mm` (its largest spacing) that is
  /// longer than its own diameter has a median radius of at least kBranchRadius_vox voxels: no thin
  /// branch was coded at a scale too coarse for it.
  static bool resolvesEveryBranch(const RawSkeleton& coarse, double coarseVoxel_mm);
};

} // namespace vtouch

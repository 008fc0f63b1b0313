// The single run's SS code (VoxelCoder's stage 2, SeedCodeStage) on a whole mask: what the
// distributed stages' tests and benchmarks compare every rank's field with (issue 19 item 2).
// The grid, codes, meter and stage wired as VoxelCoder wires them (no progress, cluster width 0);
// one place for the set-up that vtouchDistributedSeedCodeTest, vtouchSeededDistributedCodingTest,
// vtouchDistributedRootChoiceTest (SingleRun, RodCode) and the two distributed benchmarks each
// carried (duplicates --change; branch hdup).
#pragma once

#include "vtouchSkeletonRunMeter.h"
#include "vtouchSkeletonSeedCodeStage.h"
#include "vtouchSkeletonVoxelCodes.h"
#include "vtouchSkeletonVoxelGrid.h"
#include "vtouchSparseVesselMask.h"
#include "vtouchVoxelCoding.h"

#include <array>
#include <cstdint>
#include <functional>
#include <vector>

namespace vtouch::test
{

struct SeedCodeRun
{
  /// The stage on `mask` with voxels of `spacing_mm`; every code infinite until propagateFrom.
  SeedCodeRun(const SparseVesselMask& mask, const std::array<double, 3>& spacing_mm);
  SeedCodeRun(const SeedCodeRun&) = delete;
  SeedCodeRun& operator=(const SeedCodeRun&) = delete;

  /// Propagates from `roots` (whole-volume voxel indices of vessel voxels) as one source set;
  /// the field, indexed by the mask's rank.
  const std::vector<float>& propagateFrom(const std::vector<std::array<std::int64_t, 3>>& roots);
  /// The code (mm) of vessel voxel `v`.
  float ssAt(const std::array<std::int64_t, 3>& v) const;
  std::uint32_t linOf(const std::array<std::int64_t, 3>& v) const;

  skeleton::VoxelGrid grid;
  skeleton::VoxelCodes codes;
  std::function<bool(double)> noProgress;
  skeleton::RunMeter meter;
  skeleton::SeedCodeStage stage;
};

/// The single run's SS field from `roots` on `mask` (indexed by the mask's rank).
std::vector<float> singleRunField(const SparseVesselMask& mask,
  const std::array<double, 3>& spacing_mm,
  const std::vector<std::array<std::int64_t, 3>>& roots);

/// The single run's skeleton seeded at `root` (VoxelCoder with hasSeed) on voxels of `spacing_mm`.
RawSkeleton seededSkeleton(const SparseVesselMask& mask,
  const std::array<double, 3>& spacing_mm,
  const std::array<std::int64_t, 3>& root);

} // namespace vtouch::test

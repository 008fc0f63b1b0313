// Private to Logic/Skeleton: stage 2 of vtouch::VoxelCoder, the single-seed (SS) code.
#pragma once

#include "vtouchSkeletonRunMeter.h"
#include "vtouchSkeletonVoxelCodes.h"
#include "vtouchSkeletonVoxelGrid.h"

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

namespace vtouch
{
namespace skeleton
{

/// The SS code (Zhou & Toga's single-seed code, from a root: Yi & Hayward §3.1's seed, or an
/// extremity when none is given): the exact geodesic
/// distance (mm, 26-neighbour steps of their metric length) from the sources, by Dijkstra on a
/// bucket queue; and the choice of the root at an extremity of a component (double propagation).
///
/// Input: the grid. Output, in `codes`: `ss`, `order` (the component in SS order) and the kDone
/// flag; `ss` must be infinite and kDone clear on the voxels it reaches (reset() restores that).
class SeedCodeStage
{
public:
  /// `clusterWidth_mm` is passed on to the coarse grid of the exploratory propagation.
  SeedCodeStage(const VoxelGrid& grid, RunMeter& meter, VoxelCodes& codes, double clusterWidth_mm);
  ~SeedCodeStage();
  SeedCodeStage(const SeedCodeStage&) = delete;
  SeedCodeStage& operator=(const SeedCodeStage&) = delete;

  /// Propagates the SS code from `sources` (vessel voxels, lin) over their component.
  void propagate(const std::vector<std::uint32_t>& sources);

  /// A voxel (lin) and its distance from the root, mm: a source of relax().
  struct Source
  {
    std::uint32_t lin;
    float ss_mm;
  };

  /// The propagate() variant of the distributed SS code's rounds (vtouch::DistributedSeedCode):
  /// lowers `ss` from `sources` (each a vessel voxel with a distance from the root that another
  /// piece found, or 0 at the root) and from every voxel it lowers, by the same Dijkstra on the
  /// same bucket queue, each source entering the queue when it reaches the source's bucket.
  /// Unlike propagate(), it keeps the `ss` of earlier calls (only lower values pass) and clears
  /// kDone on every voxel it lowers, so calls may follow each other; it leaves `order` alone.
  /// Appends to `lowered` (lin) every voxel whose `ss` it lowered (a voxel may appear twice).
  /// Returns the voxels it settled (popped with their final value): each lowered voxel once,
  /// as Dijkstra does, unless float round-off lowers a settled one again.
  std::size_t relax(std::vector<Source> sources, std::vector<std::uint32_t>& lowered);

  /// Undoes the last propagation (its voxels back to infinite SS, kDone clear).
  void reset();

  /// The far end of the last propagation: in its last SS bucket (as wide as the smallest voxel
  /// side), the voxel with the largest linear index (project rule, vtouchSkeletonEndCapRule.h:
  /// a distributed run finds the same).
  std::uint32_t farVoxel() const;

  /// The automatic root: the cluster of voxels farthest from an arbitrary start (double
  /// propagation: the voxels within one band of farVoxel()'s SS connected to it), reduced to the
  /// vessel voxel nearest its centroid (integer index sums; the end cap is centred on the axis),
  /// or the whole cluster when that voxel is background. Reads the last propagation.
  std::vector<std::uint32_t> extremityRegion();

  /// The exploratory half of the double propagation on the 2x2x2 block mask (about a sixth of
  /// the voxels of a thick vessel): the far end of `lin`'s component from `lin`'s block, as the
  /// vessel voxel nearest that end cap's centre. kNoVoxel for small masks (the exact search is
  /// as cheap) or when no vessel voxel lies near it. Any extremity gives a valid SS code, and the
  /// tree's root is moved to its thickest end afterwards anyway.
  std::uint32_t coarseExtremity(std::uint32_t lin);
  static constexpr std::uint32_t kNoVoxel = 0xFFFFFFFFU;
  /// coarseExtremity() explores on blocks from this many vessel voxels in the mask (below, the
  /// exact search costs little and the block mask would not pay for itself).
  static constexpr std::uint64_t kCoarseFromVoxels = std::uint64_t{ 1 } << 17;

  /// The largest bucket queue so far, entries.
  std::size_t peakQueue() const { return this->peakQueueEntries; }
  /// The block mask and the explorer's arrays, bytes (0 when no exploration ran); they live until
  /// the end of the run.
  std::size_t explorerBytes() const;

private:
  struct Explorer;

  const VoxelGrid& grid;
  RunMeter& meter;
  VoxelCodes& codes;
  double clusterWidth_mm;
  std::size_t peakQueueEntries = 0;
  std::unique_ptr<Explorer> explorer;
};

} // namespace skeleton
} // namespace vtouch

// The SS code of the voxel coding across the pieces of a distributed volume, in rounds (issue 19
// item 2: every rank codes with the single run's SS field, not with a root of its own).
//
// The SS code is a shortest-path distance (Zhou & Toga's single-seed code: SeedCodeStage), so it
// is computed distributed exactly, as a distributed Bellman-Ford whose rounds are each a local
// Dijkstra: each rank runs SeedCodeStage::relax on its held box from its sources (the root when it
// holds it; then the voxels whose distance another rank reported, with that distance), and
// reports the vessel voxels it owns whose distance fell and that another rank holds (sparse:
// whole-volume linear index and distance); the rounds end when no rank reports one.
//
// Exact (the single run's float values, not an approximation): every value on every rank is the
// float sum along a real path, so never below the single run's; and along a shortest path
// v0 (the root) .. vk, the owner of v(i-1) holds v(i) (held boxes reach at least one voxel past
// the owned ones), so the owner of v(i) gets v(i)'s value either by its own step from v(i-1),
// reported to it when v(i-1)'s owner is another rank, or from v(i-1)'s owner's report of v(i-1),
// then steps to v(i) itself. By induction each owner ends with the single run's value on its
// voxels, and each rank receives its other held voxels' values from their owners. The rounds are
// at most the number of owner changes along the longest shortest path, plus one.
//
// Memory: the piece's 5 bytes per vessel voxel (ss and flags) and the queue; no whole-volume
// array on any rank.
#pragma once

#include "vtouchPieceLayout.h"
#include "vtouchRankCollectives.h"
#include "vtouchRoundsOutcome.h"
#include "vtouchSparseVesselMask.h"

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace vtouch
{

class DistributedSeedCode
{
public:
  /// A project rule, as DistributedRegionGrowth's: a vessel network whose shortest paths cross
  /// between pieces more often than this is not a vessel tree; the rounds stop with a message,
  /// every rank at the same round.
  static constexpr int kDefaultMaximumRounds = 1000;

  /// `layout`: the pieces (held boxes must reach at least one voxel past the owned ones on every
  /// face that is not the volume's, so that every 26-neighbour step is inside some rank's box).
  /// `pieceMask`: this rank's vessel voxels on its held box (local linear index, finalized),
  /// equal to the whole mask there. `spacing_mm`: the voxel size (> 0, the same on every rank).
  /// Throws std::invalid_argument on a layout, mask or spacing that cannot work.
  DistributedSeedCode(PieceLayout layout,
    const SparseVesselMask& pieceMask,
    const std::array<double, 3>& spacing_mm);
  ~DistributedSeedCode();
  DistributedSeedCode(const DistributedSeedCode&) = delete;
  DistributedSeedCode& operator=(const DistributedSeedCode&) = delete;

  /// What the rounds did (the same rounds and message on every rank).
  using Outcome = RoundsOutcome;

  /// Collective: the SS code from `roots_Whole` (whole-volume voxel indices, the same list on
  /// every rank, distance 0 each: the seed, or the automatic root) to the end of the rounds.
  /// Every root must be a vessel voxel: otherwise every rank throws std::invalid_argument
  /// together (its owner tells the others in the first exchange). Starts from infinite codes.
  /// The rounds are CollectiveRounds's (a failure on one rank is thrown on every rank).
  Outcome run(RankCollectives& collectives,
    const std::vector<std::array<std::int64_t, 3>>& roots_Whole,
    int maximumRounds = kDefaultMaximumRounds);

  /// The SS code after run(), mm, per vessel voxel of the piece mask (indexed by
  /// SparseVesselMask::rank); infinite where no root's component reaches.
  const std::vector<float>& ss() const;
  /// The SS code of local voxel `localLinear` (infinite when it is background or not reached).
  float ssAt(std::uint64_t localLinear) const;

private:
  struct Impl;
  std::unique_ptr<Impl> P;
};

} // namespace vtouch

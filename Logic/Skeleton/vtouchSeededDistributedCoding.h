// The seeded modes' global SS code on one rank's piece, for the voxel coder (issue 19 item 2):
// the agreement before vtouch::DistributedSeedCode's rounds, the root, and the rounds.
//
// The rounds are collective: every rank must reach them exactly once per run, with the mask its
// coder codes. A rank reaches them from inside its coder (code(), with the final mask: after the
// threshold or the raw region; at full resolution) or, when its run stopped before the coder (a
// piece without vessels, an error), from the caller afterwards (join(), with an empty mask). Both
// take the same collective steps, so no rank waits for one that is not coming:
//  1. one AllGather of each rank's state: whether it can take part (its held box, its mask's size,
//     DistributedSeedCode's checks) and, on the ranks holding the seed, the root they propose;
//  2. a common verdict from those data (the same on every rank): a rank that cannot take part, no
//     root (the seed outside the volume) or a seed off the vessels stop every rank with the same
//     message, before any round;
//  3. DistributedSeedCode::run from that root, every rank to the same last round (a round cap
//     stops every rank with the same message).
// The root is the single run's (VoxelCodingSkeletonFilter::SeedIndex): the vessel voxel of the
// seed voxel's 3 x 3 x 3 block nearest its centre (first in k, j, i order among ties), proposed by
// the rank owning the seed voxel (its held box holds the block and equals the whole mask there);
// only when no owner proposes (the raw mode: the region's seed is known on the seed's rank only)
// by the lowest rank that proposes.
//
// Plain C++ over vtouch::RankCollectives (the filter: vtkMultiProcessController; the tests:
// threads).
#pragma once

#include "vtouchDistributedSeedCode.h"
#include "vtouchPieceLayout.h"
#include "vtouchRankCollectives.h"
#include "vtouchSparseVesselMask.h"

#include <array>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace vtouch
{

/// Clears `mask`'s vessel voxels outside rank `layout.rank`'s evaluable box (its outermost layer
/// on faces that are not the volume's: the raw seeded mode, Settings::clearOuterLayer); returns
/// how many. `mask`: the rank's held box, local linear index; finalized again.
std::uint64_t clearOuterLayer(SparseVesselMask& mask, const PieceLayout& layout);

/// Thrown by code() and join() on every rank together, with the same message.
class SeededDistributedCodingError : public std::runtime_error
{
public:
  using std::runtime_error::runtime_error;
};

class SeededDistributedCoding
{
public:
  struct Settings
  {
    /// Clear the piece mask's outermost layer on shared faces before the rounds (the raw seeded
    /// mode: the region is exact only on the evaluable box, PieceLayout::evaluable; off: the
    /// mask equals the whole mask on the whole held box, as a threshold mask does).
    bool clearOuterLayer = false;
    int maximumRounds = DistributedSeedCode::kDefaultMaximumRounds;
  };

  /// What the run did (valid after code() or join()).
  struct Report
  {
    int rounds = 0;                   ///< exchanges of the SS rounds (the same on every rank)
    std::uint64_t reportedVoxels = 0; ///< voxels this rank reported, all rounds
    std::uint64_t clearedVoxels = 0;  ///< vessel voxels cleared from the outer layer
    std::array<std::int64_t, 3> root_Whole{ -1, -1, -1 }; ///< the common root
  };

  /// `layout`: the pieces, the same on every rank (gathered), `layout.rank` this rank. A rank
  /// without a piece has an empty held box (every rank then stops at the verdict).
  /// `spacing_mm`: the voxel size. `hasSeed`: this rank knows the seed voxel `seed_Whole`
  /// (whole-volume index; it may lie outside the volume: the verdict says so).
  SeededDistributedCoding(RankCollectives& collectives,
    PieceLayout layout,
    const std::array<double, 3>& spacing_mm,
    bool hasSeed,
    const std::array<std::int64_t, 3>& seed_Whole,
    const Settings& settings);

  /// Collective, once per run: the single run's SS field on `mask` (this rank's vessel voxels on
  /// its held box, local linear index, finalized), indexed by `mask`'s rank, mm; infinite where
  /// the seed's network does not reach. With clearOuterLayer the mask loses its outer layer
  /// first (the field is indexed by the mask as left). Throws SeededDistributedCodingError (every
  /// rank together) when the verdict or the rounds fail; std::logic_error when called twice.
  std::vector<float> code(SparseVesselMask& mask);

  /// Collective: takes part with an empty mask, for a rank whose run stopped before its coder
  /// (call it when joined() is false after the run). Throws as code() does.
  void join();

  bool joined() const { return this->Joined; }
  const Report& report() const { return this->Result; }

private:
  std::vector<float> take(SparseVesselMask& mask, bool usable);

  RankCollectives& Collectives;
  PieceLayout Layout;
  std::array<double, 3> Spacing_mm;
  bool HasSeed;
  std::array<std::int64_t, 3> Seed_Whole;
  Settings Options;
  bool Joined = false;
  Report Result;
};

} // namespace vtouch

// The single run's order of the true tips across the pieces (issue 19 item 2, h17j): the key a
// rank coded with the global SS field orders its tips by, and carries along the tips' traces to
// the face tips (vtouch::DistributedFaceTips).
//
// The single run traces its tips farthest first (Zhou & Toga's back-tracing, Yi & Hayward §3.1):
// by band, higher first, and tips of one band in its clusters' number order, the key order (the
// SS of the cluster's smallest voxel, then that voxel's index: ClusterStage::build, "One cluster
// order" in Docs/CLIENT-SERVER.md). A piece numbers its clusters in the same key order, so its
// own tips of one band keep the single run's order; but a face tip answered with the band of a
// true tip beyond the face could only tie with a true tip of that band held by the rank, and the
// tie went to the true tip (its own band is the higher). The 256^3 raw phantom without a seed on
// 2 ranks: the two arms of the junction near the automatic root end at two tips of band 193;
// the single run traces the one at (104, 142, 5) first (the smaller key), rank 1 holds the other,
// (93, 211, 111), and traced it first, so the arms' roles swapped (Docs/CLIENT-SERVER.md, "The
// raw modes"). Hence the rank key: the band and the tip's place in the single run's order.
//
// The rank key (int64): the band in the bits from kPlaceBits up, and below them kPlaceMask minus
// the tip's place in the single run's order of all the volume's true tips (larger: traced
// first); a tip whose place is not known has 0 there (after the placed tips of its band). The
// key stays below 2^53, so a double carries it exactly (the face tips' rounds): bands below
// kBandLimit (thrown otherwise, on every rank together).
#pragma once

#include "vtouchRankCollectives.h"

#include <cstddef>
#include <cstdint>
#include <unordered_map>
#include <utility>
#include <vector>

namespace vtouch
{

class DistributedTipOrder
{
public:
  static constexpr int kPlaceBits = 32;
  static constexpr std::int64_t kPlaceMask = (std::int64_t{ 1 } << kPlaceBits) - 1;
  /// Bands at or above this do not fit a rank key a double holds exactly (2^53 / 2^32).
  static constexpr std::int64_t kBandLimit = std::int64_t{ 1 } << 21;

  /// One true tip: its cluster's band, the SS (mm) of its smallest voxel and that voxel's
  /// whole-volume linear index (the single run's cluster key).
  struct Tip
  {
    std::uint32_t band = 0;
    float firstSs_mm = 0.0F;
    std::int64_t firstWhole = 0;
  };

  /// The rank key of a tip of `band` at `place` in the single run's order (see above).
  static std::int64_t rankKey(std::uint32_t band, std::int64_t place);
  /// The rank key of a tip of `band` whose place is not known (and the single run's tips: every
  /// tip unplaced, the band alone orders them).
  static std::int64_t unplacedRankKey(std::uint32_t band) { return rankKey(band, kPlaceMask); }

  /// Collective, once per run on every rank: `mine` are this rank's true tips, each volume tip on
  /// exactly one rank (the owner of its trace's start). Throws std::runtime_error on every rank
  /// when a band reaches kBandLimit.
  void gather(RankCollectives& collectives, const std::vector<Tip>& mine);

  /// The rank key of the tip whose smallest voxel is `firstWhole`, of `band`, or the unplaced
  /// key when no rank gathered it.
  std::int64_t rankKeyOf(std::int64_t firstWhole, std::uint32_t band) const;

  std::size_t tips() const { return this->PlaceOf.size(); }

private:
  std::unordered_map<std::int64_t, std::pair<std::uint32_t, std::int64_t>> PlaceOf; // band, place
};

} // namespace vtouch

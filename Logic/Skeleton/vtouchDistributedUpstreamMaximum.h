// The farthest tip above every vessel voxel, across pieces (issue 19 item 2, h19q): a candidate
// key for ordering a piece's tips as the single run does; right on trees, not on loops (below).
//
// Why. The voxel coder traces its tips farthest first (TraceStage: clusters without higher
// neighbours, by SS band); the first trace through a junction is the path that runs through it,
// the later ones are branches joined to it, so the order shapes the junction's geometry. A rank
// coding its grown piece with the single run's SS field (the global field) sees, where its piece
// cuts a vessel, a tip at the cut whose SS is the cut's, lower than the single run's tip beyond.
// It may then trace another vessel through the junction first: on ClientServer.
// DistributedExtraction's Y on 4 ranks that moves 4 points by up to 0.581 voxel, on the 256^3
// scaling tree by up to 1.66 voxel (Docs/CLIENT-SERVER.md, "Where the distributed geometry
// departs"). For a voxel v: U(v), the largest SS on a path from v along which SS rises at every
// step (26-neighbours); at a tip of the single run (a local maximum) U is its own SS. Tips
// ordered by U, wired through a pvserver (tried, not kept): the Y on 4 ranks 0.000 voxel, the
// tree 0.767; but the seeded ring (a loop) lost a bifurcation: both legs rise to where the
// fronts meet, so two cut tips get one key, while the single run descends one leg only. The
// key the coder needs follows the descent (SkeletonTracer::descend's steps), not every rising
// step; these rounds carry over to it, the step does not.
//
// How, exactly. U is a maximum over rising paths, so it is a fixed point of
// U(v) = max(SS(v), U(w) for every neighbour w with SS(w) > SS(v)), reached from U = SS by
// raising values only. Each round every rank makes one pass over its held voxels in decreasing
// SS (which settles every rising path inside its box), then reports the voxels it owns whose U
// rose and that another rank holds (whole-volume linear index and the float value as a double:
// exact); a rank takes a reported value where it is higher. Every value is the SS of a voxel
// reached by a rising path, so never above the whole volume's U; along a rising path the owner
// of each voxel holds the next (held boxes reach one voxel past the owned ones), so each owner
// ends with the whole volume's U on its voxels and every rank gets its other held voxels' values
// from their owners. The rounds end when no rank reports (CollectiveRounds: one verdict, a cap).
#pragma once

#include "vtouchPieceLayout.h"
#include "vtouchRankCollectives.h"
#include "vtouchRoundsOutcome.h"
#include "vtouchSparseVesselMask.h"

#include <vector>

namespace vtouch
{

class DistributedUpstreamMaximum
{
public:
  /// A project rule, as DistributedSeedCode's: a network whose rising paths cross between
  /// pieces more often than this is not a vessel tree.
  static constexpr int kDefaultMaximumRounds = 1000;

  /// `layout`: the pieces (held boxes one voxel or more past the owned ones; checked).
  /// `pieceMask`: this rank's vessel voxels on its held box (local linear index, finalized).
  /// `ss_mm`: the global SS field on them (indexed by SparseVesselMask::rank; infinite where no
  /// root reaches). Throws std::invalid_argument on a layout or field that cannot work.
  DistributedUpstreamMaximum(PieceLayout layout,
    const SparseVesselMask& pieceMask,
    const std::vector<float>& ss_mm);

  /// Collective: the rounds to the end (every rank the same number; a failure or the cap on
  /// every rank together).
  RoundsOutcome run(RankCollectives& collectives, int maximumRounds = kDefaultMaximumRounds);

  /// U after run(), mm, per vessel voxel of the piece mask (infinite where SS is).
  const std::vector<float>& upstream_mm() const { return this->Upstream; }

  /// The definition on one whole mask (one process): the reference for the distributed rounds.
  static std::vector<float> wholeVolume(const SparseVesselMask& mask,
    const std::vector<float>& ss_mm);

private:
  /// One pass in decreasing SS; the local linear indices of owned voxels that rose.
  void pass(std::vector<std::uint64_t>& rose);

  PieceLayout Layout;
  const SparseVesselMask& Mask;
  const std::vector<float>& Ss;
  std::vector<float> Upstream;
  std::vector<std::uint64_t> Descending; ///< held vessel voxels with a finite SS, SS decreasing
};

} // namespace vtouch

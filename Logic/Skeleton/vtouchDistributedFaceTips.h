// The single run's answer for each face tip of a piece coded with the global SS field (issue 19
// item 2, "A root in the middle of a tube", Docs/CLIENT-SERVER.md).
//
// A face tip is a cluster without higher neighbours that touches a face of the piece shared with
// another piece (where the coded mask ends: the held box's face, or the evaluable box's in the raw
// seeded mode, setOuterLayerCleared): a local maximum of the SS code only because the piece ends
// there. The single run has no such tip: it traces the farthest true tip beyond the face first
// (its tip order is by the tip's band, Zhou & Toga's back-tracing, Yi & Hayward §3.1), or, when
// no tip's trace enters the piece there, reaches that side only by closing a loop
// (LoopStage::closeLoops' side B). The root's rank has to know which, or it orders and joins the
// root's two sides unlike the single run.
//
// How: the traces of the true tips, without touches (SkeletonTracer::descend on the global field,
// which steps from a voxel to its lower neighbour of largest BS: memoryless, so the same chain on
// every rank away from its faces), are followed across the pieces in collective rounds
// (CollectiveRounds, as the SS field's): each rank descends from its own true tips (not at a
// shared face, starting voxel owned) and from the chain voxels handed to it, along its owned box;
// where a chain steps into another rank's owned box it hands the chain over (the voxel and the
// tip's band), and it tells every rank whose held box the chain crosses in its owned box which
// voxels it crossed, with the band. The rounds end when no rank hands anything over; at most one
// round per owner change along the longest chain, plus one.
//
// A face tip's answer: its own descent (no touches) from the face, the first cluster within a few
// bands plus two of the vessel's radii (kAnswerWindow_*) of where the descent leaves the face
// (its last voxel within a radius of a cut face, or in a cluster a shared face cuts) that holds
// a voxel of a crossing chain gives the largest rank key among those voxels; none: no tip's trace
// enters the piece there (a loop's second side). The chains carry their tip's rank key
// (vtouch::DistributedTipOrder, gathered once before the rounds: the band, then the tip's place
// in the single run's order), not its band alone (h17j): a face tip answered with a tip of the
// band of a true tip the rank holds goes before or after it as the single run traces them. The
// radius is the largest BS of the clusters the descent crossed, not the face tip's own: where a
// vessel crosses the face obliquely that is a sliver at the wall (h19k); where a vessel grazes the
// face, its axis outside, the descent runs along cut slabs (h19j). Departure (named): tips tied in
// rank and in their own band (the face tips answered with one true tip, TraceStage) are ordered by
// cluster index, which may differ between a piece and the single run.
//
// Every rank must call answer() or join() exactly once per run (a collective), with or without a
// piece or vessel; a round cap (kDefaultMaximumRounds, a project rule as the SS field's) stops
// every rank in the same round with the same message (thrown).
#pragma once

#include "vtouchPieceLayout.h"
#include "vtouchRankCollectives.h"
#include "vtouchRoundsOutcome.h"

#include <cstdint>
#include <stdexcept>
#include <vector>

namespace vtouch
{
namespace skeleton
{
class SkeletonTracer;
} // namespace skeleton

/// Thrown by answer() and join() on every rank in the same round, with the same message.
class DistributedFaceTipsError : public std::runtime_error
{
public:
  using std::runtime_error::runtime_error;
};

class DistributedFaceTips
{
public:
  /// Per cluster in answer()'s result: not a face tip (the cluster keeps its own band).
  static constexpr std::int64_t kNotAFaceTip = -2;
  /// Per cluster: a face tip that no true tip's trace enters (the single run closes a loop there).
  static constexpr std::int64_t kNoTipBeyond = -1;
  /// A project rule, as DistributedSeedCode's: chains that change owner more often than this are
  /// not a vessel tree's traces.
  static constexpr int kDefaultMaximumRounds = 1000;

  /// `layout`: the pieces, the same on every rank (PieceLayout::check()ed by the caller).
  DistributedFaceTips(RankCollectives& collectives,
    PieceLayout layout,
    int maximumRounds = kDefaultMaximumRounds);

  /// Collective, once: per cluster of `tracer`'s graph (the global-field coder's, after its
  /// clusters and before its traces, on this rank's held box), kNotAFaceTip, kNoTipBeyond, or the
  /// rank key (DistributedTipOrder) of the true tip the single run traces first of those whose
  /// traces enter the piece through that face tip; a true tip (not cut by a shared face) gets its
  /// own rank key (DistributedTipOrder::unplacedRankKey when no rank gathered it).
  std::vector<std::int64_t> answer(const skeleton::SkeletonTracer& tracer);
  /// Collective, once: takes part without clusters (a rank whose coder did not reach answer()).
  void join();

  /// The coder's mask lost its outermost layer on shared faces before coding (the raw seeded
  /// mode, SeededDistributedCoding::Settings::clearOuterLayer): the piece's cut faces are then
  /// those of the evaluable box (PieceLayout::evaluable), one voxel inside the held box's. Off
  /// (the default): the held box's. Call before answer(). Without it a vessel crossing such a
  /// face would end in a cluster one voxel short of the held face: not a face tip, but a true tip
  /// ranked by its own band (the 112^3 raw phantom seeded on 4 ranks traced a junction's other
  /// branch through: Docs/CLIENT-SERVER.md, "The raw seeded mode on 4 ranks: the face tips where
  /// the coded mask ends").
  void setOuterLayerCleared(bool cleared) { this->OuterLayerCleared = cleared; }

  bool joined() const { return this->Joined; }
  /// The rounds' outcome (the same rounds on every rank) and this rank's messages.
  const RoundsOutcome& outcome() const { return this->Outcome; }

private:
  std::vector<std::int64_t> run(const skeleton::SkeletonTracer* tracer);

  RankCollectives& Collectives;
  PieceLayout Layout;
  int MaximumRounds;
  bool Joined = false;
  bool OuterLayerCleared = false;
  RoundsOutcome Outcome;
};

} // namespace vtouch

// Region growing across the pieces of a distributed volume, in rounds (issue 19 item 2: the raw
// seeded mode, one click, on a parallel pvserver). Each rank holds its piece grown by the ghost
// margin and grows a 26-connected region through the voxels a rule accepts, from the seed when it
// holds it and from the voxels the other ranks report; then the ranks exchange the voxels they
// newly joined that they own and another rank can decide (sparse: whole-volume linear indices,
// never a mask), until no rank reports one.
//
// Exact (the project's rule, so that every rank's region is the single run's on the voxels it
// decides): a rank grows only into the voxels it decides exactly (PieceLayout::evaluable: every
// neighbour the rule reads is held), so every voxel it joins is in the single run's region; and a
// step u -> w of any path of the single run's region is taken by the owner of u, or by the owner
// of w once it receives u (u is then in its evaluable box: with a ghost margin of at least 2
// voxels, an owned voxel's neighbours are evaluable). So the rounds end with every rank's region
// equal to the single run's on its evaluable box; a network leaving a piece and coming back is
// found on the way back through the neighbour. The round count is at most the number of times
// the longest path from the seed crosses between owners, plus one.
#pragma once

#include "vtouchCollectiveRounds.h"
#include "vtouchPieceLayout.h"
#include "vtouchRankCollectives.h"
#include "vtouchRoundsOutcome.h"
#include "vtouchSparseVesselMask.h"

#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace vtouch
{

class DistributedRegionGrowth
{
public:
  /// Whether the voxel at this local linear index joins (called only on evaluable voxels).
  using Accept = std::function<bool(std::uint64_t localLinear)>;
  /// Called once for every voxel that joins this rank's region (grown here or received).
  using OnJoin = std::function<void(std::uint64_t localLinear)>;

  /// A project rule: a network that needs more rounds crosses between pieces more than this
  /// many times along one path: not a vessel tree; the growth stops with an error (every rank
  /// at the same round, so none waits for another).
  static constexpr int kDefaultMaximumRounds = 1000;

  explicit DistributedRegionGrowth(PieceLayout layout)
    : Layout(std::move(layout))
  {
    this->Layout.check();
    this->Dims = this->Layout.pieceDims();
    this->Evaluable = this->Layout.evaluable(this->Layout.rank);
    const VoxelBox& held = this->Layout.mine();
    // Local coordinates of the evaluable box.
    for (int a = 0; a < 3; ++a)
    {
      this->LocalEvaluable.lo[a] = this->Evaluable.lo[a] - held.lo[a];
      this->LocalEvaluable.hi[a] = this->Evaluable.hi[a] - held.lo[a];
    }
    for (int r = 0; r < this->Layout.ranks(); ++r)
    {
      if (r != this->Layout.rank)
      {
        this->OthersEvaluable.push_back(this->Layout.evaluable(r));
      }
    }
  }

  struct RoundOutput
  {
    std::vector<std::uint64_t> joined;  ///< local linear indices newly joined
    std::vector<std::int64_t> reported; ///< whole linear indices to report to the others
  };

  /// One round on this rank: sets `seeds` (local linear, not re-tested: decided by their owner
  /// or the seed) in `mask` (this piece's grid, not finalized) and grows from them through
  /// accepted evaluable voxels.
  RoundOutput grow(SparseVesselMask& mask,
    const std::vector<std::uint64_t>& seeds,
    const Accept& accept,
    const OnJoin& onJoin) const
  {
    RoundOutput out;
    std::vector<std::uint64_t> stack;
    for (std::uint64_t s : seeds)
    {
      if (!mask.test(s))
      {
        mask.set(s);
        stack.push_back(s);
        this->joined(s, out, onJoin);
      }
    }
    while (!stack.empty())
    {
      const std::uint64_t lin = stack.back();
      stack.pop_back();
      const auto c = this->local(lin);
      for (std::int64_t dk = -1; dk <= 1; ++dk)
        for (std::int64_t dj = -1; dj <= 1; ++dj)
          for (std::int64_t di = -1; di <= 1; ++di)
          {
            const std::int64_t i = c[0] + di, j = c[1] + dj, k = c[2] + dk;
            if (!this->LocalEvaluable.contains(i, j, k))
            {
              continue;
            }
            const std::uint64_t n = this->linear(i, j, k);
            if (mask.test(n) || !accept(n))
            {
              continue;
            }
            mask.set(n);
            stack.push_back(n);
            this->joined(n, out, onJoin);
          }
    }
    return out;
  }

  /// The received whole-volume indices this rank decides and has not joined yet (local linear).
  std::vector<std::uint64_t> received(const SparseVesselMask& mask,
    const std::vector<std::vector<std::int64_t>>& fromRanks) const
  {
    std::vector<std::uint64_t> seeds;
    for (int r = 0; r < static_cast<int>(fromRanks.size()); ++r)
    {
      if (r == this->Layout.rank)
      {
        continue;
      }
      for (std::int64_t w : fromRanks[static_cast<std::size_t>(r)])
      {
        const auto c = this->Layout.wholeIndex(w);
        if (!this->Evaluable.contains(c))
        {
          continue;
        }
        const auto l = this->Layout.toLocal(c);
        const std::uint64_t lin = this->linear(l[0], l[1], l[2]);
        if (!mask.test(lin))
        {
          seeds.push_back(lin);
        }
      }
    }
    return seeds;
  }

  /// What the rounds did (the same rounds and message on every rank).
  using Outcome = RoundsOutcome;

  /// Collective: the rounds to the end (CollectiveRounds: stop when no rank reports, the cap,
  /// a failure on one rank thrown on all). `seeds` (local linear indices): the seed on the rank
  /// that owns it, empty elsewhere (a rank may start from several). `mask` is this piece's grid
  /// (not finalized). `maximumRounds`: the cap (every rank stops at the same round).
  Outcome run(RankCollectives& collectives,
    SparseVesselMask& mask,
    const std::vector<std::uint64_t>& seeds,
    const Accept& accept,
    const OnJoin& onJoin,
    int maximumRounds = kDefaultMaximumRounds) const
  {
    return roundsOfGrowth().run(
      collectives,
      [&](const CollectiveRounds::Exchange& previous)
      {
        const std::vector<std::uint64_t> next =
          previous.rounds == 0 ? seeds : this->received(mask, previous.indices);
        RoundOutput round = this->grow(mask, next, accept, onJoin);
        return CollectiveRounds::Report{ std::move(round.reported), {} };
      },
      maximumRounds);
  }

  const PieceLayout& layout() const { return this->Layout; }

  /// The growth's loop: indices only, the cap's words (the project rule above).
  static CollectiveRounds roundsOfGrowth()
  {
    return CollectiveRounds({ "the region growth across the pieces",
                              "a network crossing between pieces that often is not a vessel tree",
                              "set the thresholds, or extract on one rank" },
      CollectiveRounds::Payload::Indices);
  }

private:
  std::array<std::int64_t, 3> local(std::uint64_t lin) const
  {
    const auto l = static_cast<std::int64_t>(lin);
    return {
      l % this->Dims[0], (l / this->Dims[0]) % this->Dims[1], l / (this->Dims[0] * this->Dims[1])
    };
  }
  std::uint64_t linear(std::int64_t i, std::int64_t j, std::int64_t k) const
  {
    return static_cast<std::uint64_t>(i + this->Dims[0] * (j + this->Dims[1] * k));
  }
  /// Records a joined voxel; reports it when this rank owns it and another rank decides it.
  void joined(std::uint64_t lin, RoundOutput& out, const OnJoin& onJoin) const
  {
    out.joined.push_back(lin);
    if (onJoin)
    {
      onJoin(lin);
    }
    const auto c = this->Layout.toWhole(this->local(lin));
    if (!this->Layout.owned[static_cast<std::size_t>(this->Layout.rank)].contains(c))
    {
      return;
    }
    for (const VoxelBox& other : this->OthersEvaluable)
    {
      if (other.contains(c))
      {
        out.reported.push_back(this->Layout.wholeLinear(c));
        return;
      }
    }
  }

  PieceLayout Layout;
  std::array<std::int64_t, 3> Dims{ 0, 0, 0 };
  VoxelBox Evaluable;                    ///< whole-volume index
  VoxelBox LocalEvaluable;               ///< this piece's index
  std::vector<VoxelBox> OthersEvaluable; ///< the other ranks' evaluable boxes (whole index)
};

} // namespace vtouch

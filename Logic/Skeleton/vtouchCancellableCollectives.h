// A cancel that reaches every rank at the same collective step (issue 19 item 1, issue 16 item 6
// on a parallel pvserver). Only the first rank of a pvserver hears the client's Cancel (its side
// channel, vtouch::RemoteCancelListener); a rank that stopped alone would leave the others
// waiting in their next exchange for ever. This decorator of the ranks' collectives carries each
// rank's cancel request as one status word after its values in every allGather (the pattern of
// CollectiveRounds' failure word: no extra collective while nobody cancels), so every rank reads
// the same words and every rank throws vtouch::Cancelled from the same call. After that the
// decorator stays cancelled: each later call throws at once on every rank without exchanging
// (every rank took the same branch), so a run that catches the first Cancelled somewhere and goes
// on (a stage's own cancel handling) cannot pair an exchange of one rank with another's.
// gather() is not a cancel point (only its root would learn of a cancel); agree() is one of its
// own (one word per rank), for the places between long local stages.
#pragma once

#include "vtouchRankCollectives.h"

#include <functional>

namespace vtouch
{

class CancellableCollectives : public RankCollectives
{
public:
  /// Whether this rank was asked to cancel (called before each exchange, on this rank's thread).
  using CancelCheck = std::function<bool()>;

  /// `inner` must outlive this object. `cancelRequested` may be empty (this rank never asks).
  CancellableCollectives(RankCollectives& inner, CancelCheck cancelRequested);

  int rank() const override;
  int ranks() const override;
  /// Collective and a cancel point: throws vtouch::Cancelled on every rank when any asked.
  std::vector<std::vector<double>> allGather(const std::vector<double>& mine) override;
  std::vector<std::vector<std::int64_t>> allGather(const std::vector<std::int64_t>& mine) override;
  /// Collective, not a cancel point (throws Cancelled only once the ranks agreed to cancel).
  std::vector<std::vector<std::int64_t>> gather(const std::vector<std::int64_t>& mine,
    int root) override;

  /// Collective: a cancel point that exchanges nothing else (one word per rank).
  void agree();
  /// Whether the ranks agreed to cancel (the same on every rank).
  bool cancelled() const { return this->Cancelled; }

private:
  /// Throws vtouch::Cancelled once the ranks agreed to cancel.
  void throwIfCancelled() const;
  bool asked() const { return this->CancelRequested && this->CancelRequested(); }

  RankCollectives& Inner;
  CancelCheck CancelRequested;
  bool Cancelled = false;
};

} // namespace vtouch

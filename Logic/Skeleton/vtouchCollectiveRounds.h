// The round loop of the distributed stages (issue 19 item 2): DistributedRegionGrowth and
// DistributedSeedCode each run a local step, exchange sparse reports (whole-volume linear
// indices, with one value each for the SS code) with AllGathers, and stop when no rank reports
// one. This class owns that loop, so that every such algorithm shares one agreement on stopping:
//  - settled: every rank sees the same gathered reports, so every rank sees "none reported" in
//    the same exchange and stops there (the exchange that finds none counts as a round);
//  - the cap: every rank counts the same exchanges, so every rank stops at the same round, with
//    the same message;
//  - a failure: a step that throws on one rank would leave the others waiting in the next
//    exchange for ever; instead the rank still makes the exchange with a failure flag (one
//    status word after its indices, so no extra collective while every step succeeds), the
//    ranks exchange the failing rank's text, and every rank throws in the same round: the
//    failing rank its own exception, the others std::runtime_error naming that rank.
// Every rank must call run() with the same description, payload and cap (a collective).
#pragma once

#include "vtouchRankCollectives.h"
#include "vtouchRoundsOutcome.h"

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace vtouch
{

class CollectiveRounds
{
public:
  /// The words of the cap's message: "<subject> did not settle in <cap> rounds (<capReason>):
  /// <capAdvice>". `subject` also names the rounds in a failure's message.
  struct Description
  {
    std::string subject;   ///< e.g. "the region growth across the pieces"
    std::string capReason; ///< why a network that needs more rounds is not a vessel tree
    std::string capAdvice; ///< what the user can do
  };

  /// Whether a report carries one value per index (a second AllGather each round).
  enum class Payload
  {
    Indices,
    IndicesAndValues
  };

  /// What this rank reports in one round.
  struct Report
  {
    std::vector<std::int64_t> indices; ///< whole-volume linear indices
    std::vector<double> values;        ///< one per index with IndicesAndValues, else empty
  };

  /// Every rank's report of the last exchange, indexed by rank.
  struct Exchange
  {
    int rounds = 0; ///< exchanges made so far: 0 before the first (then the lists are empty)
    std::vector<std::vector<std::int64_t>> indices;
    std::vector<std::vector<double>> values; ///< empty lists unless IndicesAndValues
  };

  /// One round's local work on this rank, from the last exchange (its own report included, at
  /// its rank's place; round 1 gets an Exchange with rounds == 0): what this rank reports.
  using Step = std::function<Report(const Exchange& previous)>;

  CollectiveRounds(Description description, Payload payload);

  /// Collective: the rounds to the end. `maximumRounds` (>= 1, the same on every rank): the
  /// exchanges after which the rounds stop unsettled when a rank still reports. Throws
  /// std::invalid_argument (before any exchange) on a cap below 1; rethrows a step's exception
  /// on its rank and throws std::runtime_error on the others, every rank in the same round.
  RoundsOutcome run(RankCollectives& collectives, const Step& step, int maximumRounds) const;

  /// The cap's message for `maximumRounds`.
  std::string capMessage(int maximumRounds) const;

private:
  Description Words;
  Payload Carries;
};

} // namespace vtouch

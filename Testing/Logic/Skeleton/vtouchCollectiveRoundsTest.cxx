// vtouch::CollectiveRounds, the round loop of the distributed stages (issue 19 item 2), with 1-4
// ranks as threads of one process (InProcessWorld, no MPI): one exchange when nobody reports,
// every rank's report reaching every rank's next step, the cap stopping every rank at the same
// round with the same message, and a step failing on one rank thrown on every rank in that
// round (instead of the others waiting in the next exchange).
#include "vtouchCollectiveRounds.h"
#include "vtouchInProcessCollectives.h"

#include <gtest/gtest.h>

#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

namespace vtouch
{
namespace
{
using test::InProcessWorld;

const CollectiveRounds::Description kWords{ "the test's relay across the ranks",
  "a relay that long is a loop",
  "fix the test" };

/// What one rank saw of a run.
struct RankRun
{
  RoundsOutcome outcome;
  int steps = 0;             ///< calls of its step
  std::string error;         ///< what() of what run() threw; empty when it returned
  bool ownException = false; ///< the exception was its step's own (std::domain_error)
  bool runtimeError = false; ///< the exception was a std::runtime_error from the driver
  bool logicError = false;   ///< another std::logic_error (the driver's check of a report)
};

/// Runs rounds of `payload` on every rank of `world` with `step(rank, previous)`; each rank's
/// result.
std::vector<RankRun> runAll(InProcessWorld& world,
  CollectiveRounds::Payload payload,
  const std::function<CollectiveRounds::Report(int, const CollectiveRounds::Exchange&)>& step,
  int maximumRounds)
{
  const CollectiveRounds rounds(kWords, payload);
  std::vector<RankRun> runs(static_cast<std::size_t>(world.ranks()));
  world.run(
    [&](int rank, RankCollectives& collectives)
    {
      RankRun& mine = runs[static_cast<std::size_t>(rank)];
      try
      {
        mine.outcome = rounds.run(
          collectives,
          [&](const CollectiveRounds::Exchange& previous)
          {
            ++mine.steps;
            EXPECT_EQ(previous.rounds, mine.steps - 1) << "rank " << rank;
            EXPECT_EQ(previous.indices.size(), static_cast<std::size_t>(world.ranks()));
            EXPECT_EQ(previous.values.size(), static_cast<std::size_t>(world.ranks()));
            return step(rank, previous);
          },
          maximumRounds);
      }
      catch (const std::domain_error& e)
      {
        mine.error = e.what();
        mine.ownException = true;
      }
      catch (const std::runtime_error& e)
      {
        mine.error = e.what();
        mine.runtimeError = true;
      }
      catch (const std::logic_error& e)
      {
        mine.error = e.what();
        mine.logicError = true;
      }
    });
  return runs;
}

TEST(CollectiveRounds, SettlesInOneExchangeWhenNobodyReports)
{
  for (const CollectiveRounds::Payload payload :
    { CollectiveRounds::Payload::Indices, CollectiveRounds::Payload::IndicesAndValues })
  {
    InProcessWorld world(3);
    const std::vector<RankRun> runs = runAll(
      world,
      payload,
      [](int, const CollectiveRounds::Exchange&) { return CollectiveRounds::Report(); },
      1000);
    for (const RankRun& r : runs)
    {
      EXPECT_TRUE(r.outcome.settled);
      // The exchange that finds no report is the only round: no step after it.
      EXPECT_EQ(r.outcome.rounds, 1);
      EXPECT_EQ(r.steps, 1);
      EXPECT_EQ(r.outcome.reportedVoxels, 0U);
      EXPECT_TRUE(r.outcome.message.empty());
    }
    // One AllGather a round, two when the reports carry values; none for the failure text.
    EXPECT_EQ(world.calls(), payload == CollectiveRounds::Payload::Indices ? 1 : 2);
  }
}

TEST(CollectiveRounds, HandsEveryRanksReportToEveryRanksNextStep)
{
  // A relay: rank 0 reports index 1 with value 0.5; the rank whose number was reported reports
  // the next number (value: half of it), read from the reporter's place in the exchange; index 4
  // is nobody's, so the relay ends: 4 reporting rounds, then the exchange that finds none.
  constexpr int kRanks = 4;
  InProcessWorld world(kRanks);
  const std::vector<RankRun> runs = runAll(
    world,
    CollectiveRounds::Payload::IndicesAndValues,
    [](int rank, const CollectiveRounds::Exchange& previous)
    {
      CollectiveRounds::Report report;
      if (previous.rounds == 0)
      {
        if (rank == 0)
        {
          report = { { 1 }, { 0.5 } };
        }
        return report;
      }
      for (std::size_t from = 0; from < previous.indices.size(); ++from)
      {
        const std::vector<std::int64_t>& got = previous.indices[from];
        if (got.empty())
        {
          continue;
        }
        EXPECT_EQ(got.size(), 1U);
        EXPECT_EQ(got[0], static_cast<std::int64_t>(from) + 1) << "the status word is removed";
        EXPECT_EQ(previous.values[from], std::vector<double>{ 0.5 * static_cast<double>(got[0]) });
        if (got[0] == rank)
        {
          report = { { rank + 1 }, { 0.5 * (rank + 1) } };
        }
      }
      return report;
    },
    1000);
  for (const RankRun& r : runs)
  {
    EXPECT_TRUE(r.outcome.settled) << r.outcome.message;
    EXPECT_EQ(r.outcome.rounds, kRanks + 1);
    EXPECT_EQ(r.steps, kRanks + 1);
    EXPECT_EQ(r.outcome.reportedVoxels, 1U) << "each rank relays once";
  }
}

TEST(CollectiveRounds, CapStopsEveryRankAtTheSameRoundWithTheSameMessage)
{
  // Only rank 1 ever reports; the others must still stop with it, at the cap.
  InProcessWorld world(3);
  const std::vector<RankRun> runs = runAll(
    world,
    CollectiveRounds::Payload::Indices,
    [](int rank, const CollectiveRounds::Exchange&)
    {
      CollectiveRounds::Report report;
      if (rank == 1)
      {
        report.indices = { 7, 8 };
      }
      return report;
    },
    5);
  const std::string expected = "the test's relay across the ranks did not settle in 5 rounds (a "
                               "relay that long is a loop): fix the test";
  EXPECT_EQ(CollectiveRounds(kWords, CollectiveRounds::Payload::Indices).capMessage(5), expected);
  for (std::size_t r = 0; r < runs.size(); ++r)
  {
    EXPECT_FALSE(runs[r].outcome.settled);
    EXPECT_EQ(runs[r].outcome.rounds, 5) << "rank " << r;
    EXPECT_EQ(runs[r].steps, 5) << "rank " << r;
    EXPECT_EQ(runs[r].outcome.message, expected);
    EXPECT_EQ(runs[r].outcome.reportedVoxels, r == 1 ? 10U : 0U);
  }
  EXPECT_EQ(world.calls(), 5);
}

TEST(CollectiveRounds, StepFailingOnOneRankThrowsOnEveryRankInThatRound)
{
  // Rank 2's step throws in round 3 while the others still report: without the shared verdict
  // they would wait for rank 2 in the next exchange (InProcessWorld fails after 60 s).
  InProcessWorld world(3);
  const std::vector<RankRun> runs = runAll(
    world,
    CollectiveRounds::Payload::IndicesAndValues,
    [](int rank, const CollectiveRounds::Exchange& previous)
    {
      if (rank == 2 && previous.rounds == 2)
      {
        throw std::domain_error("rank two's piece is broken");
      }
      return CollectiveRounds::Report{ { rank }, { 1.0 } };
    },
    1000);
  for (std::size_t r = 0; r < runs.size(); ++r)
  {
    EXPECT_EQ(runs[r].steps, 3) << "rank " << r << ": no step after the failing round";
    if (r == 2)
    {
      EXPECT_TRUE(runs[r].ownException) << "the failing rank rethrows its own exception";
      EXPECT_EQ(runs[r].error, "rank two's piece is broken");
    }
    else
    {
      EXPECT_TRUE(runs[r].runtimeError) << "rank " << r;
      EXPECT_EQ(runs[r].error,
        "the test's relay across the ranks: rank 2 failed in round 3: rank two's piece is broken");
    }
  }
  // 3 rounds of two AllGathers, then one for the failing rank's text.
  EXPECT_EQ(world.calls(), 7);
}

TEST(CollectiveRounds, ReportWithValuesNotMatchingItsIndicesFailsOnEveryRank)
{
  // Rank 1 reports two indices with one distance; rank 0 a good report.
  const auto twoIndicesOneValue = [](int rank, const CollectiveRounds::Exchange&)
  {
    return rank == 1 ? CollectiveRounds::Report{ { 3, 4 }, { 1.0 } }
                     : CollectiveRounds::Report{ { 5 }, { 2.0 } };
  };
  InProcessWorld world(2);
  const std::vector<RankRun> runs =
    runAll(world, CollectiveRounds::Payload::IndicesAndValues, twoIndicesOneValue, 1000);
  EXPECT_TRUE(runs[1].logicError) << "the rank whose report is wrong throws the check's error";
  EXPECT_TRUE(runs[0].runtimeError);
  EXPECT_NE(runs[0].error.find("rank 1 failed in round 1: CollectiveRounds (the test's relay "
                               "across the ranks): a report's values do not match its indices"),
    std::string::npos)
    << runs[0].error;
  EXPECT_EQ(runs[0].steps, 1);
}

TEST(CollectiveRounds, RefusesACapBelowOneBeforeAnyExchange)
{
  InProcessWorld world(1);
  const CollectiveRounds rounds(kWords, CollectiveRounds::Payload::Indices);
  world.run(
    [&](int, RankCollectives& collectives)
    {
      EXPECT_THROW(rounds.run(
                     collectives,
                     [](const CollectiveRounds::Exchange&) { return CollectiveRounds::Report(); },
                     0),
        std::invalid_argument);
    });
  EXPECT_EQ(world.calls(), 0);
}

} // namespace
} // namespace vtouch

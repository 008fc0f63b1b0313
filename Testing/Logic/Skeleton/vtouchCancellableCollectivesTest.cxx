// vtouch::CancellableCollectives (issue 19 item 1, issue 16 item 6 on a parallel pvserver), ranks
// as threads of one process (InProcessWorld, no MPI; every wait has its 60 s time-out): a cancel
// asked on the first rank alone, mid-rounds, stops every rank's rounds in the same exchange with
// vtouch::Cancelled (no rank left waiting), the values pass unchanged while nobody asks, and once
// the ranks agreed, every later collective throws at once without exchanging.
#include "vtouchCancellableCollectives.h"
#include "vtouchCollectiveRounds.h"
#include "vtouchInProcessCollectives.h"
#include "vtouchProgress.h"

#include <gtest/gtest.h>

#include <atomic>
#include <future>
#include <string>
#include <thread>
#include <vector>

namespace vtouch
{
namespace
{
using test::InProcessWorld;

const CollectiveRounds::Description kWords{ "the test's endless relay",
  "a relay that long is a loop",
  "fix the test" };

/// What one rank saw of a run of rounds that never settles (every rank reports every round).
struct RankRun
{
  int steps = 0;          ///< calls of its step
  bool cancelled = false; ///< run() threw vtouch::Cancelled
  std::string other;      ///< what() of any other exception
  bool agreed = false;    ///< the decorator's cancelled() after the rounds
};

/// Rounds on every rank of `world`, each rank's collectives decorated with `asks(rank)`;
/// `onStep(rank, round)` runs in each step. The cap is far above any test's cancel round.
std::vector<RankRun> runEndlessRounds(InProcessWorld& world,
  const std::function<bool(int)>& asks,
  const std::function<void(int, int)>& onStep)
{
  const CollectiveRounds rounds(kWords, CollectiveRounds::Payload::IndicesAndValues);
  std::vector<RankRun> runs(static_cast<std::size_t>(world.ranks()));
  world.run(
    [&](int rank, RankCollectives& inner)
    {
      RankRun& mine = runs[static_cast<std::size_t>(rank)];
      CancellableCollectives collectives(inner, [&asks, rank] { return asks(rank); });
      try
      {
        rounds.run(
          collectives,
          [&](const CollectiveRounds::Exchange& previous)
          {
            ++mine.steps;
            onStep(rank, previous.rounds + 1);
            for (const std::vector<std::int64_t>& theirs : previous.indices)
            {
              // The cancel word never reaches the rounds: each rank's report is its own index.
              EXPECT_LE(theirs.size(), 1U);
            }
            return CollectiveRounds::Report{ { rank }, { 0.5 } };
          },
          1000000);
      }
      catch (const Cancelled&)
      {
        mine.cancelled = true;
      }
      catch (const std::exception& e)
      {
        mine.other = e.what();
      }
      mine.agreed = collectives.cancelled();
    });
  return runs;
}

TEST(CancellableCollectives, FirstRanksCancelMidRoundsStopsEveryRankInTheSameRound)
{
  for (const int ranks : { 2, 4 })
  {
    InProcessWorld world(ranks);
    // The first rank's flag, raised in its own step of round 5 (its listener's thread would do
    // it at any time; the next exchange carries it).
    std::atomic<bool> firstRankFlag{ false };
    const std::vector<RankRun> runs = runEndlessRounds(
      world,
      [&](int rank) { return rank == 0 && firstRankFlag.load(); },
      [&](int rank, int round)
      {
        if (rank == 0 && round == 5)
        {
          firstRankFlag = true;
        }
      });
    for (std::size_t r = 0; r < runs.size(); ++r)
    {
      EXPECT_TRUE(runs[r].cancelled) << ranks << " ranks, rank " << r << ": " << runs[r].other;
      EXPECT_TRUE(runs[r].other.empty()) << runs[r].other;
      EXPECT_TRUE(runs[r].agreed) << "rank " << r;
      // Every rank made round 5's step and stopped in its exchange: no rank one step further.
      EXPECT_EQ(runs[r].steps, 5) << ranks << " ranks, rank " << r;
    }
    // Two AllGathers a round (indices and values): round 5's first carried the cancel.
    EXPECT_EQ(world.calls(), 4 * 2 + 1);
  }
}

TEST(CancellableCollectives, CancelFromAnotherThreadStopsEveryRankWithoutAHang)
{
  // The listener's side: a thread of its own raises the first rank's flag once the rounds run;
  // every rank's rounds end with Cancelled (the world's 60 s time-out fails a hang).
  InProcessWorld world(3);
  std::atomic<bool> firstRankFlag{ false };
  std::promise<void> roundsRunning;
  std::atomic<bool> told{ false };
  std::thread listener(
    [&]
    {
      roundsRunning.get_future().wait();
      firstRankFlag = true;
    });
  const std::vector<RankRun> runs = runEndlessRounds(
    world,
    [&](int rank) { return rank == 0 && firstRankFlag.load(); },
    [&](int rank, int round)
    {
      if (rank == 0 && round == 3 && !told.exchange(true))
      {
        roundsRunning.set_value();
      }
    });
  listener.join();
  ASSERT_EQ(runs.size(), 3U);
  for (const RankRun& r : runs)
  {
    EXPECT_TRUE(r.cancelled) << r.other;
    EXPECT_TRUE(r.agreed);
    EXPECT_EQ(r.steps, runs[0].steps) << "every rank stopped in the same round";
    EXPECT_GE(r.steps, 3);
  }
}

TEST(CancellableCollectives, PassesValuesUnchangedAndStaysCancelledOnceAgreed)
{
  InProcessWorld world(2);
  std::vector<std::string> errors(2);
  std::vector<long> callsAfterCancel(2, -1);
  world.run(
    [&](int rank, RankCollectives& inner)
    {
      bool ask = false;
      CancellableCollectives c(inner, [&ask] { return ask; });
      // Nobody asks: the values come back as sent, the lengths differing between ranks.
      const auto d = c.allGather(std::vector<double>(static_cast<std::size_t>(rank + 1), 2.5));
      EXPECT_EQ(d[0], std::vector<double>{ 2.5 });
      EXPECT_EQ(d[1], (std::vector<double>{ 2.5, 2.5 }));
      const auto i = c.allGather(std::vector<std::int64_t>{ rank });
      EXPECT_EQ(i[1], std::vector<std::int64_t>{ 1 });
      EXPECT_EQ(c.gather({ 7 }, 0)[0],
        rank == 0 ? std::vector<std::int64_t>{ 7 } : std::vector<std::int64_t>{});
      c.agree();
      EXPECT_FALSE(c.cancelled());
      // The second rank asks between two long local stages: agree() stops both.
      ask = rank == 1;
      EXPECT_THROW(c.agree(), Cancelled);
      EXPECT_TRUE(c.cancelled());
      // Later calls throw at once on every rank, exchanging nothing (no pairing with a rank
      // elsewhere in its run).
      EXPECT_THROW(c.allGather(std::vector<double>{ 1.0 }), Cancelled);
      EXPECT_THROW(c.gather({ 1 }, 0), Cancelled);
      EXPECT_THROW(c.agree(), Cancelled);
    });
  // 2 allGathers, the gather and 2 agree(); none after the cancel.
  EXPECT_EQ(world.calls(), 5);
}

} // namespace
} // namespace vtouch

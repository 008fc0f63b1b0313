// vtouch::RankCollectives for N ranks as N threads of one process (the distributed stages'
// tests, no MPI): every allGather deposits this rank's values, waits (with a time-out: a rank
// that never comes fails the test instead of hanging it) until every rank has, copies them all
// (gather: only the root copies), and waits again until every rank has copied before a slot may
// be reused.
#pragma once

#include "vtouchRankCollectives.h"

#include <chrono>
#include <condition_variable>
#include <exception>
#include <functional>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <vector>

namespace vtouch::test
{

class InProcessWorld
{
public:
  explicit InProcessWorld(int ranks)
    : Ranks(ranks)
    , Doubles(static_cast<std::size_t>(ranks))
    , Integers(static_cast<std::size_t>(ranks))
  {
  }
  int ranks() const { return this->Ranks; }
  /// Collective calls made by all ranks together (each allGather counts one).
  long calls() const { return this->Calls; }

  /// Runs `body(rank, collectives)` on one thread per rank and joins them; rethrows the first
  /// exception a rank threw.
  void run(const std::function<void(int, RankCollectives&)>& body)
  {
    std::vector<std::thread> threads;
    std::vector<std::exception_ptr> errors(static_cast<std::size_t>(this->Ranks));
    for (int r = 0; r < this->Ranks; ++r)
    {
      threads.emplace_back(
        [this, r, &body, &errors]
        {
          Rank rank(*this, r);
          try
          {
            body(r, rank);
          }
          catch (...)
          {
            errors[static_cast<std::size_t>(r)] = std::current_exception();
          }
        });
    }
    for (std::thread& t : threads)
    {
      t.join();
    }
    for (const std::exception_ptr& e : errors)
    {
      if (e)
      {
        std::rethrow_exception(e);
      }
    }
  }

private:
  class Rank : public RankCollectives
  {
  public:
    Rank(InProcessWorld& world, int rank)
      : World(world)
      , Id(rank)
    {
    }
    int rank() const override { return this->Id; }
    int ranks() const override { return this->World.Ranks; }
    std::vector<std::vector<double>> allGather(const std::vector<double>& mine) override
    {
      return this->World.gather(this->Id, mine, this->World.Doubles);
    }
    std::vector<std::vector<std::int64_t>> allGather(const std::vector<std::int64_t>& mine) override
    {
      return this->World.gather(this->Id, mine, this->World.Integers);
    }
    /// Every rank deposits and waits as allGather; only `root` copies the lists.
    std::vector<std::vector<std::int64_t>> gather(const std::vector<std::int64_t>& mine,
      int root) override
    {
      return this->World.gather(this->Id, mine, this->World.Integers, root);
    }

  private:
    InProcessWorld& World;
    int Id;
  };

  void barrier(std::unique_lock<std::mutex>& lock)
  {
    const long generation = this->Generation;
    if (++this->Arrived == this->Ranks)
    {
      this->Arrived = 0;
      ++this->Generation;
      this->Changed.notify_all();
      return;
    }
    if (!this->Changed.wait_for(
          lock, std::chrono::seconds(60), [&] { return this->Generation != generation; }))
    {
      throw std::runtime_error("InProcessWorld: a rank never reached the collective");
    }
  }

  /// `root` -1: every rank copies the lists (allGather); else only `root` (the others get empty
  /// lists, one per rank).
  template<typename V>
  std::vector<V> gather(int rank, const V& mine, std::vector<V>& slots, int root = -1)
  {
    std::unique_lock<std::mutex> lock(this->Mutex);
    slots[static_cast<std::size_t>(rank)] = mine;
    this->barrier(lock);
    std::vector<V> all = root < 0 || rank == root ? slots : std::vector<V>(slots.size());
    if (rank == 0)
    {
      ++this->Calls;
    }
    this->barrier(lock);
    return all;
  }

  int Ranks;
  std::mutex Mutex;
  std::condition_variable Changed;
  int Arrived = 0;
  long Generation = 0;
  long Calls = 0;
  std::vector<std::vector<double>> Doubles;
  std::vector<std::vector<std::int64_t>> Integers;
};

} // namespace vtouch::test

// The real-time haptic loop: an object that owns its thread and ticks a target on absolute
// deadlines.
#pragma once

#include "vtouchLoopStatistics.h"

#include <atomic>
#include <cstdint>
#include <string>
#include <thread>

namespace vtouch
{

/// What the loop drives. Both functions run on the loop thread and must not allocate, lock, log or
/// throw (they are noexcept: a throw would terminate, which is the only safe thing left).
class HapticTickTarget
{
public:
  virtual ~HapticTickTarget() = default;
  /// One tick at `time_s` (seconds since start) after `dt_s` (measured interval since the last).
  virtual void tick(double time_s, double dt_s) noexcept = 0;
  /// Command zero force now (called before the loop reports a fault).
  virtual void emergencyStop() noexcept = 0;
};

/// Why the loop zeroed the force.
enum class LoopFault : std::uint8_t
{
  None = 0,
  WatchdogOverrun = 1 ///< a tick itself ran longer than LoopOptions::watchdog_s (the haptic
                      ///< thread stopped making progress), or, with faultOnLateWake, a tick
                      ///< started that late after its deadline
};

struct LoopOptions
{
  /// Tick rate, Hz, clamped to [100, 10000]. Default 1000 Hz.
  double rate_Hz = 1000.0;
  /// Sleep (clock_nanosleep, absolute) until this long before the deadline, then spin. Timer
  /// wake-ups on the target VMs are 65-140 us late, so the default 250 us leaves margin. 0 = sleep
  /// only (lower CPU use, more jitter). Capped at half the period so the thread sleeps in every
  /// period (a SCHED_FIFO thread spinning whole periods is throttled by the kernel for 50 ms every
  /// second): 50 us at 10 kHz.
  double spinMargin_us = 250.0;
  /// Ask for SCHED_FIFO at this priority (1..99); 0 = do not ask. Default 80.
  int realtimePriority = 80;
  /// Watchdog on the haptic thread's own progress: a tick that runs longer than this, s, zeroes
  /// the force (target->emergencyStop()) and latches LoopFault::WatchdogOverrun. A wake-up later
  /// than this after its deadline (the whole VM stalled: the device was frozen too) zeroes the
  /// force as well and the target re-engages softly, but it is only counted as a stall (see
  /// LoopStatisticsSummary::stalls) unless faultOnLateWake is set. Default 0.02 s; 0 disables.
  double watchdog_s = 0.02;
  /// Also latch the fault on a late wake-up (the behaviour before stalls were told apart).
  /// Default false.
  bool faultOnLateWake = false;
};

/// Owns its std::thread; stop() (or the destructor) sets an atomic flag and joins.
/// Deadlines are absolute (start + k * period); after a stall missed deadlines are skipped
/// (counted) instead of being caught up in a burst.
class HapticLoop
{
public:
  HapticLoop() = default;
  ~HapticLoop();
  HapticLoop(const HapticLoop&) = delete;
  HapticLoop& operator=(const HapticLoop&) = delete;

  /// Starts ticking `target` (which must outlive the loop or stop()). False if already running.
  bool start(HapticTickTarget& target, const LoopOptions& options = LoopOptions{});
  /// Stops promptly (within one period) and joins. Idempotent.
  void stop();
  bool running() const { return this->Running.load(); }

  LoopStatisticsSummary statistics() const { return this->Stats.summary(); }
  /// True when SCHED_FIFO was granted to the loop thread.
  bool realtimeGranted() const { return this->RealtimeGranted.load(); }
  /// A sentence on the scheduling outcome, for the GUI/log (valid once running() is true).
  std::string schedulerNotice() const;
  LoopFault fault() const { return this->Fault.load(); }
  void clearFault() { this->Fault.store(LoopFault::None); }

private:
  void run(HapticTickTarget* target, LoopOptions options);

  std::thread Thread;
  std::atomic<bool> StopFlag{ false };
  std::atomic<bool> Running{ false };
  std::atomic<bool> RealtimeGranted{ false };
  std::atomic<int> SchedulerError{ 0 };
  std::atomic<bool> SchedulerRequested{ false };
  std::atomic<LoopFault> Fault{ LoopFault::None };
  LoopStatistics Stats;
};

} // namespace vtouch

#include "vtouchHapticLoop.h"

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstring>
#include <ctime>
#include <pthread.h>
#include <sched.h>

namespace vtouch
{

namespace
{
std::int64_t nowNs()
{
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<std::int64_t>(ts.tv_sec) * 1000000000LL + ts.tv_nsec;
}

inline void cpuRelax()
{
#if defined(__x86_64__) || defined(__i386__)
  __builtin_ia32_pause(); // lets the sibling hyperthread (or the hypervisor) breathe while we spin
#endif
}

void sleepUntilNs(std::int64_t t)
{
  timespec ts{};
  ts.tv_sec = static_cast<time_t>(t / 1000000000LL);
  ts.tv_nsec = static_cast<long>(t % 1000000000LL);
  while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr) == EINTR)
  {
  }
}
} // namespace

HapticLoop::~HapticLoop()
{
  this->stop();
}

bool HapticLoop::start(HapticTickTarget& target, const LoopOptions& options)
{
  if (this->Thread.joinable())
  {
    return false;
  }
  LoopOptions o = options;
  o.rate_Hz = std::clamp(std::isfinite(o.rate_Hz) ? o.rate_Hz : 1000.0, 100.0, 10000.0);
  // At most half the period: the thread must sleep in every period. A SCHED_FIFO thread that
  // spins through whole periods (10 kHz with a 250 us margin) exhausts the kernel's real-time
  // budget (sched_rt_runtime_us 950000 of 1000000) and is throttled for 50 ms every second --
  // the "hypervisor stalls" that cost the 10 kHz loop 5 % of its deadlines.
  o.spinMargin_us =
    std::clamp(std::isfinite(o.spinMargin_us) ? o.spinMargin_us : 250.0, 0.0, 0.5e6 / o.rate_Hz);
  this->Stats.reset(o.rate_Hz);
  this->StopFlag.store(false);
  this->Fault.store(LoopFault::None);
  this->RealtimeGranted.store(false);
  this->SchedulerRequested.store(o.realtimePriority > 0);
  this->SchedulerError.store(0);
  this->Running.store(true);
  this->Thread = std::thread(&HapticLoop::run, this, &target, o);
  // Ask for SCHED_FIFO from here so the outcome is known when start() returns.
  if (o.realtimePriority > 0)
  {
    sched_param sp{};
    sp.sched_priority = std::clamp(o.realtimePriority, 1, 99);
    const int rc = pthread_setschedparam(this->Thread.native_handle(), SCHED_FIFO, &sp);
    this->SchedulerError.store(rc);
    this->RealtimeGranted.store(rc == 0);
  }
  return true;
}

void HapticLoop::stop()
{
  this->StopFlag.store(true);
  if (this->Thread.joinable())
  {
    this->Thread.join();
  }
  this->Running.store(false);
}

std::string HapticLoop::schedulerNotice() const
{
  if (!this->SchedulerRequested.load())
  {
    return "haptic loop: SCHED_FIFO not requested; running with the default scheduler";
  }
  if (this->RealtimeGranted.load())
  {
    return "haptic loop: SCHED_FIFO granted";
  }
  return std::string("haptic loop: SCHED_FIFO NOT granted (") +
         std::strerror(this->SchedulerError.load()) +
         "); running with the default scheduler, expect more timing jitter. Grant it with "
         "CAP_SYS_NICE or an rtprio limit in /etc/security/limits.conf.";
}

void HapticLoop::run(HapticTickTarget* target, LoopOptions o)
{
  const std::int64_t period = static_cast<std::int64_t>(std::llround(1e9 / o.rate_Hz));
  const std::int64_t margin = static_cast<std::int64_t>(o.spinMargin_us * 1000.0);
  const std::int64_t watchdog = static_cast<std::int64_t>(o.watchdog_s * 1e9);
  const std::int64_t start = nowNs() + period;
  std::int64_t deadline = start;
  std::int64_t last = start - period;
  while (!this->StopFlag.load(std::memory_order_relaxed))
  {
    if (margin > 0)
    {
      sleepUntilNs(deadline - margin);
      while (nowNs() < deadline)
      {
        // spin the last stretch: timer wake-ups are late by 65-140 us on the target VMs
        cpuRelax();
      }
    }
    else
    {
      sleepUntilNs(deadline);
    }
    const std::int64_t woke = nowNs();
    const std::int64_t late = woke - deadline;
    this->Stats.recordPeriodError(static_cast<double>(late) * 1e-3);
    if (watchdog > 0 && late > watchdog)
    {
      // Woke far too late. On the target VMs this is a whole-host stall (the device was frozen
      // as well), not a fault of this thread: zero the force now and let the target re-engage
      // softly, count it, and keep the fault for a stalled tick (below) unless asked otherwise.
      target->emergencyStop();
      this->Stats.recordStall(static_cast<double>(late) * 1e-9);
      if (o.faultOnLateWake && this->Fault.load() == LoopFault::None)
      {
        this->Fault.store(LoopFault::WatchdogOverrun);
      }
    }
    const double dt =
      std::clamp(static_cast<double>(woke - last) * 1e-9, 0.1 / o.rate_Hz, 5.0 / o.rate_Hz);
    last = woke;
    target->tick(static_cast<double>(woke - start) * 1e-9, dt);
    const std::int64_t done = nowNs();
    this->Stats.recordTickCost(static_cast<double>(done - woke) * 1e-3);
    if (watchdog > 0 && done - woke > watchdog && this->Fault.load() == LoopFault::None)
    {
      target->emergencyStop(); // the tick itself stalled: zero force first ...
      this->Fault.store(LoopFault::WatchdogOverrun); // ... then report
    }
    this->Stats.setElapsed(static_cast<double>(done - start) * 1e-9);
    deadline += period;
    if (done >= deadline)
    {
      // Missed one or more deadlines: skip them rather than bursting to catch up.
      const std::int64_t missed = (done - deadline) / period + 1;
      this->Stats.recordOverrun(static_cast<std::uint64_t>(missed));
      deadline += missed * period;
    }
  }
  target->emergencyStop();
}

} // namespace vtouch

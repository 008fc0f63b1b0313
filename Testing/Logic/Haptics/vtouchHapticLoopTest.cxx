// The real-time loop and the lock-free exchanges around it (run these under TSan too). No
// wall-clock assertions: the tests wait for events with generous guards, never for durations.
#include "vtouchHapticLoop.h"
#include "vtouchHapticSession.h"
#include "vtouchHapticsTestUtilities.h"
#include "vtouchLoopStatistics.h"
#include "vtouchSimulatedDevice.h"

#include <gtest/gtest.h>

#include <atomic>
#include <cerrno>
#include <csignal>
#include <ctime>
#include <pthread.h>
#include <chrono>
#include <thread>

namespace vtouch
{
namespace
{
using namespace vtouch::testing;

/// Waits until `done()` or a generous guard expires (the guard only prevents a hang).
template<typename F>
bool waitFor(F done)
{
  for (int i = 0; i < 20000 && !done(); ++i)
  {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return done();
}

class CountingTarget : public HapticTickTarget
{
public:
  std::atomic<int> ticks{ 0 };
  std::atomic<int> stops{ 0 };
  std::atomic<bool> monotonic{ true };
  double lastTime = -1.0;
  void tick(double time_s, double dt_s) noexcept override
  {
    if (!(time_s > this->lastTime) || !(dt_s > 0.0))
    {
      this->monotonic.store(false);
    }
    this->lastTime = time_s;
    this->ticks.fetch_add(1);
  }
  void emergencyStop() noexcept override { this->stops.fetch_add(1); }
};

TEST(HapticLoop, TicksOnItsOwnThreadAndStopsWhenAsked)
{
  CountingTarget target;
  {
    HapticLoop loop;
    LoopOptions o;
    o.rate_Hz = 1000.0;
    ASSERT_TRUE(loop.start(target, o));
    EXPECT_FALSE(loop.start(target, o)); // already running
    EXPECT_TRUE(loop.running());
    ASSERT_TRUE(waitFor([&] { return target.ticks.load() >= 100; }));
    loop.stop();
    EXPECT_FALSE(loop.running());
    const int after = target.ticks.load();
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
    EXPECT_EQ(target.ticks.load(), after); // really stopped
    const LoopStatisticsSummary s = loop.statistics();
    EXPECT_EQ(s.ticks, static_cast<std::uint64_t>(after));
    EXPECT_GT(s.achievedRate_Hz, 0.0);
    EXPECT_LE(s.periodErrorP50_us, s.periodErrorP99_us);
    EXPECT_LE(s.periodErrorP99_us, s.periodErrorP999_us);
    EXPECT_GT(s.tickCostMax_us, 0.0);
    EXPECT_EQ(target.stops.load(), 1); // zero force when the loop ends
    EXPECT_FALSE(loop.schedulerNotice().empty());
    EXPECT_NE(loop.schedulerNotice().find("SCHED_FIFO"), std::string::npos);
  }
  EXPECT_TRUE(target.monotonic.load());
}

TEST(HapticLoop, DestructorStopsAndJoins)
{
  CountingTarget target;
  {
    HapticLoop loop;
    LoopOptions o;
    o.rate_Hz = 10000.0;
    o.realtimePriority = 0;
    ASSERT_TRUE(loop.start(target, o));
    ASSERT_TRUE(waitFor([&] { return target.ticks.load() >= 50; }));
    EXPECT_NE(loop.schedulerNotice().find("not requested"), std::string::npos);
  } // joins here
  EXPECT_EQ(target.stops.load(), 1);
}

/// Stalls in one tick (test only) so the next one starts late.
class StallingTarget : public HapticTickTarget
{
public:
  HapticLoop* loop = nullptr;
  std::atomic<int> ticks{ 0 };
  std::atomic<bool> zeroedBeforeReport{ false };
  std::atomic<int> stops{ 0 };
  void tick(double, double) noexcept override
  {
    if (this->ticks.fetch_add(1) == 5)
    {
      std::this_thread::sleep_for(std::chrono::milliseconds(60));
    }
  }
  void emergencyStop() noexcept override
  {
    if (this->stops.fetch_add(1) == 0)
    {
      this->zeroedBeforeReport.store(this->loop->fault() == LoopFault::None);
    }
  }
};

TEST(HapticLoop, OverrunZeroesForceBeforeReportingFault)
{
  StallingTarget target;
  HapticLoop loop;
  target.loop = &loop;
  LoopOptions o;
  o.watchdog_s = 0.02;
  o.realtimePriority = 0; // the machine is shared: keep SCHED_FIFO for the test that checks it
  ASSERT_TRUE(loop.start(target, o));
  ASSERT_TRUE(waitFor([&] { return loop.fault() != LoopFault::None; }));
  EXPECT_EQ(loop.fault(), LoopFault::WatchdogOverrun);
  EXPECT_TRUE(target.zeroedBeforeReport.load());
  ASSERT_TRUE(waitFor([&] { return target.ticks.load() > 10; }));
  loop.stop();
  const LoopStatisticsSummary s = loop.statistics();
  EXPECT_GE(s.overruns, 1u);
  EXPECT_GE(s.skippedDeadlines, 10u); // the stalled deadlines were skipped, not caught up
  EXPECT_GE(s.tickCostMax_us, 60000.0);
}

TEST(LoopStatistics, PercentilesComeFromTheHistogram)
{
  LoopStatistics stats;
  stats.reset(1000.0);
  for (int i = 0; i < 1000; ++i)
  {
    stats.recordPeriodError(i < 990 ? 5.5 : 2500.0); // 1 % late by 2.5 ms
    stats.recordTickCost(1.02);
  }
  stats.recordPeriodError(50000.0);
  stats.setElapsed(1.001);
  const LoopStatisticsSummary s = stats.summary();
  EXPECT_EQ(s.ticks, 1001u);
  EXPECT_EQ(s.periodErrorP50_us, 6.0); // upper edge of the 1 us bin
  EXPECT_EQ(s.periodErrorP99_us, 2501.0);
  EXPECT_EQ(s.periodErrorP999_us, 2501.0);
  EXPECT_EQ(s.periodErrorMax_us, 50000.0);
  EXPECT_NEAR(s.tickCostP50_us, 1.05, 1e-9); // 50 ns bins
  EXPECT_NEAR(s.achievedRate_Hz, 1000.0, 1e-9);
}

/// A device whose read() starts failing after some ticks; records what was written.
class FailingDevice : public HapticDevice
{
public:
  int failAfter = 20;
  int reads = 0;
  Vec3 lastWrite{ 99, 99, 99 };
  int writes = 0;
  DeviceCapabilities caps;
  DeviceStatus open() override { return DeviceStatus::Ok; }
  void close() override {}
  bool isOpen() const override { return true; }
  const DeviceCapabilities& capabilities() const override { return this->caps; }
  DeviceStatus read(DeviceState& s) override
  {
    s.pressure = 1.0;
    return ++this->reads > this->failAfter ? DeviceStatus::IoError : DeviceStatus::Ok;
  }
  DeviceStatus write(const Vec3& f) override
  {
    this->lastWrite = f;
    ++this->writes;
    return DeviceStatus::Ok;
  }
  const char* lastError() const override { return "test"; }
};

TEST(HapticSession, DeviceFaultCommandsZeroForceThenLatches)
{
  HapticSession session;
  session.setSkeleton(straightLine({ -20, 0, 0 }, { 20, 0, 20 }, 0.25));
  session.setCamera(topCamera({ 0, 0, 10 }));
  auto device = std::make_shared<FailingDevice>();
  session.setDevice(device);
  session.setParameters(immediateContact(session.parameters())); // starts on the vessel
  for (int k = 0; k < 20; ++k)
  {
    session.tick(k * 0.001, 0.001);
  }
  EXPECT_EQ(session.fault(), SessionFault::None);
  EXPECT_EQ(session.agentState().state, InteractionState::Tracing);
  session.tick(0.020, 0.001); // read fails
  EXPECT_EQ(session.fault(), SessionFault::DeviceError);
  EXPECT_EQ(device->lastWrite.norm(), 0.0);
  device->failAfter = 1 << 30; // the device recovers, the fault stays latched: zero force
  for (int k = 21; k < 40; ++k)
  {
    session.tick(k * 0.001, 0.001);
    EXPECT_EQ(device->lastWrite.norm(), 0.0);
  }
  session.clearFault();
  EXPECT_EQ(session.fault(), SessionFault::None);
}

TEST(HapticSession, RealTimeLoopPublishesStateWhileGuiSwapsViews)
{
  HapticSession session;
  session.setSkeleton(straightLine({ -40, 0, 0 }, { 40, 0, 20 }, 0.25));
  ASSERT_TRUE(session.setCamera(topCamera({ 0, 0, 10 })));
  SimulatedDeviceParameters dp;
  dp.clock = SimulatedDeviceParameters::Clock::RealTime;
  auto device = std::make_shared<SimulatedDevice>(dp);
  HandScript hand = HandScript::circle({ 0, 0 }, 3.0, 2.0, 2000.0);
  auto circle = hand.trajectory;
  hand.trajectory = [circle](double t, HandSample& s)
  {
    circle(t, s);
    s.pressure = 1.0;
  };
  device->setHandScript(hand);
  session.setDevice(device);
  LoopOptions o;
  o.rate_Hz = 2000.0;
  o.realtimePriority = 0;
  o.watchdog_s = 5.0; // this test is about the exchanges; sanitizer builds on a busy host stall
  ASSERT_TRUE(session.start(o)) << session.lastError();
  std::printf("[ loop     ] %s\n", session.schedulerNotice().c_str());
  // The "GUI": swaps camera snapshots, switches laws and reads the agent state concurrently.
  std::uint64_t lastTick = 0;
  int views = 0;
  while (views < 60)
  {
    session.setCamera(topCamera({ 0.1 * (views % 7), 0, 10 }));
    session.setForceLaw(views % 2 ? ForceLawId::ChangeOfHeight : ForceLawId::Ldgf);
    session.setZoom(1.0 + 0.01 * views);
    const AgentState s = session.agentState();
    EXPECT_GE(s.tick, lastTick);
    EXPECT_TRUE(s.force_N.isFinite());
    lastTick = s.tick;
    ++views;
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  ASSERT_TRUE(waitFor([&] { return session.agentState().tick > 200; }));
  session.stop();
  EXPECT_FALSE(session.isRunning());
  EXPECT_EQ(session.fault(), SessionFault::None);
  EXPECT_GT(session.statistics().ticks, 200u);
}

// --- Host stalls (the whole thread stops between ticks) vs. a stalled tick ---------------------

std::atomic<bool> gInTick{ false };
std::atomic<bool> gLandedInTick{ false };

extern "C" void stallThisThread(int)
{
  // Async-signal-safe: emulates a hypervisor stall of the loop thread between two ticks.
  if (gInTick.load())
  {
    gLandedInTick.store(true);
  }
  timespec ts{ 0, 40000000 }; // 40 ms, above the 20 ms watchdog
  while (nanosleep(&ts, &ts) == -1 && errno == EINTR)
  {
  }
}

class ThreadRecordingTarget : public HapticTickTarget
{
public:
  std::atomic<int> ticks{ 0 };
  std::atomic<int> stops{ 0 };
  std::atomic<bool> hasThread{ false };
  pthread_t thread{};
  void tick(double, double) noexcept override
  {
    gInTick.store(true);
    if (!this->hasThread.load())
    {
      this->thread = pthread_self();
      this->hasThread.store(true);
    }
    this->ticks.fetch_add(1);
    gInTick.store(false);
  }
  void emergencyStop() noexcept override { this->stops.fetch_add(1); }
};

/// Runs a loop, stalls its thread once outside a tick, returns false if the stall hit a tick.
bool runWithHostStall(bool faultOnLateWake,
  LoopFault& fault,
  LoopStatisticsSummary& stats,
  int& stops,
  int& ticksAfterStall)
{
  struct sigaction sa
  {
  };
  sa.sa_handler = &stallThisThread;
  sigemptyset(&sa.sa_mask);
  sigaction(SIGUSR1, &sa, nullptr);
  gLandedInTick.store(false);
  ThreadRecordingTarget target;
  HapticLoop loop;
  LoopOptions o;
  o.realtimePriority = 0;
  o.watchdog_s = 0.02;
  o.faultOnLateWake = faultOnLateWake;
  EXPECT_TRUE(loop.start(target, o));
  EXPECT_TRUE(waitFor([&] { return target.ticks.load() >= 20 && target.hasThread.load(); }));
  pthread_kill(target.thread, SIGUSR1);
  EXPECT_TRUE(waitFor([&] { return loop.statistics().stalls >= 1 || gLandedInTick.load(); }));
  const int atStall = target.ticks.load();
  EXPECT_TRUE(waitFor([&] { return target.ticks.load() >= atStall + 20; }));
  ticksAfterStall = target.ticks.load() - atStall;
  fault = loop.fault();
  loop.stop();
  stats = loop.statistics();
  stops = target.stops.load();
  return !gLandedInTick.load();
}

TEST(HapticLoop, HostStallBetweenTicksZeroesForceButDoesNotLatchAFault)
{
  LoopFault fault = LoopFault::None;
  LoopStatisticsSummary s;
  int stops = 0;
  int after = 0;
  bool clean = false;
  for (int attempt = 0; attempt < 5 && !clean; ++attempt)
  {
    clean = runWithHostStall(false, fault, s, stops, after);
  }
  ASSERT_TRUE(clean) << "the injected stall kept landing inside a tick";
  EXPECT_EQ(fault, LoopFault::None); // the thread itself made progress: no latched fault
  EXPECT_GE(s.stalls, 1u);
  EXPECT_GE(s.stallTime_s, 0.02);
  EXPECT_GE(stops, 2);                // zeroed at the stall (re-engage softly), and at stop
  EXPECT_GE(s.skippedDeadlines, 10u); // the stalled deadlines were skipped, not caught up
  EXPECT_EQ(s.deadlines, s.ticks + s.skippedDeadlines);
  EXPECT_GE(after, 20); // and the loop went on ticking
}

TEST(HapticLoop, HostStallLatchesTheFaultWhenAskedTo)
{
  LoopFault fault = LoopFault::None;
  LoopStatisticsSummary s;
  int stops = 0;
  int after = 0;
  bool clean = false;
  for (int attempt = 0; attempt < 5 && !clean; ++attempt)
  {
    clean = runWithHostStall(true, fault, s, stops, after);
  }
  ASSERT_TRUE(clean);
  EXPECT_EQ(fault, LoopFault::WatchdogOverrun);
  EXPECT_GE(stops, 2);
}

TEST(LoopStatistics, StallsAreReportedApartFromTheAchievedRate)
{
  LoopStatistics stats;
  stats.reset(1000.0);
  for (int i = 0; i < 1000; ++i)
  {
    stats.recordPeriodError(5.0);
  }
  stats.recordStall(0.05);
  stats.recordOverrun(49);
  stats.setElapsed(1.05);
  const LoopStatisticsSummary s = stats.summary();
  EXPECT_EQ(s.ticks, 1000u);
  EXPECT_EQ(s.skippedDeadlines, 49u);
  EXPECT_EQ(s.deadlines, 1049u);
  EXPECT_EQ(s.stalls, 1u);
  EXPECT_NEAR(s.stallTime_s, 0.05, 1e-12);
  EXPECT_NEAR(s.achievedRate_Hz, 1000.0 / 1.05, 1e-9);       // all time, stalls included
  EXPECT_NEAR(s.achievedRateOutsideStalls_Hz, 1000.0, 1e-9); // while the host ran the loop
}

} // namespace
} // namespace vtouch

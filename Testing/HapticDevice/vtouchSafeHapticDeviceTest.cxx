#include "vtouchSafeHapticDevice.h"
#include "vtouchSimulatedDevice.h"
#include "vtouchTestDevices.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <memory>
#include <thread>

namespace
{
using vtouch::DeviceState;
using vtouch::DeviceStatus;
using vtouch::SafeHapticDevice;
using vtouch::SafeHapticDeviceParameters;
using vtouch::SafetyFault;
using vtouch::Vec3;
using vtouch::test::RecordingDevice;

/// A clock the test advances by hand; atomic so the watchdog thread may read it too.
struct ManualClock
{
  std::atomic<double> now{ 10.0 };
  std::function<double()> function()
  {
    return [this]() { return this->now.load(); };
  }
};

SafeHapticDeviceParameters offlineParameters(ManualClock& clock)
{
  SafeHapticDeviceParameters p;
  p.watchdogThread = false;
  p.clock_s = clock.function();
  p.filter.engageTicks = 3;
  p.filter.maxSlewRate_N_per_s = 1e6;
  return p;
}

/// Waits (bounded, not a timing assertion) until `predicate` holds.
template<typename Predicate>
bool eventually(Predicate predicate)
{
  for (int i = 0; i < 5000 && !predicate(); ++i)
  {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return predicate();
}

void engage(SafeHapticDevice& device, ManualClock* clock = nullptr)
{
  for (int i = 0; i < 3; ++i)
  {
    device.write(Vec3{});
    if (clock)
    {
      clock->now = clock->now + 0.001;
    }
  }
}

TEST(SafeHapticDevice, ClampsToDeviceMaximumWhenCommandIsLarge)
{
  ManualClock clock;
  auto inner = std::make_unique<RecordingDevice>();
  RecordingDevice* raw = inner.get();
  SafeHapticDevice device(std::move(inner), offlineParameters(clock));
  ASSERT_EQ(device.open(), DeviceStatus::Ok);
  engage(device, &clock);
  EXPECT_EQ(device.write(Vec3{ 10.0, 0.0, 0.0 }), DeviceStatus::Ok);
  EXPECT_NEAR(raw->last().x, 2.0, 1e-12); // RecordingDevice says 2 N max
}

TEST(SafeHapticDevice, SendsZeroAndReturnsInvalidArgumentWhenForceIsNaN)
{
  ManualClock clock;
  auto inner = std::make_unique<RecordingDevice>();
  RecordingDevice* raw = inner.get();
  SafeHapticDevice device(std::move(inner), offlineParameters(clock));
  ASSERT_EQ(device.open(), DeviceStatus::Ok);
  engage(device, &clock);
  device.write(Vec3{ 1.0, 0.0, 0.0 });
  EXPECT_EQ(device.write(Vec3{ std::nan(""), 1.0, 0.0 }), DeviceStatus::InvalidArgument);
  EXPECT_EQ(raw->last().norm(), 0.0);
  EXPECT_EQ(device.nonFiniteCount(), 1u);
  EXPECT_EQ(device.fault(), SafetyFault::None);
  // Forces come back only through the quiet gate.
  device.write(Vec3{ 1.0, 0.0, 0.0 });
  EXPECT_EQ(raw->last().norm(), 0.0);
}

TEST(SafeHapticDevice, LatchesWatchdogAndZeroesForceWhenWritesStop)
{
  ManualClock clock;
  auto inner = std::make_unique<RecordingDevice>();
  RecordingDevice* raw = inner.get();
  SafeHapticDevice device(std::move(inner), offlineParameters(clock));
  ASSERT_EQ(device.open(), DeviceStatus::Ok);
  engage(device, &clock);
  device.write(Vec3{ 1.0, 0.5, 0.0 });
  EXPECT_GT(raw->last().norm(), 0.5);
  clock.now = clock.now + 0.029;
  EXPECT_FALSE(device.pollWatchdog(clock.now));
  EXPECT_EQ(device.fault(), SafetyFault::None);
  clock.now = clock.now + 0.002;
  EXPECT_TRUE(device.pollWatchdog(clock.now));
  EXPECT_EQ(device.fault(), SafetyFault::Watchdog);
  EXPECT_EQ(raw->last().norm(), 0.0);
  EXPECT_EQ(device.watchdogTrips(), 1u);
  // Latched: further writes send zero until cleared.
  EXPECT_EQ(device.write(Vec3{ 1.0, 0.0, 0.0 }), DeviceStatus::Fault);
  EXPECT_EQ(raw->last().norm(), 0.0);
  EXPECT_TRUE(device.clearFault());
  engage(device, &clock);
  EXPECT_EQ(device.write(Vec3{ 1.0, 0.0, 0.0 }), DeviceStatus::Ok);
  EXPECT_NEAR(raw->last().x, 1.0, 1e-12);
}

TEST(SafeHapticDevice, StaysQuietWhenNoWriteEverArrived)
{
  ManualClock clock;
  SafeHapticDevice device(std::make_unique<RecordingDevice>(), offlineParameters(clock));
  ASSERT_EQ(device.open(), DeviceStatus::Ok);
  clock.now = clock.now + 10.0;
  EXPECT_FALSE(device.pollWatchdog(clock.now));
  EXPECT_EQ(device.fault(), SafetyFault::None);
}

TEST(SafeHapticDevice, WatchdogThreadZeroesForceWhenHapticLoopStalls)
{
  auto inner = std::make_unique<RecordingDevice>();
  RecordingDevice* raw = inner.get();
  SafeHapticDeviceParameters p;
  p.filter.engageTicks = 1;
  p.filter.maxSlewRate_N_per_s = 1e6;
  SafeHapticDevice device(std::move(inner), p);
  ASSERT_EQ(device.open(), DeviceStatus::Ok);
  device.write(Vec3{});
  device.write(Vec3{ 1.0, 0.0, 0.0 });
  EXPECT_GT(raw->last().x, 0.0); // slew-limited by the real elapsed time
  // The loop stops writing: the watchdog thread must zero the force on its own.
  ASSERT_TRUE(eventually([&]() { return device.fault() == SafetyFault::Watchdog; }));
  EXPECT_TRUE(eventually([&]() { return raw->last().norm() == 0.0; }));
  device.close();
}

TEST(SafeHapticDevice, KeepsRunningWithoutFaultWhenLoopWritesSteadily)
{
  SafeHapticDeviceParameters p;
  p.watchdogTimeout_s = 5.0; // generous: a loaded CI machine must not trip it
  SafeHapticDevice device(std::make_unique<RecordingDevice>(), p);
  ASSERT_EQ(device.open(), DeviceStatus::Ok);
  std::atomic<bool> stop{ false };
  std::thread loop(
    [&]()
    {
      DeviceState s;
      for (int i = 0; i < 2000 && !stop; ++i)
      {
        device.read(s);
        device.write(Vec3{ 0.001 * (i % 100), 0.0, 0.0 });
        std::this_thread::sleep_for(std::chrono::microseconds(100));
      }
    });
  for (int i = 0; i < 50; ++i)
  {
    EXPECT_EQ(device.fault(), SafetyFault::None);
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  stop = true;
  loop.join();
  EXPECT_EQ(device.fault(), SafetyFault::None);
}

TEST(SafeHapticDevice, LatchesDeviceErrorAndZeroesWhenWriteFails)
{
  ManualClock clock;
  auto inner = std::make_unique<RecordingDevice>();
  RecordingDevice* raw = inner.get();
  SafeHapticDevice device(std::move(inner), offlineParameters(clock));
  ASSERT_EQ(device.open(), DeviceStatus::Ok);
  engage(device, &clock);
  device.write(Vec3{ 1.0, 0.0, 0.0 });
  raw->FailWrites = true;
  EXPECT_EQ(device.write(Vec3{ 1.0, 0.0, 0.0 }), DeviceStatus::IoError);
  EXPECT_EQ(device.fault(), SafetyFault::DeviceError);
  EXPECT_STREQ(device.lastError(), "recording device error");
  raw->FailWrites = false;
  EXPECT_EQ(device.write(Vec3{ 1.0, 0.0, 0.0 }), DeviceStatus::Fault);
  EXPECT_EQ(raw->last().norm(), 0.0);
}

TEST(SafeHapticDevice, ReopensAndReengagesSoftlyWhenDeviceIsReplugged)
{
  ManualClock clock;
  auto inner = std::make_unique<RecordingDevice>();
  RecordingDevice* raw = inner.get();
  SafeHapticDeviceParameters p = offlineParameters(clock);
  SafeHapticDevice device(std::move(inner), p);
  ASSERT_EQ(device.open(), DeviceStatus::Ok);
  engage(device, &clock);
  device.write(Vec3{ 1.0, 0.0, 0.0 });
  raw->Unplugged = true;
  DeviceState s;
  EXPECT_EQ(device.read(s), DeviceStatus::Disconnected);
  EXPECT_EQ(device.fault(), SafetyFault::Disconnected);
  EXPECT_EQ(device.write(Vec3{ 1.0, 0.0, 0.0 }), DeviceStatus::Disconnected);
  EXPECT_FALSE(device.clearFault());
  clock.now = clock.now + 1.0;
  device.pollWatchdog(clock.now); // still unplugged: the reopen fails
  EXPECT_EQ(device.reopenCount(), 0u);
  raw->Unplugged = false;
  clock.now = clock.now + 1.0;
  device.pollWatchdog(clock.now);
  EXPECT_EQ(device.reopenCount(), 1u);
  EXPECT_EQ(device.fault(), SafetyFault::None);
  EXPECT_EQ(raw->Opens.load(), 2);
  device.write(Vec3{ 1.0, 0.0, 0.0 });
  EXPECT_EQ(raw->last().norm(), 0.0); // not engaged yet
  engage(device, &clock);
  device.write(Vec3{ 1.0, 0.0, 0.0 });
  EXPECT_NEAR(raw->last().x, 1.0, 1e-12);
}

TEST(SafeHapticDevice, SendsZeroAndClosesInnerWhenClosed)
{
  ManualClock clock;
  auto inner = std::make_unique<RecordingDevice>();
  RecordingDevice* raw = inner.get();
  SafeHapticDevice device(std::move(inner), offlineParameters(clock));
  ASSERT_EQ(device.open(), DeviceStatus::Ok);
  engage(device, &clock);
  device.write(Vec3{ 1.0, 0.0, 0.0 });
  device.close();
  EXPECT_EQ(raw->last().norm(), 0.0);
  EXPECT_FALSE(raw->isOpen());
  EXPECT_EQ(device.write(Vec3{ 1.0, 0.0, 0.0 }), DeviceStatus::NotOpen);
}

TEST(SafeHapticDevice, DrivesSimulatedDeviceWhenWrapped)
{
  vtouch::SimulatedDeviceParameters sp;
  auto inner = std::make_unique<vtouch::SimulatedDevice>(sp);
  vtouch::SimulatedDevice* sim = inner.get();
  ManualClock clock;
  SafeHapticDevice device(std::move(inner), offlineParameters(clock));
  ASSERT_EQ(device.open(), DeviceStatus::Ok);
  for (int i = 0; i < 100; ++i)
  {
    DeviceState s;
    device.read(s);
    device.write(Vec3{ i < 10 ? 0.0 : 0.5, 0.0, 0.0 });
    sim->advance(0.001);
    clock.now = clock.now + 0.001;
  }
  EXPECT_NEAR(sim->appliedForce_Device_N().x, 0.5, 1e-12);
  EXPECT_GT(sim->energy().deviceWork_J, 0.0);
}

} // namespace

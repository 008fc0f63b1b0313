#include "vtouchSimulatedDevice.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace
{
using vtouch::DeviceState;
using vtouch::DeviceStatus;
using vtouch::HandScript;
using vtouch::SimulatedDevice;
using vtouch::SimulatedDeviceParameters;
using vtouch::Vec2;
using vtouch::Vec3;

SimulatedDeviceParameters freeHandle()
{
  SimulatedDeviceParameters p;
  p.mass_kg = 0.05;
  p.damping_N_s_per_m = 2.0;
  return p;
}

TEST(SimulatedDevice, ReachesTerminalVelocityWhenConstantForceOnDampedMass)
{
  SimulatedDevice device(freeHandle());
  ASSERT_EQ(device.open(), DeviceStatus::Ok);
  ASSERT_EQ(device.write(Vec3{ 1.0, -0.5, 0.0 }), DeviceStatus::Ok);
  // Time constant m/b = 25 ms; after 0.5 s (20 time constants) v = F/b to far below 1e-6.
  for (int i = 0; i < 500; ++i)
  {
    device.advance(0.001);
  }
  const Vec2 v = device.trueVelocity_Device_mm_per_s();
  EXPECT_NEAR(v.x, 1.0 / 2.0 * 1000.0, 1e-3);
  EXPECT_NEAR(v.y, -0.5 / 2.0 * 1000.0, 1e-3);
}

TEST(SimulatedDevice, FollowsExponentialApproachWhenStepForceApplied)
{
  SimulatedDeviceParameters p = freeHandle();
  p.subStep_s = 1e-5;
  SimulatedDevice device(p);
  ASSERT_EQ(device.open(), DeviceStatus::Ok);
  device.write(Vec3{ 1.0, 0.0, 0.0 });
  device.advance(0.025); // one time constant
  const double expected = 500.0 * (1.0 - std::exp(-1.0));
  EXPECT_NEAR(device.trueVelocity_Device_mm_per_s().x, expected, 0.5);
}

TEST(SimulatedDevice, BalancesEnergyWhenHandAndDeviceBothPush)
{
  SimulatedDevice device(freeHandle());
  device.setHandScript(HandScript::circle(Vec2{ 10.0, 0.0 }, 20.0, 1.5, 300.0));
  ASSERT_EQ(device.open(), DeviceStatus::Ok);
  for (int i = 0; i < 2000; ++i)
  {
    DeviceState s;
    device.read(s);
    // A virtual spring to the origin, k = 200 N/m.
    device.write(Vec3{ -0.2 * s.position_Device_mm.x, -0.2 * s.position_Device_mm.y, 0.0 });
    device.advance(0.001);
  }
  const auto& e = device.energy();
  const double balance =
    e.initialKinetic_J + e.deviceWork_J + e.handWork_J - e.dampingLoss_J - e.integrationLoss_J;
  EXPECT_GT(std::abs(e.deviceWork_J), 1e-4);
  EXPECT_GE(e.dampingLoss_J, 0.0);
  EXPECT_GE(e.integrationLoss_J, 0.0);
  EXPECT_NEAR(balance, e.kinetic_J, 1e-9);
}

TEST(SimulatedDevice, DoesNoNetWorkWhenForceIsPerpendicularToMotion)
{
  SimulatedDeviceParameters p = freeHandle();
  SimulatedDevice device(p);
  device.setHandScript(HandScript::moveLinear(Vec2{ 0.0, 0.0 }, Vec2{ 50.0, 0.0 }, 1e4));
  ASSERT_EQ(device.open(), DeviceStatus::Ok);
  for (int i = 0; i < 200; ++i)
  {
    device.advance(0.001);
  }
  const double before = device.energy().deviceWork_J;
  EXPECT_EQ(before, 0.0);
  EXPECT_NEAR(device.truePosition_Device_mm().x, 10.0, 0.5);
}

TEST(SimulatedDevice, SaturatesWhenCommandExceedsMaximumForce)
{
  SimulatedDevice device;
  ASSERT_EQ(device.open(), DeviceStatus::Ok);
  EXPECT_EQ(device.write(Vec3{ 30.0, 40.0, 0.0 }), DeviceStatus::Ok);
  EXPECT_NEAR(device.appliedForce_Device_N().norm(), 3.0, 1e-12);
  EXPECT_NEAR(device.appliedForce_Device_N().x, 1.8, 1e-12);
}

TEST(SimulatedDevice, AppliesZeroForceWhenCommandIsNotFinite)
{
  SimulatedDevice device;
  ASSERT_EQ(device.open(), DeviceStatus::Ok);
  device.write(Vec3{ 1.0, 0.0, 0.0 });
  EXPECT_EQ(device.write(Vec3{ std::nan(""), 0.0, 0.0 }), DeviceStatus::InvalidArgument);
  EXPECT_EQ(device.appliedForce_Device_N().norm(), 0.0);
  EXPECT_STRNE(device.lastError(), "");
}

TEST(SimulatedDevice, IsIdenticalWhenRunTwiceWithSameSeed)
{
  SimulatedDeviceParameters p = freeHandle();
  p.noiseStdDev_mm = 0.05;
  p.noiseSeed = 1234;
  p.quantization_mm = 0.01;
  auto run = [&p]()
  {
    SimulatedDevice device(p);
    device.setHandScript(HandScript::circle(Vec2{}, 15.0, 2.0));
    device.open();
    double checksum = 0.0;
    for (int i = 0; i < 1000; ++i)
    {
      DeviceState s;
      device.read(s);
      device.write(Vec3{ -0.1 * s.position_Device_mm.x, 0.0, 0.0 });
      device.advance(0.001);
      checksum += s.position_Device_mm.x * (i + 1) + s.position_Device_mm.y;
    }
    return checksum;
  };
  EXPECT_EQ(run(), run());
}

TEST(SimulatedDevice, ChangesNoiseWhenSeedChanges)
{
  SimulatedDeviceParameters p;
  p.noiseStdDev_mm = 0.1;
  auto first = [&p](std::uint64_t seed)
  {
    p.noiseSeed = seed;
    SimulatedDevice device(p);
    device.open();
    DeviceState s;
    device.read(s);
    return s.position_Device_mm.x;
  };
  EXPECT_NE(first(1), first(2));
}

TEST(SimulatedDevice, DelaysSamplesWhenLatencyConfigured)
{
  SimulatedDeviceParameters p = freeHandle();
  p.latency_samples = 3;
  SimulatedDevice device(p);
  device.setHandScript(HandScript::moveLinear(Vec2{}, Vec2{ 100.0, 0.0 }, 1e4));
  ASSERT_EQ(device.open(), DeviceStatus::Ok);
  double times[10];
  for (int i = 0; i < 10; ++i)
  {
    DeviceState s;
    device.read(s);
    times[i] = s.timestamp_s;
    device.advance(0.001);
  }
  EXPECT_DOUBLE_EQ(times[9], 0.006);
  EXPECT_DOUBLE_EQ(times[2], 0.0);
}

TEST(SimulatedDevice, QuantizesPositionWhenStepConfigured)
{
  SimulatedDeviceParameters p = freeHandle();
  p.quantization_mm = 0.5;
  p.initialPosition_Device_mm = Vec2{ 1.3, -0.2 };
  SimulatedDevice device(p);
  ASSERT_EQ(device.open(), DeviceStatus::Ok);
  DeviceState s;
  device.read(s);
  EXPECT_DOUBLE_EQ(s.position_Device_mm.x, 1.5);
  EXPECT_DOUBLE_EQ(s.position_Device_mm.y, 0.0);
}

TEST(SimulatedDevice, ReportsScriptedPressureAndButtons)
{
  SimulatedDevice device;
  HandScript script;
  script.trajectory = [](double t, vtouch::HandSample& s)
  {
    s.pressure = t > 0.01 ? 0.75 : 0.0;
    s.buttons = t > 0.01 ? 0x2u : 0x0u;
  };
  device.setHandScript(script);
  ASSERT_EQ(device.open(), DeviceStatus::Ok);
  DeviceState s;
  device.read(s);
  EXPECT_EQ(s.buttons, 0u);
  device.advance(0.02);
  device.read(s);
  EXPECT_EQ(s.buttons, 0x2u);
  EXPECT_DOUBLE_EQ(s.pressure, 0.75);
}

TEST(SimulatedDevice, EstimatesVelocityWhenHandMovesSteadily)
{
  SimulatedDevice device(freeHandle());
  device.setHandScript(HandScript::moveLinear(Vec2{}, Vec2{ 40.0, -20.0 }, 2000.0));
  ASSERT_EQ(device.open(), DeviceStatus::Ok);
  DeviceState s;
  for (int i = 0; i < 500; ++i)
  {
    device.advance(0.001);
    device.read(s);
  }
  EXPECT_NEAR(s.velocity_Device_mm_per_s.x, 40.0, 0.5);
  EXPECT_NEAR(s.velocity_Device_mm_per_s.y, -20.0, 0.5);
}

TEST(SimulatedDevice, HoldsHandleWhenHandHoldsPosition)
{
  SimulatedDevice device(freeHandle());
  device.setHandScript(HandScript::holdAt(Vec2{ 5.0, 5.0 }, 200.0));
  ASSERT_EQ(device.open(), DeviceStatus::Ok);
  device.write(Vec3{ 1.0, 0.0, 0.0 }); // the hand spring balances 1 N at 5 mm
  device.advance(2.0);
  EXPECT_NEAR(device.truePosition_Device_mm().x, 10.0, 1e-3);
  EXPECT_NEAR(device.truePosition_Device_mm().y, 5.0, 1e-3);
}

TEST(SimulatedDevice, RefusesScriptWhenOpen)
{
  SimulatedDevice device;
  ASSERT_EQ(device.open(), DeviceStatus::Ok);
  EXPECT_FALSE(device.setHandScript(HandScript::none()));
  device.close();
  EXPECT_TRUE(device.setHandScript(HandScript::none()));
}

TEST(SimulatedDevice, ReturnsNotOpenWhenClosed)
{
  SimulatedDevice device;
  DeviceState s;
  EXPECT_EQ(device.read(s), DeviceStatus::NotOpen);
  EXPECT_EQ(device.write(Vec3{}), DeviceStatus::NotOpen);
}

TEST(SimulatedDevice, AdvancesWithSteadyClockWhenRealTime)
{
  SimulatedDeviceParameters p;
  p.clock = SimulatedDeviceParameters::Clock::RealTime;
  SimulatedDevice device(p);
  ASSERT_EQ(device.open(), DeviceStatus::Ok);
  DeviceState a, b;
  device.read(a);
  while (device.time_s() < 0.002)
  {
    device.read(b);
  }
  EXPECT_GT(b.timestamp_s, a.timestamp_s);
}

} // namespace

namespace
{
/// A 1 kHz haptic loop rendering a virtual wall (x > 0 is inside) on a simulated stylus held by a
/// hand tracing a circle across the wall. Returns the net work the device did on the handle over
/// whole periods: a passive wall never gives energy back beyond what it took.
double wallWork_J(double wallStiffness_N_per_m, double deviceDamping_N_s_per_m)
{
  vtouch::SimulatedDeviceParameters p;
  p.mass_kg = 0.05;
  p.damping_N_s_per_m = deviceDamping_N_s_per_m;
  p.maxContinuousForce_N = 100.0;
  vtouch::SimulatedDevice device(p);
  device.setHandScript(vtouch::HandScript::circle(Vec2{ 0.0, 0.0 }, 10.0, 1.0, 300.0));
  EXPECT_EQ(device.open(), DeviceStatus::Ok);
  for (int tick = 0; tick < 2000; ++tick) // two hand periods
  {
    DeviceState s;
    device.read(s);
    const double penetration_m = std::max(0.0, s.position_Device_mm.x) * 1e-3;
    device.write(Vec3{ -wallStiffness_N_per_m * penetration_m, 0.0, 0.0 });
    device.advance(0.001);
  }
  return device.energy().deviceWork_J;
}
} // namespace

TEST(SimulatedDevice, AbsorbsEnergyWhenWallSatisfiesColgateCondition)
{
  // b > K T / 2: 2 N s/m > 1000 N/m * 1 ms / 2 = 0.5 N s/m.
  EXPECT_LE(wallWork_J(1000.0, 2.0), 1e-6);
}

TEST(SimulatedDevice, GeneratesEnergyWhenWallIsTooStiffForItsDamping)
{
  // b << K T / 2: the zero-order-held wall pushes out harder than it was pushed in.
  EXPECT_GT(wallWork_J(20000.0, 0.0), 1e-4);
}

// Soft onset of the force (ForceOnsetRamp) and the session start on a slope.
#include "vtouchForceOnsetRamp.h"
#include "vtouchHapticSession.h"
#include "vtouchHapticsTestUtilities.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

namespace vtouch
{
namespace
{
using namespace vtouch::testing;

/// A hand resting (pressure 1) wherever the session put the cursor; records every write.
class RestingDevice : public HapticDevice
{
public:
  std::vector<Vec3> writes;
  DeviceCapabilities caps;
  DeviceStatus open() override { return DeviceStatus::Ok; }
  void close() override {}
  bool isOpen() const override { return true; }
  const DeviceCapabilities& capabilities() const override { return this->caps; }
  DeviceStatus read(DeviceState& s) override
  {
    s.pressure = 1.0;
    return DeviceStatus::Ok;
  }
  DeviceStatus write(const Vec3& f) override
  {
    this->writes.push_back(f);
    return DeviceStatus::Ok;
  }
  const char* lastError() const override { return "test"; }
};

TEST(ForceOnsetRamp, HoldsThenRampsLinearlyToFullScale)
{
  ForceOnsetRampParameters p;
  p.holdTicks = 3;
  p.rampTime_s = 0.01;
  ForceOnsetRamp ramp(p);
  const Vec3 f{ 1.0, 0.5, 0.0 };
  for (int k = 0; k < 3; ++k)
  {
    EXPECT_EQ(ramp.apply(f, 0.001).norm(), 0.0);
  }
  double previous = 0.0;
  for (int k = 1; k <= 10; ++k)
  {
    const double s = ramp.apply(f, 0.001).norm() / f.norm();
    EXPECT_NEAR(s, 0.1 * k, 1e-12);
    EXPECT_GT(s, previous);
    previous = s;
  }
  EXPECT_EQ(ramp.scale(), 1.0);
  EXPECT_NEAR((ramp.apply(f, 0.001) - f).norm(), 0.0, 1e-15);
}

TEST(ForceOnsetRamp, StallEarnsNoMoreThanTheMaximumTickInterval)
{
  ForceOnsetRampParameters p;
  p.holdTicks = 0;
  p.rampTime_s = 0.05;
  p.maxTickInterval_s = 0.002;
  ForceOnsetRamp ramp(p);
  ramp.apply({ 1, 0, 0 }, 0.5); // a 500 ms stall
  EXPECT_NEAR(ramp.scale(), 0.002 / 0.05, 1e-12);
}

TEST(ForceOnsetRamp, QuietStartNeedsNoRampAndNonFinitePassesThrough)
{
  ForceOnsetRampParameters p;
  p.holdTicks = 2;
  ForceOnsetRamp ramp(p);
  ramp.apply({ 0.01, 0, 0 }, 0.001);
  ramp.apply({ 0.0, 0, 0 }, 0.001);
  EXPECT_EQ(ramp.apply({ 0.02, 0, 0 }, 0.001).x, 0.02); // engaged quietly: full scale at once
  ramp.reset();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_TRUE(std::isnan(ramp.apply({ nan, 0, 0 }, 0.001).x)); // the safety filter must see it
}

TEST(HapticSession, StartOnASlopeRampsTheForceInSmoothly)
{
  // The cursor starts at the viewport centre, on an inclined vessel: contact at the first tick,
  // a steady LDGF force from then on. The old quiet gate kept this at zero forever.
  HapticSession session;
  session.setSkeleton(straightLine({ -20, 0, 0 }, { 20, 0, 20 }, 0.25));
  session.setCamera(topCamera({ 0, 0, 10 }));
  auto device = std::make_shared<RestingDevice>();
  session.setDevice(device);
  session.setParameters(immediateContact(session.parameters())); // starts on the vessel
  ForceSafetyParameters safety;
  safety.maxSlewRate_N_per_s = 1e6; // isolate the ramp from the slew limit
  session.setSafetyParameters(safety);
  ForceOnsetRampParameters ramp = session.onsetRampParameters();
  EXPECT_EQ(ramp.rampTime_s, 0.05);
  EXPECT_EQ(ramp.holdTicks, safety.engageTicks);
  const double dt = 0.001;
  for (int k = 0; k < 300; ++k)
  {
    session.tick(k * dt, dt);
  }
  ASSERT_EQ(device->writes.size(), 300u);
  EXPECT_EQ(session.agentState().state, InteractionState::Tracing);
  const double full = device->writes.back().norm();
  ASSERT_GT(full, 0.3);
  for (int k = 0; k < ramp.holdTicks; ++k)
  {
    EXPECT_EQ(device->writes[k].norm(), 0.0) << k; // the hold: downstream quiet gates engage
  }
  // The pipeline's own force interpolation may still be settling at the start: allow its
  // bounded increment on top of the ramp's full * dt / T.
  const double maxIncrement_N = full * dt / ramp.rampTime_s + 0.1 + 1e-9;
  double previous = 0.0;
  int reachedFull = -1;
  for (std::size_t k = 1; k < device->writes.size(); ++k)
  {
    const double f = device->writes[k].norm();
    EXPECT_GE(f, previous - 1e-12) << k; // monotone onset
    EXPECT_LE((device->writes[k] - device->writes[k - 1]).norm(), maxIncrement_N) << k;
    if (reachedFull < 0 && f >= full * (1.0 - 1e-9))
    {
      reachedFull = static_cast<int>(k);
    }
    previous = f;
  }
  ASSERT_GE(reachedFull, 0);
  // Not a step: full force takes the hold plus about the ramp time.
  EXPECT_GE(reachedFull, ramp.holdTicks + 45);
  EXPECT_LE(reachedFull, ramp.holdTicks + 60);
}

TEST(HapticSession, ClearedFaultReengagesThroughTheRamp)
{
  HapticSession session;
  session.setSkeleton(straightLine({ -20, 0, 0 }, { 20, 0, 20 }, 0.25));
  session.setCamera(topCamera({ 0, 0, 10 }));
  auto device = std::make_shared<RestingDevice>();
  session.setDevice(device);
  session.setParameters(immediateContact(session.parameters())); // starts on the vessel
  ForceSafetyParameters safety;
  safety.maxSlewRate_N_per_s = 1e6;
  session.setSafetyParameters(safety);
  int k = 0;
  for (; k < 200; ++k)
  {
    session.tick(k * 0.001, 0.001);
  }
  const double full = device->writes.back().norm();
  ASSERT_GT(full, 0.3);
  session.emergencyStop(); // what the loop does on a stall
  EXPECT_EQ(device->writes.back().norm(), 0.0);
  const std::size_t restart = device->writes.size();
  for (; k < 400; ++k)
  {
    session.tick(k * 0.001, 0.001);
  }
  double previous = 0.0;
  for (std::size_t i = restart; i < device->writes.size(); ++i)
  {
    const double f = device->writes[i].norm();
    EXPECT_GE(f, previous - 1e-12) << i;
    EXPECT_LE(f - previous, full * 0.001 / 0.05 + 0.1 + 1e-9) << i;
    previous = f;
  }
  EXPECT_NEAR(previous, full, 1e-9);
}

} // namespace
} // namespace vtouch

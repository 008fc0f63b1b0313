#include "vtouchReplayDevice.h"
#include "vtouchSimulatedDevice.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <unistd.h>

namespace
{
using vtouch::DeviceState;
using vtouch::DeviceStatus;
using vtouch::ReplayDevice;
using vtouch::ReplayDeviceParameters;
using vtouch::ReplayForce;
using vtouch::ReplaySample;
using vtouch::Vec2;
using vtouch::Vec3;

std::string temporaryPath(const char* name)
{
  return "/tmp/vtouch-" + std::to_string(::getpid()) + "-" + name;
}

TEST(ReplayDevice, InterpolatesPositionWhenReadBetweenSamples)
{
  ReplayDevice device;
  std::string error;
  ASSERT_TRUE(device.parseCsv("time,x,y,pressure,buttons\n"
                              "0.0, 0, 0, 0.0, 0\n"
                              "# a comment\n"
                              "0.1, 10, -20, 1.0, 3\n",
    error))
    << error;
  ASSERT_EQ(device.open(), DeviceStatus::Ok);
  device.advance(0.025);
  DeviceState s;
  ASSERT_EQ(device.read(s), DeviceStatus::Ok);
  EXPECT_NEAR(s.position_Device_mm.x, 2.5, 1e-12);
  EXPECT_NEAR(s.position_Device_mm.y, -5.0, 1e-12);
  EXPECT_NEAR(s.pressure, 0.25, 1e-12);
  EXPECT_EQ(s.buttons, 0u); // buttons hold the previous sample
  device.advance(1.0);
  device.read(s);
  EXPECT_EQ(s.buttons, 3u);
  EXPECT_TRUE(device.finished());
}

TEST(ReplayDevice, RejectsCsvWhenMalformed)
{
  ReplayDevice device;
  std::string error;
  EXPECT_FALSE(device.parseCsv("0,1,2,3\n", error));
  EXPECT_FALSE(device.parseCsv("0,1,2,0,0\n0,1,2,0,0\n", error)); // time does not increase
  EXPECT_FALSE(device.parseCsv("0,1,nan,0,0\n", error));
  EXPECT_FALSE(device.parseCsv("", error));
  EXPECT_FALSE(device.parseCsv("0,1,2,0,-1\n", error));
  EXPECT_EQ(device.open(), DeviceStatus::NotOpen);
}

TEST(ReplayDevice, ReproducesRecordedSessionWhenRoundTrippedThroughCsv)
{
  // Record a simulated exploration, save it, replay it: the same positions at the same times.
  vtouch::SimulatedDevice sim;
  sim.setHandScript(vtouch::HandScript::circle(Vec2{ 5.0, 0.0 }, 20.0, 1.0));
  ASSERT_EQ(sim.open(), DeviceStatus::Ok);
  std::vector<ReplaySample> recorded;
  for (int i = 0; i < 500; ++i)
  {
    DeviceState s;
    sim.read(s);
    recorded.push_back(ReplaySample{ s.timestamp_s,
      Vec2{ s.position_Device_mm.x, s.position_Device_mm.y },
      0.5,
      static_cast<std::uint32_t>(i % 4) });
    sim.advance(0.001);
  }
  const std::string trajectory = temporaryPath("trajectory.csv");
  const std::string forces = temporaryPath("forces.csv");
  ASSERT_TRUE(ReplayDevice::saveCsv(trajectory, recorded));

  ReplayDeviceParameters p;
  p.forceRecordPath = forces;
  ReplayDevice replay(p);
  std::string error;
  ASSERT_TRUE(replay.loadCsv(trajectory, error)) << error;
  ASSERT_EQ(replay.open(), DeviceStatus::Ok);
  for (int i = 0; i < 500; ++i)
  {
    DeviceState s;
    replay.read(s);
    EXPECT_NEAR(
      s.position_Device_mm.x, recorded[static_cast<std::size_t>(i)].position_Device_mm.x, 1e-9);
    EXPECT_NEAR(
      s.position_Device_mm.y, recorded[static_cast<std::size_t>(i)].position_Device_mm.y, 1e-9);
    EXPECT_EQ(s.buttons, recorded[static_cast<std::size_t>(i)].buttons);
    replay.write(Vec3{ 0.001 * i, -0.5, 0.0 });
    replay.advance(0.001);
  }
  ASSERT_EQ(replay.forces().size(), 500u);
  replay.close();

  std::ifstream in(forces);
  std::string header, line;
  std::getline(in, header);
  EXPECT_EQ(header, "time_s,fx_N,fy_N,fz_N");
  int rows = 0;
  double t = 0, fx = 0, fy = 0, fz = 0;
  while (std::getline(in, line))
  {
    ASSERT_EQ(std::sscanf(line.c_str(), "%lf,%lf,%lf,%lf", &t, &fx, &fy, &fz), 4);
    EXPECT_DOUBLE_EQ(fx, 0.001 * rows);
    EXPECT_DOUBLE_EQ(fy, -0.5);
    ++rows;
  }
  EXPECT_EQ(rows, 500);
  std::remove(trajectory.c_str());
  std::remove(forces.c_str());
}

TEST(ReplayDevice, DropsForcesWhenCapacityIsReached)
{
  ReplayDeviceParameters p;
  p.forceCapacity = 3;
  ReplayDevice device(p);
  std::string error;
  ASSERT_TRUE(device.setSamples({ ReplaySample{ 0.0, {}, 0.0, 0 } }, error));
  ASSERT_EQ(device.open(), DeviceStatus::Ok);
  for (int i = 0; i < 5; ++i)
  {
    device.write(Vec3{ 1.0, 0.0, 0.0 });
  }
  EXPECT_EQ(device.forces().size(), 3u);
  EXPECT_EQ(device.droppedForces(), 2u);
  EXPECT_EQ(device.write(Vec3{ std::nan(""), 0.0, 0.0 }), DeviceStatus::InvalidArgument);
}

TEST(ReplayDevice, WrapsAroundWhenLooping)
{
  ReplayDeviceParameters p;
  p.loop = true;
  ReplayDevice device(p);
  std::string error;
  ASSERT_TRUE(device.parseCsv("0,0,0,0,0\n1,10,0,0,0\n", error));
  ASSERT_EQ(device.open(), DeviceStatus::Ok);
  device.advance(1.25);
  DeviceState s;
  device.read(s);
  EXPECT_NEAR(s.position_Device_mm.x, 2.5, 1e-9);
  EXPECT_FALSE(device.finished());
}

} // namespace

#include "vtouchDeviceFactory.h"

#include "vtouchHandTrack.h"
#include "vtouchPointerDevice.h"
#include "vtouchSafeHapticDevice.h"
#include "vtouchSimulatedDevice.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>

namespace
{
using vtouch::BuiltDevice;
using vtouch::DeviceKind;
using vtouch::DeviceRequest;
using vtouch::HandTrack;
using vtouch::Vec2;

TEST(HandTrack, InterpolatesLinearlyAndHoldsOutsideTheSamples)
{
  HandTrack track;
  ASSERT_TRUE(track.add(0.0, Vec2{ 0.0, 0.0 }));
  ASSERT_TRUE(track.add(1.0, Vec2{ 10.0, -4.0 }));
  Vec2 p, v;
  track.at(0.25, p, v);
  EXPECT_DOUBLE_EQ(p.x, 2.5);
  EXPECT_DOUBLE_EQ(p.y, -1.0);
  EXPECT_DOUBLE_EQ(v.x, 10.0);
  EXPECT_DOUBLE_EQ(v.y, -4.0);
  track.at(5.0, p, v);
  EXPECT_DOUBLE_EQ(p.x, 10.0);
  EXPECT_DOUBLE_EQ(v.norm(), 0.0);
  track.at(-1.0, p, v);
  EXPECT_DOUBLE_EQ(p.x, 0.0);
}

TEST(HandTrack, RefusesTimeThatDoesNotIncreaseOrNonFiniteValues)
{
  HandTrack track;
  ASSERT_TRUE(track.add(1.0, Vec2{ 1.0, 1.0 }));
  EXPECT_FALSE(track.add(1.0, Vec2{ 2.0, 2.0 }));
  EXPECT_FALSE(track.add(0.5, Vec2{ 2.0, 2.0 }));
  EXPECT_FALSE(track.add(2.0, Vec2{ std::nan(""), 0.0 }));
  EXPECT_FALSE(track.add(std::numeric_limits<double>::infinity(), Vec2{}));
  EXPECT_EQ(track.size(), 1u);
}

TEST(DeviceFactory, BuildsAnOpenSimulatedHandleThatFollowsTheScriptedHand)
{
  auto hand = std::make_shared<HandTrack>();
  hand->add(0.0, Vec2{ 5.0, 0.0 });
  hand->add(1.0, Vec2{ 15.0, 0.0 });
  DeviceRequest request;
  request.kind = DeviceKind::Simulated;
  request.offline = true;
  request.hand = hand;
  const BuiltDevice built = vtouch::buildDevice(request);
  ASSERT_TRUE(built.device) << built.error;
  ASSERT_NE(built.simulated, nullptr);
  EXPECT_EQ(built.pointer, nullptr);
  EXPECT_TRUE(built.device->isOpen());
  // The handle starts at the hand's first sample and is dragged along by the stiff grip.
  EXPECT_NEAR(built.simulated->truePosition_Device_mm().x, 5.0, 1e-9);
  for (int i = 0; i < 500; ++i)
  {
    built.simulated->advance(0.001);
  }
  EXPECT_NEAR(built.simulated->truePosition_Device_mm().x, 10.0, 0.5);
  built.device->close();
}

TEST(DeviceFactory, ExposesTheMouseInsideTheSafetyWrapper)
{
  DeviceRequest request;
  request.kind = DeviceKind::Pointer;
  const BuiltDevice built = vtouch::buildDevice(request);
  ASSERT_TRUE(built.device) << built.error;
  ASSERT_NE(built.pointer, nullptr);
  EXPECT_EQ(built.simulated, nullptr);
  built.pointer->setPointerPosition(Vec2{ 3.0, 4.0 });
  vtouch::DeviceState state;
  ASSERT_EQ(built.device->read(state), vtouch::DeviceStatus::Ok);
  built.device->close();
}

TEST(DeviceFactory, SaysWhyWhenTheRequestCannotBeBuilt)
{
  DeviceRequest replay;
  replay.kind = DeviceKind::Replay;
  BuiltDevice built = vtouch::buildDevice(replay);
  EXPECT_FALSE(built.device);
  EXPECT_NE(built.error.find("replay"), std::string::npos) << built.error;

  replay.replayFile = "/nonexistent/recording.csv";
  built = vtouch::buildDevice(replay);
  EXPECT_FALSE(built.device);
  EXPECT_FALSE(built.error.empty());

  DeviceRequest hid;
  hid.kind = DeviceKind::Hid;
  built = vtouch::buildDevice(hid);
  EXPECT_FALSE(built.device);
  EXPECT_NE(built.error.find("HID"), std::string::npos) << built.error;

  DeviceRequest absurd;
  absurd.maxForce_N = -1.0;
  built = vtouch::buildDevice(absurd);
  EXPECT_FALSE(built.device);
  EXPECT_NE(built.error.find("force limit"), std::string::npos) << built.error;

  DeviceRequest unknown;
  unknown.kind = static_cast<DeviceKind>(42);
  built = vtouch::buildDevice(unknown);
  EXPECT_FALSE(built.device);
  EXPECT_FALSE(built.error.empty());
}

} // namespace

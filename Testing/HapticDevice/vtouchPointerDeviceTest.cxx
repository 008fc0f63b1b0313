#include "vtouchPointerDevice.h"

#include <gtest/gtest.h>

#include <atomic>
#include <thread>

namespace
{
using vtouch::DeviceState;
using vtouch::DeviceStatus;
using vtouch::PointerDevice;
using vtouch::Vec2;
using vtouch::Vec3;

/// Moves the mouse 10 mm to the right in 1 mm steps under a constant force; returns the cursor x.
double cursorAfterMoveRight(const Vec3& force)
{
  PointerDevice device;
  device.setPointerPosition(Vec2{ 0.0, 0.0 });
  EXPECT_EQ(device.open(), DeviceStatus::Ok);
  DeviceState s;
  for (int i = 1; i <= 10; ++i)
  {
    device.write(force);
    device.setPointerPosition(Vec2{ static_cast<double>(i), 0.0 });
    device.read(s);
  }
  EXPECT_DOUBLE_EQ(device.displayedCursor_Device_mm().x, s.position_Device_mm.x);
  return s.position_Device_mm.x;
}

TEST(PointerDevice, FollowsMouseExactlyWhenNoForce)
{
  EXPECT_DOUBLE_EQ(cursorAfterMoveRight(Vec3{}), 10.0);
}

TEST(PointerDevice, SlowsCursorWhenForceResistsMotion)
{
  // 1 N against the motion: gain 1 - 0.3 = 0.7 (climbing toward the viewer feels heavier).
  EXPECT_NEAR(cursorAfterMoveRight(Vec3{ -1.0, 0.0, 0.0 }), 7.0, 1e-9);
}

TEST(PointerDevice, SpeedsCursorWhenForceAssistsMotion)
{
  EXPECT_NEAR(cursorAfterMoveRight(Vec3{ 1.0, 0.0, 0.0 }), 13.0, 1e-9);
}

TEST(PointerDevice, KeepsGainWhenForceIsPerpendicular)
{
  EXPECT_NEAR(cursorAfterMoveRight(Vec3{ 0.0, 2.0, 0.0 }), 10.0, 1e-9);
}

TEST(PointerDevice, BoundsGainWhenForceIsHuge)
{
  // 3 N cap, gain clamped to 0.2 at worst.
  EXPECT_NEAR(cursorAfterMoveRight(Vec3{ -100.0, 0.0, 0.0 }), 2.0, 1e-9);
}

TEST(PointerDevice, ReportsPressureFromModifierAndWheel)
{
  PointerDevice device;
  ASSERT_EQ(device.open(), DeviceStatus::Ok);
  DeviceState s;
  device.addWheelSteps(3);
  device.read(s);
  EXPECT_NEAR(s.pressure, 0.3, 1e-12);
  device.setModifierPressed(true);
  device.read(s);
  EXPECT_DOUBLE_EQ(s.pressure, 1.0);
  device.setModifierPressed(false);
  device.addWheelSteps(-10);
  device.read(s);
  EXPECT_DOUBLE_EQ(s.pressure, 0.0);
  device.setButtons(0x4);
  device.read(s);
  EXPECT_EQ(s.buttons, 0x4u);
}

TEST(PointerDevice, ExposesForceForDisplayWhenWritten)
{
  PointerDevice device;
  ASSERT_EQ(device.open(), DeviceStatus::Ok);
  device.write(Vec3{ 0.5, -0.25, 0.0 });
  EXPECT_DOUBLE_EQ(device.displayedForce_Device_N().x, 0.5);
  EXPECT_DOUBLE_EQ(device.displayedForce_Device_N().y, -0.25);
  EXPECT_EQ(device.write(Vec3{ std::nan(""), 0.0, 0.0 }), DeviceStatus::InvalidArgument);
  EXPECT_DOUBLE_EQ(device.displayedForce_Device_N().x, 0.0);
}

TEST(PointerDevice, RecentersCursorUnderPointerWhenAsked)
{
  PointerDevice device;
  ASSERT_EQ(device.open(), DeviceStatus::Ok);
  DeviceState s;
  device.write(Vec3{ -1.0, 0.0, 0.0 });
  device.setPointerPosition(Vec2{ 10.0, 0.0 });
  device.read(s);
  EXPECT_NEAR(s.position_Device_mm.x, 7.0, 1e-9);
  device.recenter();
  device.read(s);
  EXPECT_DOUBLE_EQ(s.position_Device_mm.x, 10.0);
}

TEST(PointerDevice, DeliversQuickClickWhenPressAndReleaseFallWithinOneTick)
{
  // Issue 20: an instant click (press and release between two haptic reads) was lost.
  PointerDevice device;
  ASSERT_EQ(device.open(), DeviceStatus::Ok);
  DeviceState s;
  device.read(s);
  EXPECT_EQ(s.buttons, 0u);
  device.setButtons(0x1);
  device.setButtons(0x0);
  EXPECT_EQ(device.pressCount(0), 1u);
  EXPECT_EQ(device.deliveredPressCount(0), 0u);
  device.read(s);
  EXPECT_EQ(s.buttons, 0x1u); // the press, latched
  EXPECT_EQ(device.deliveredPressCount(0), 1u);
  device.read(s);
  EXPECT_EQ(s.buttons, 0x0u); // then the release
  device.read(s);
  EXPECT_EQ(s.buttons, 0x0u);
}

TEST(PointerDevice, ReplaysEveryEdgeWhenSeveralClicksFallWithinOneTick)
{
  PointerDevice device;
  ASSERT_EQ(device.open(), DeviceStatus::Ok);
  DeviceState s;
  // A double click of button 0 and a click of button 2, all between two reads.
  for (int k = 0; k < 2; ++k)
  {
    device.setButtons(0x1);
    device.setButtons(0x0);
  }
  device.setButtons(0x4);
  device.setButtons(0x0);
  EXPECT_EQ(device.pressCount(0), 2u);
  EXPECT_EQ(device.pressCount(2), 1u);
  std::uint32_t seen[5] = {};
  int pressEdges0 = 0;
  std::uint32_t previous = 0;
  for (std::uint32_t& b : seen)
  {
    device.read(s);
    b = s.buttons;
    pressEdges0 += ((b & 0x1u) && !(previous & 0x1u)) ? 1 : 0;
    previous = b;
  }
  EXPECT_EQ(seen[0], 0x5u); // both buttons' first press
  EXPECT_EQ(seen[1], 0x0u); // both releases
  EXPECT_EQ(seen[2], 0x1u); // the second press of button 0
  EXPECT_EQ(seen[3], 0x0u);
  EXPECT_EQ(seen[4], 0x0u);
  EXPECT_EQ(pressEdges0, 2);
  EXPECT_EQ(device.deliveredPressCount(0), 2u);
  EXPECT_EQ(device.pressCount(99), 0u);
}

TEST(PointerDevice, ReportsHeldButtonWhileHeld)
{
  PointerDevice device;
  device.setButtons(0x2); // held before open: reported as held, not as a new click
  ASSERT_EQ(device.open(), DeviceStatus::Ok);
  DeviceState s;
  for (int k = 0; k < 3; ++k)
  {
    device.read(s);
    EXPECT_EQ(s.buttons, 0x2u);
  }
  EXPECT_EQ(device.deliveredPressCount(1), device.pressCount(1));
  device.setButtons(0x0);
  device.read(s);
  EXPECT_EQ(s.buttons, 0x0u);
}

TEST(PointerDevice, StaysConsistentWhenHostFeedsFromAnotherThread)
{
  PointerDevice device;
  ASSERT_EQ(device.open(), DeviceStatus::Ok);
  std::atomic<bool> stop{ false };
  std::thread host(
    [&]()
    {
      for (int i = 0; !stop; ++i)
      {
        // x == y always: a torn read would show x != y.
        device.setPointerPosition(Vec2{ 0.001 * (i % 1000), 0.001 * (i % 1000) });
        device.addWheelSteps(i % 2 ? 1 : -1);
        if (i < 2000)
        {
          device.setButtons(i % 2 ? 0x1u : 0x0u); // 1000 clicks, latched across the reads
        }
      }
    });
  DeviceState s;
  for (int i = 0; i < 20000; ++i)
  {
    device.read(s);
    device.write(Vec3{});
    EXPECT_DOUBLE_EQ(
      device.displayedCursor_Device_mm().x - device.displayedCursor_Device_mm().y, 0.0);
  }
  stop = true;
  host.join();
  // Every latched press is eventually delivered once the host stops clicking.
  for (int i = 0; i < 4000 && device.deliveredPressCount(0) != device.pressCount(0); ++i)
  {
    device.read(s);
  }
  EXPECT_EQ(device.deliveredPressCount(0), device.pressCount(0));
}

TEST(PointerDevice, GivesTheGuiAnUntornCursorAndForceWhileTheTickWrites)
{
  PointerDevice device;
  ASSERT_EQ(device.open(), DeviceStatus::Ok);
  std::atomic<bool> stop{ false };
  std::atomic<int> torn{ 0 };
  // The GUI thread draws the cursor and the force arrow while the haptic thread updates them.
  std::thread gui(
    [&]()
    {
      while (!stop)
      {
        const Vec2 c = device.displayedCursor_Device_mm();
        const Vec3 f = device.displayedForce_Device_N();
        if (c.x != c.y || f.x != f.y)
        {
          ++torn;
        }
      }
    });
  DeviceState s;
  for (int i = 0; i < 20000; ++i)
  {
    const double v = 0.001 * (i % 1000);
    device.setPointerPosition(Vec2{ v, v });
    device.read(s);
    device.write(Vec3{ 1e-3 * v, 1e-3 * v, 0.0 }); // tiny: the gain stays ~1 along x = y
  }
  stop = true;
  gui.join();
  EXPECT_EQ(torn.load(), 0);
}

} // namespace

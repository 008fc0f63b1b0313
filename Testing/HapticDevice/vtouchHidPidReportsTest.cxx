#include "vtouchHidPidReports.h"
#include "vtouchHidTestDescriptors.h"

#include <gtest/gtest.h>

#include <cmath>

namespace
{
using vtouch::HidBlockLoadStatus;
using vtouch::HidPidLayout;
using vtouch::HidPidReports;
using vtouch::HidReportDescriptor;
using vtouch::test::hexBytes;

struct Device
{
  explicit Device(const char* hex)
  {
    const auto bytes = hexBytes(hex);
    EXPECT_TRUE(descriptor.parse(bytes.data(), bytes.size()));
    layout = HidPidLayout::find(descriptor);
  }
  HidReportDescriptor descriptor;
  HidPidLayout layout;
};

TEST(HidPidReports, MapsAnglesOntoOneTurnWhenRangeIs8Bit)
{
  Device d(vtouch::test::kShieldPidSegmentGamepad); // direction 0..255
  HidPidReports r(d.descriptor, d.layout);
  EXPECT_EQ(r.direction(0.0), 0);
  EXPECT_EQ(r.direction(90.0), 64);
  EXPECT_EQ(r.direction(180.0), 128);
  EXPECT_EQ(r.direction(-90.0), 192);
  EXPECT_EQ(r.direction(359.9), 0); // wraps instead of overflowing to 256
  EXPECT_EQ(r.direction(720.0 + 45.0), 32);
}

TEST(HidPidReports, MapsAnglesOntoHundredthsWhenRangeIs0To36000)
{
  Device d(vtouch::test::kOpenFfboard2Axis);
  HidPidReports r(d.descriptor, d.layout);
  EXPECT_EQ(r.direction(90.0), 9000);
  EXPECT_EQ(r.direction(270.0), 27000);
  EXPECT_EQ(r.direction(360.0), 0);
}

TEST(HidPidReports, ScalesAndClampsMagnitudeToLogicalRange)
{
  Device d(vtouch::test::kShieldPidSegmentGamepad); // -255..255
  HidPidReports r(d.descriptor, d.layout);
  EXPECT_TRUE(r.signedMagnitude());
  EXPECT_EQ(r.magnitude(1.0), 255);
  EXPECT_EQ(r.magnitude(-1.0), -255);
  EXPECT_EQ(r.magnitude(0.5), 128);
  EXPECT_EQ(r.magnitude(7.0), 255);
  EXPECT_EQ(r.magnitude(std::nan("")), 0);
}

TEST(HidPidReports, UsesAllOnesForInfiniteDurationUnlessQuirkSaysZero)
{
  Device d(vtouch::test::kOpenFfboard2Axis);
  HidPidReports r(d.descriptor, d.layout);
  EXPECT_EQ(r.infiniteDuration(-1), 0xFFFF);
  EXPECT_EQ(r.infiniteDuration(0), 0);
}

TEST(HidPidReports, ReadsBlockLoadAnswersWhenStatusVaries)
{
  Device d(vtouch::test::kOpenFfboard2Axis); // Block Load: [0x12, block, status, pool lo, pool hi]
  HidPidReports r(d.descriptor, d.layout);
  std::int64_t block = 0;
  const std::uint8_t success[] = { 0x12, 0x03, 0x01, 0xFF, 0xFF };
  EXPECT_EQ(r.parseBlockLoad(success, sizeof(success), block), HidBlockLoadStatus::Success);
  EXPECT_EQ(block, 3);
  const std::uint8_t full[] = { 0x12, 0x00, 0x02, 0x00, 0x00 };
  EXPECT_EQ(r.parseBlockLoad(full, sizeof(full), block), HidBlockLoadStatus::Full);
  const std::uint8_t error[] = { 0x12, 0x00, 0x03, 0x00, 0x00 };
  EXPECT_EQ(r.parseBlockLoad(error, sizeof(error), block), HidBlockLoadStatus::Error);
  const std::uint8_t pending[] = { 0x12, 0x00, 0x00, 0x00, 0x00 };
  EXPECT_EQ(r.parseBlockLoad(pending, sizeof(pending), block), HidBlockLoadStatus::Pending);
  const std::uint8_t truncated[] = { 0x12 };
  EXPECT_EQ(r.parseBlockLoad(truncated, sizeof(truncated), block), HidBlockLoadStatus::Unreadable);
  EXPECT_EQ(r.parseBlockLoad(nullptr, 5, block), HidBlockLoadStatus::Unreadable);
}

TEST(HidPidReports, BuildsNothingWhenDeviceHasNoPidReports)
{
  Device d(vtouch::test::kHidSpecMouse);
  HidPidReports r(d.descriptor, d.layout);
  EXPECT_TRUE(r.constantForce(1, 100).bytes.empty());
  EXPECT_TRUE(r.setEffect(1, vtouch::PidEffectMode::Polar, 0, -1).bytes.empty());
  EXPECT_EQ(r.magnitude(0.5), 0);
}

} // namespace

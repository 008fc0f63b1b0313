#include "vtouchHidPidLayout.h"
#include "vtouchHidReportDescriptor.h"
#include "vtouchHidTestDescriptors.h"

#include <gtest/gtest.h>

#include <random>

namespace
{
using vtouch::HidField;
using vtouch::HidPidLayout;
using vtouch::HidReportDescriptor;
using vtouch::HidReportType;
using vtouch::test::hexBytes;
namespace pid = vtouch::pid;

HidReportDescriptor parsed(const char* hex)
{
  HidReportDescriptor d;
  const auto bytes = hexBytes(hex);
  EXPECT_TRUE(d.parse(bytes.data(), bytes.size())) << d.error() << " at " << d.errorOffset();
  return d;
}

TEST(HidReportDescriptor, ParsesOpenFfboardWhenDescriptorIsComplete)
{
  const HidReportDescriptor d = parsed(vtouch::test::kOpenFfboard2Axis);
  EXPECT_TRUE(d.usesReportIds());
  EXPECT_EQ(d.reportBytes(HidReportType::Input, 1), 25u);
  EXPECT_EQ(d.reportBytes(HidReportType::Output, 1), 22u); // Set Effect
  EXPECT_EQ(d.reportBytes(HidReportType::Output, 5), 4u);  // Set Constant Force
  EXPECT_EQ(d.reportBytes(HidReportType::Output, 0x0C), 2u);
  EXPECT_EQ(d.reportBytes(HidReportType::Feature, 0x12), 5u);
  EXPECT_EQ(d.reportBytes(HidReportType::Feature, 0x13), 5u);
  EXPECT_EQ(d.reportBytes(HidReportType::Output, 0xA1), 1u + 1 + 2 + 1 + 4 + 8 + 8);
  EXPECT_EQ(d.reportBytes(HidReportType::Output, 0x42), 0u);
}

TEST(HidReportDescriptor, ReadsSignedAndUnsignedRangesWhenItemSizesDiffer)
{
  const HidReportDescriptor d = parsed(vtouch::test::kOpenFfboard2Axis);
  const HidPidLayout l = HidPidLayout::find(d);
  const HidField& magnitude = d.fields()[static_cast<std::size_t>(l.cfMagnitude.field)];
  EXPECT_EQ(magnitude.logicalMinimum, -32768);
  EXPECT_EQ(magnitude.logicalMaximum, 32767);
  const HidField& direction = d.fields()[static_cast<std::size_t>(l.seDirection0.field)];
  EXPECT_EQ(direction.logicalMinimum, 0);
  EXPECT_EQ(direction.logicalMaximum, 36000);
  const HidField& x = d.fields()[static_cast<std::size_t>(l.x.field)];
  EXPECT_EQ(x.logicalMinimum, -32767);
  EXPECT_EQ(x.bitOffset, 64u);
  EXPECT_EQ(x.reportSize, 16u);
}

TEST(HidPidLayout, FindsEveryReportByUsageWhenDeviceIsOpenFfboard)
{
  const HidReportDescriptor d = parsed(vtouch::test::kOpenFfboard2Axis);
  const HidPidLayout l = HidPidLayout::find(d);
  ASSERT_TRUE(l.hasConstantForce());
  ASSERT_TRUE(l.hasPosition());
  EXPECT_EQ(l.input.reportId, 1);
  EXPECT_EQ(l.buttons.size(), 32u);
  EXPECT_EQ(l.setEffect.reportId, 1);
  EXPECT_EQ(l.setConstantForce.reportId, 5);
  EXPECT_EQ(l.effectOperation.reportId, 0x0A);
  EXPECT_EQ(l.deviceControl.reportId, 0x0C);
  EXPECT_EQ(l.deviceGain.reportId, 0x0D);
  EXPECT_EQ(l.blockFree.reportId, 0x0B);
  EXPECT_EQ(l.createNewEffect.reportId, 0x11);
  EXPECT_EQ(l.blockLoad.reportId, 0x12);
  EXPECT_EQ(l.pool.reportId, 0x13);
  EXPECT_TRUE(l.seAxisX.valid());
  EXPECT_TRUE(l.seAxisY.valid());
  EXPECT_TRUE(l.seDirection1.valid());
  EXPECT_TRUE(l.seStartDelay.valid());
  // Device Control is a bit field here: each control is one bit set to 1.
  EXPECT_EQ(l.dcEnableActuators.element, 0u);
  EXPECT_EQ(l.dcEnableActuators.value, 1);
  EXPECT_EQ(l.dcStopAllEffects.element, 2u);
  EXPECT_EQ(l.eoStart.value, 1);
  EXPECT_EQ(l.eoStop.value, 3);
  EXPECT_EQ(l.blSuccess.value, 1);
  EXPECT_EQ(l.blFull.value, 2);
  EXPECT_EQ(l.cneConstantForce.value, 1);
}

TEST(HidPidLayout, FindsEveryReportByUsageWhenDeviceIsShieldLayout)
{
  const HidReportDescriptor d = parsed(vtouch::test::kShieldPidSegmentGamepad);
  const HidPidLayout l = HidPidLayout::find(d);
  ASSERT_TRUE(l.hasConstantForce());
  ASSERT_TRUE(l.hasPosition());
  EXPECT_EQ(l.setEffect.reportId, 0x21);
  EXPECT_EQ(l.setEffect.bytes, 16u);
  EXPECT_EQ(l.setConstantForce.reportId, 5);
  EXPECT_EQ(l.blockLoad.reportId, 0x20);
  EXPECT_EQ(l.createNewEffect.reportId, 9);
  EXPECT_EQ(l.pool.reportId, 3);
  EXPECT_EQ(l.deviceControl.reportId, 0x0C);
  // Device Control is a selector array here: the value names the control.
  EXPECT_EQ(l.dcEnableActuators.element, 0u);
  EXPECT_EQ(l.dcEnableActuators.value, 1);
  EXPECT_EQ(l.dcDisableActuators.value, 2);
  EXPECT_EQ(l.dcStopAllEffects.value, 3);
  EXPECT_EQ(l.buttons.size(), 8u);
  const HidField& magnitude = d.fields()[static_cast<std::size_t>(l.cfMagnitude.field)];
  EXPECT_EQ(magnitude.logicalMinimum, -255);
  EXPECT_EQ(magnitude.logicalMaximum, 255);
  // The X/Y of Download Force Sample (output 8) must not be taken for the Axes Enable bits.
  const HidField& axisX = d.fields()[static_cast<std::size_t>(l.seAxisX.field)];
  EXPECT_EQ(axisX.reportId, 0x21);
}

TEST(HidPidLayout, FindsPositionButNoForceWhenDeviceIsPlainMouse)
{
  const HidReportDescriptor d = parsed(vtouch::test::kHidSpecMouse);
  EXPECT_FALSE(d.usesReportIds());
  EXPECT_EQ(d.reportBytes(HidReportType::Input, 0), 3u);
  const HidPidLayout l = HidPidLayout::find(d);
  EXPECT_TRUE(l.hasPosition());
  EXPECT_FALSE(l.hasConstantForce());
  EXPECT_FALSE(l.hasAnyPidReport());
  EXPECT_TRUE(d.fields()[static_cast<std::size_t>(l.x.field)].isRelative());
  EXPECT_EQ(l.buttons.size(), 3u);
}

TEST(HidReportDescriptor, RejectsDescriptorWhenTruncatedAnywhere)
{
  const auto bytes = hexBytes(vtouch::test::kShieldPidSegmentGamepad);
  int rejected = 0;
  for (std::size_t n = 1; n < bytes.size(); ++n)
  {
    HidReportDescriptor d;
    if (!d.parse(bytes.data(), n))
    {
      ++rejected;
      EXPECT_STRNE(d.error(), "");
      EXPECT_TRUE(d.fields().empty());
    }
  }
  // Every cut inside the enclosing collection leaves it unbalanced or an item short.
  EXPECT_EQ(rejected, static_cast<int>(bytes.size()) - 1);
}

TEST(HidReportDescriptor, RejectsMalformedItemsWithReason)
{
  struct Case
  {
    const char* hex;
    const char* reason;
  };
  const Case cases[] = {
    { "C0", "End Collection without Collection" },
    { "A1 01 09 30", "unbalanced collections at end of descriptor" },
    { "85 00", "invalid report ID" },
    { "B4", "Pop without Push" },
    { "A4 A4 A4 A4 A4 A4 A4 A4 A4", "Push stack overflow" },
    { "26 FF", "truncated item" },
    { "FE 05 00 01", "truncated long item" },
    { "75 08 96 00 40 81 02", "report size or count out of range" },
    { "05 01", "descriptor declares no report field" },
    { "F0", "unknown main item" },
  };
  for (const Case& c : cases)
  {
    HidReportDescriptor d;
    const auto bytes = hexBytes(c.hex);
    EXPECT_FALSE(d.parse(bytes.data(), bytes.size())) << c.hex;
    EXPECT_STREQ(d.error(), c.reason) << c.hex;
  }
  HidReportDescriptor d;
  EXPECT_FALSE(d.parse(nullptr, 0));
}

TEST(HidReportDescriptor, SkipsLongItemsAndHonoursPushPop)
{
  // Long item, then Push / change size / Pop around two inputs.
  HidReportDescriptor d;
  const auto bytes =
    hexBytes("FE 02 10 AA BB 05 01 09 30 75 08 95 01 A4 75 10 B4 81 02 09 31 81 02");
  ASSERT_TRUE(d.parse(bytes.data(), bytes.size())) << d.error();
  ASSERT_EQ(d.fields().size(), 2u);
  EXPECT_EQ(d.fields()[0].reportSize, 8u);
  EXPECT_EQ(d.fields()[1].bitOffset, 8u);
}

TEST(HidReportDescriptor, ExpandsUsageRangesWhenArrayFieldUsesMinimumMaximum)
{
  HidReportDescriptor d;
  // Keyboard-like array: usages 0..0x65 of page 7, six 8-bit slots.
  const auto bytes = hexBytes("05 07 19 00 29 65 15 00 25 65 75 08 95 06 81 00");
  ASSERT_TRUE(d.parse(bytes.data(), bytes.size()));
  const HidField& f = d.fields()[0];
  EXPECT_EQ(d.usageCount(f), 0x66u);
  EXPECT_EQ(d.usageAt(f, 4), vtouch::hidUsage(7, 4));
  EXPECT_EQ(d.usageAt(f, 0x66), 0u);
  EXPECT_EQ(d.indexOfUsage(f, vtouch::hidUsage(7, 0x10)), 0x10);
}

TEST(HidField, RoundTripsValuesWhenElementsStraddleBytes)
{
  HidField f;
  f.bitOffset = 3;
  f.reportSize = 10;
  f.reportCount = 3;
  f.logicalMinimum = -512;
  f.logicalMaximum = 511;
  std::uint8_t payload[5] = {};
  EXPECT_TRUE(f.write(payload, sizeof(payload), 0, -300));
  EXPECT_TRUE(f.write(payload, sizeof(payload), 1, 511));
  EXPECT_TRUE(f.write(payload, sizeof(payload), 2, -1));
  std::int64_t v = 0;
  EXPECT_TRUE(f.read(payload, sizeof(payload), 0, v));
  EXPECT_EQ(v, -300);
  EXPECT_TRUE(f.read(payload, sizeof(payload), 1, v));
  EXPECT_EQ(v, 511);
  EXPECT_TRUE(f.read(payload, sizeof(payload), 2, v));
  EXPECT_EQ(v, -1);
  EXPECT_FALSE(f.read(payload, 3, 2, v)); // element 2 ends at bit 33: outside 3 bytes
  EXPECT_FALSE(f.write(payload, sizeof(payload), 3, 0));
}

TEST(HidReportDescriptor, NeverCrashesWhenBytesAreRandom)
{
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> byte(0, 255);
  const auto seed = hexBytes(vtouch::test::kOpenFfboard2Axis);
  for (int trial = 0; trial < 2000; ++trial)
  {
    std::vector<std::uint8_t> bytes = seed;
    for (int k = 0; k < 4; ++k)
    {
      bytes[static_cast<std::size_t>(rng() % bytes.size())] = static_cast<std::uint8_t>(byte(rng));
    }
    HidReportDescriptor d;
    if (d.parse(bytes.data(), bytes.size()))
    {
      const HidPidLayout l = HidPidLayout::find(d);
      (void)l;
    }
  }
  SUCCEED();
}

} // namespace

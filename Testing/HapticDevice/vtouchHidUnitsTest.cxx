// Position resolution of HID devices from the report descriptor's physical units (HID 1.11,
// 6.2.2.7), and its fallback: one count of the calibrated frame. It sets z_max of the
// change-of-height estimate (Hayward & Yi, Appendix A).
#include "vtouchFakeHidTransport.h"
#include "vtouchHidPidDevice.h"
#include "vtouchHidPidLayout.h"
#include "vtouchHidTestDescriptors.h"
#include "vtouchHidUnits.h"

#include <gtest/gtest.h>

#include <memory>

namespace
{
using vtouch::DeviceCalibration;
using vtouch::DeviceState;
using vtouch::DeviceStatus;
using vtouch::FakeHidDevice;
using vtouch::FakeHidTransport;
using vtouch::HidField;
using vtouch::HidPidDevice;
using vtouch::HidPidLayout;
using vtouch::HidReportDescriptor;
using vtouch::HidResolutionSource;
using vtouch::test::hexBytes;
using Bytes = std::vector<std::uint8_t>;

constexpr double kInch_mm = 25.4;

struct Axes
{
  HidField x, y;
};

Axes axesOf(const char* descriptorHex)
{
  const Bytes bytes = hexBytes(descriptorHex);
  HidReportDescriptor d;
  EXPECT_TRUE(d.parse(bytes.data(), bytes.size())) << d.error();
  const HidPidLayout layout = HidPidLayout::find(d);
  EXPECT_TRUE(layout.hasPosition());
  Axes axes;
  if (layout.hasPosition())
  {
    axes.x = d.fields()[static_cast<std::size_t>(layout.x.field)];
    axes.y = d.fields()[static_cast<std::size_t>(layout.y.field)];
  }
  return axes;
}

FakeHidDevice device(const char* path, std::uint16_t vendor, const char* descriptorHex)
{
  FakeHidDevice d;
  d.info.path = path;
  d.info.vendorId = vendor;
  d.info.productId = 0x0001;
  d.info.product = path;
  d.descriptor = hexBytes(descriptorHex);
  return d;
}

/// A length field: `unit` and `exponent` over physical 0..physMax, logical 0..logMax.
HidField lengthField(std::uint32_t unit, int exponent, std::int64_t physMax, std::int64_t logMax)
{
  HidField f;
  f.unit = unit;
  f.unitExponent = exponent;
  f.physicalMaximum = physMax;
  f.logicalMaximum = logMax;
  return f;
}
} // namespace

TEST(HidUnits, PenDigitizerResolutionIsPhysicalRangeOverLogicalRange)
{
  const Axes pen = axesOf(vtouch::test::kMicrosoftSamplePen);
  EXPECT_EQ(pen.x.unit, 0x13u);
  EXPECT_EQ(pen.x.unitExponent, -3);
  EXPECT_NEAR(vtouch::hidLengthPerCount_mm(pen.x), 8.250 * kInch_mm / 21240.0, 1e-12);
  EXPECT_NEAR(vtouch::hidLengthPerCount_mm(pen.y), 6.188 * kInch_mm / 15980.0, 1e-12);
}

TEST(HidUnits, ConvertsSiCentimetresAndSignedPhysicalRanges)
{
  // SI Linear (cm), exponent -2: physical 0..1000 = 10 cm over 4000 counts = 0.025 mm.
  EXPECT_NEAR(vtouch::hidLengthPerCount_mm(lengthField(0x11, -2, 1000, 4000)), 0.025, 1e-12);
  // A centred axis: physical -500..500, logical -2000..2000, same resolution.
  HidField centred = lengthField(0x11, -2, 500, 2000);
  centred.physicalMinimum = -500;
  centred.logicalMinimum = -2000;
  EXPECT_NEAR(vtouch::hidLengthPerCount_mm(centred), 0.025, 1e-12);
}

TEST(HidUnits, GivesNoPhysicalResolutionWhenTheUnitIsNotALength)
{
  // No unit: the OpenFFBoard joystick axes (physical = logical, HID 1.11 6.2.2.7).
  const Axes ffb = axesOf(vtouch::test::kOpenFfboard2Axis);
  EXPECT_EQ(vtouch::hidLengthPerCount_mm(ffb.x), 0.0);
  EXPECT_EQ(vtouch::hidLengthPerCount_mm(lengthField(0x1001, -4, 65535, 65535)), 0.0); // seconds
  EXPECT_EQ(vtouch::hidLengthPerCount_mm(lengthField(0x14, 0, 360, 36000)), 0.0);      // degrees
  EXPECT_EQ(vtouch::hidLengthPerCount_mm(lengthField(0x21, 0, 100, 100)), 0.0);        // cm^2
  EXPECT_EQ(vtouch::hidLengthPerCount_mm(lengthField(0x111, 0, 100, 100)), 0.0);       // cm*g
  EXPECT_EQ(vtouch::hidLengthPerCount_mm(lengthField(0x11, 0, 100, 0)), 0.0);          // no range
}

TEST(HidPidDevice, PositionResolutionComesFromThePhysicalUnitsWithoutAPreset)
{
  auto transport = std::make_shared<FakeHidTransport>(
    std::vector<FakeHidDevice>{ device("fake:pen", 0x045E, vtouch::test::kMicrosoftSamplePen) });
  HidPidDevice pen(transport, "fake:pen");
  pen.setPresetDirectory("/nonexistent/presets");
  ASSERT_EQ(pen.open(), DeviceStatus::Ok) << pen.lastError();
  EXPECT_EQ(pen.resolutionSource(), HidResolutionSource::Descriptor);
  EXPECT_NEAR(pen.capabilities().positionResolution_mm, 8.250 * kInch_mm / 21240.0, 1e-12);
  // The workspace is the physical extent, so the frame's millimetres are real ones.
  EXPECT_NEAR(pen.capabilities().workspace_mm.x, 8.250 * kInch_mm, 1e-9);
  EXPECT_NEAR(pen.capabilities().workspace_mm.y, 6.188 * kInch_mm, 1e-9);
  // X at its logical maximum is half the physical width right of centre; one count further in
  // is one resolution step.
  Bytes report{
    0x01, 0x00, 0xF8, 0x52, 0x6C, 0x3E, 0x00, 0x00, 0x00, 0x00
  }; // id, bits, X, Y, P, tilts
  transport->pushInput(report);
  DeviceState s;
  ASSERT_EQ(pen.read(s), DeviceStatus::Ok);
  EXPECT_NEAR(s.position_Device_mm.x, 0.5 * 8.250 * kInch_mm, 1e-9);
  report[2] = 0xF7; // X = 21239
  transport->pushInput(report);
  DeviceState t;
  ASSERT_EQ(pen.read(t), DeviceStatus::Ok);
  EXPECT_NEAR(s.position_Device_mm.x - t.position_Device_mm.x,
    pen.capabilities().positionResolution_mm,
    1e-9);
}

TEST(HidPidDevice, PositionResolutionIsOneCountOfThePresetFrameWhenAPresetApplies)
{
  // A preset fixes the frame (here 100 mm over each logical range): one count of it.
  auto transport = std::make_shared<FakeHidTransport>(
    std::vector<FakeHidDevice>{ device("fake:pen", 0x045E, vtouch::test::kMicrosoftSamplePen) });
  HidPidDevice pen(transport, "fake:pen");
  pen.setCalibration(DeviceCalibration{});
  ASSERT_EQ(pen.open(), DeviceStatus::Ok) << pen.lastError();
  EXPECT_EQ(pen.resolutionSource(), HidResolutionSource::Calibration);
  EXPECT_NEAR(pen.capabilities().positionResolution_mm, 100.0 / 15980.0, 1e-12); // the coarser Y
  EXPECT_DOUBLE_EQ(pen.capabilities().workspace_mm.x, 100.0);
}

TEST(HidPidDevice, PositionResolutionFallsBackToOneCountOfTheFrameWithoutPhysicalUnits)
{
  // OpenFFBoard declares no units: with its preset, 160 mm x 120 mm over -32767..32767 (the
  // coarser axis, X, counts); without one, the default 100 mm over the logical range.
  FakeHidDevice board = device("fake:openffboard", 0x1209, vtouch::test::kOpenFfboard2Axis);
  board.info.productId = 0xFFB0;
  auto next = std::make_shared<int>(0);
  board.featureResponder = [next](std::uint8_t* report, std::size_t size) -> int
  {
    if (report[0] != 0x12 || size < 5)
      return -1;
    report[1] = static_cast<std::uint8_t>(++*next); // Block Load: block n, success
    report[2] = 1;
    report[3] = 0xFF;
    report[4] = 0xFF;
    return 5;
  };
  auto transport = std::make_shared<FakeHidTransport>(std::vector<FakeHidDevice>{ board });
  HidPidDevice withPreset(transport, "fake:openffboard");
  withPreset.setPresetDirectory(VTOUCH_TEST_PRESETS_DIR);
  ASSERT_EQ(withPreset.open(), DeviceStatus::Ok) << withPreset.lastError();
  EXPECT_EQ(withPreset.resolutionSource(), HidResolutionSource::Calibration);
  EXPECT_NEAR(withPreset.capabilities().positionResolution_mm, 160.0 / 65534.0, 1e-12);
  withPreset.close();

  HidPidDevice noPreset(transport, "fake:openffboard");
  noPreset.setPresetDirectory("/nonexistent/presets");
  ASSERT_EQ(noPreset.open(), DeviceStatus::Ok) << noPreset.lastError();
  EXPECT_EQ(noPreset.resolutionSource(), HidResolutionSource::Calibration);
  EXPECT_NEAR(noPreset.capabilities().positionResolution_mm, 100.0 / 65534.0, 1e-12);
  EXPECT_DOUBLE_EQ(noPreset.capabilities().workspace_mm.x, 100.0);
}

TEST(HidPidDevice, PositionResolutionOfRelativeAxesIsOneCount)
{
  auto transport = std::make_shared<FakeHidTransport>(
    std::vector<FakeHidDevice>{ device("fake:mouse", 0x046D, vtouch::test::kHidSpecMouse) });
  HidPidDevice mouse(transport, "fake:mouse");
  mouse.setPresetDirectory("/nonexistent/presets");
  ASSERT_EQ(mouse.open(), DeviceStatus::Ok) << mouse.lastError();
  EXPECT_EQ(mouse.resolutionSource(), HidResolutionSource::Relative);
  EXPECT_NEAR(mouse.capabilities().positionResolution_mm, 1.0 / 16.0, 1e-12); // 16 counts/mm
}

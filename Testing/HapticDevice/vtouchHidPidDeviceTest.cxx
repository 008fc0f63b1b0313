#include "vtouchFakeHidTransport.h"
#include "vtouchHidPidDevice.h"
#include "vtouchHidTestDescriptors.h"
#include "vtouchSafeHapticDevice.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <memory>
#include <thread>

namespace
{
using vtouch::DeviceAxisCalibration;
using vtouch::DeviceCalibration;
using vtouch::DeviceState;
using vtouch::DeviceStatus;
using vtouch::FakeHidDevice;
using vtouch::FakeHidRecord;
using vtouch::FakeHidTransport;
using vtouch::HidPidDevice;
using vtouch::PidEffectMode;
using vtouch::SafeHapticDevice;
using vtouch::SafeHapticDeviceParameters;
using vtouch::SafetyFault;
using vtouch::Vec3;
using vtouch::test::hexBytes;
using Bytes = std::vector<std::uint8_t>;
using Kind = FakeHidRecord::Kind;

/// OpenFFBoard answers Block Load (feature 0x12) with blocks 1, 2, ...: [id, block, status, pool].
FakeHidDevice openFfboard()
{
  FakeHidDevice d;
  d.info.path = "fake:openffboard";
  d.info.vendorId = 0x1209;
  d.info.productId = 0xFFB0;
  d.info.product = "FFBoard";
  d.descriptor = hexBytes(vtouch::test::kOpenFfboard2Axis);
  auto next = std::make_shared<int>(0);
  d.featureResponder = [next](std::uint8_t* report, std::size_t size) -> int
  {
    if (report[0] != 0x12 || size < 5)
      return -1;
    report[1] = static_cast<std::uint8_t>(++*next);
    report[2] = 1; // Block Load Success
    report[3] = 0xFF;
    report[4] = 0xFF;
    return 5;
  };
  return d;
}

/// The SHIELD/SideWinder layout answers Block Load (feature 0x20) with blocks 5, 6... after `busy`
/// unusable answers (status 0: not yet loaded), or with Block Load Full when `full`.
FakeHidDevice shield(int busy = 0, bool full = false)
{
  FakeHidDevice d;
  d.info.path = "fake:shield";
  d.info.vendorId = 0x0955;
  d.info.productId = 0x7214;
  d.info.product = "SHIELD Controller";
  d.descriptor = hexBytes(vtouch::test::kShieldPidSegmentGamepad);
  auto calls = std::make_shared<int>(0);
  auto loaded = std::make_shared<int>(0);
  d.featureResponder = [calls, loaded, busy, full](std::uint8_t* report, std::size_t size) -> int
  {
    if (report[0] != 0x20 || size < 5)
      return -1;
    const bool ready = (*calls)++ >= busy;
    report[1] = static_cast<std::uint8_t>(5 + *loaded); // blocks 5, 6, ...
    *loaded += ready && !full ? 1 : 0;
    report[2] = full ? 2 : (ready ? 1 : 0);
    report[3] = 0x00;
    report[4] = 0x10;
    return 5;
  };
  return d;
}

FakeHidDevice mouse()
{
  FakeHidDevice d;
  d.info.path = "fake:mouse";
  d.info.vendorId = 0x046D;
  d.info.productId = 0xC077;
  d.info.product = "USB Optical Mouse";
  d.descriptor = hexBytes(vtouch::test::kHidSpecMouse);
  return d;
}

DeviceCalibration testCalibration(PidEffectMode mode = PidEffectMode::Auto)
{
  DeviceCalibration c;
  c.fullScaleForce_N = 1.0;
  c.maxContinuousForce_N = 1.0;
  c.effectMode = mode;
  c.keepAlive_s = 1e9; // no keep-alive re-sends: the byte sequence is exact
  return c;
}

std::vector<FakeHidRecord> recordsOf(const FakeHidTransport& t)
{
  return t.records();
}

void expectRecord(const FakeHidRecord& r, Kind kind, const Bytes& bytes)
{
  EXPECT_EQ(static_cast<int>(r.kind), static_cast<int>(kind));
  EXPECT_EQ(r.bytes, bytes);
}

TEST(HidPidDevice, SendsExactSetupReportsWhenOpenFfboardOpens)
{
  auto transport = std::make_shared<FakeHidTransport>(std::vector<FakeHidDevice>{ openFfboard() });
  HidPidDevice device(transport, "fake:openffboard");
  device.setCalibration(testCalibration());
  ASSERT_EQ(device.open(), DeviceStatus::Ok) << device.lastError();
  EXPECT_EQ(device.effectMode(), PidEffectMode::PerAxis);
  EXPECT_EQ(device.capabilities().actuatedDof, 2);
  EXPECT_EQ(device.capabilities().vendorId, 0x1209);
  EXPECT_STREQ(device.capabilities().name, "FFBoard");
  const auto r = recordsOf(*transport);
  ASSERT_EQ(r.size(), 13u);
  expectRecord(r[0], Kind::Output, Bytes{ 0x0C, 0x04 }); // DC Stop All Effects (bit 2)
  expectRecord(r[1], Kind::Output, Bytes{ 0x0D, 0xFF }); // Device Gain full
  expectRecord(r[2], Kind::SetFeature, Bytes{ 0x11, 0x01, 0x00, 0x00 }); // Create: constant
  expectRecord(r[3], Kind::GetFeature, Bytes{ 0x12 });                   // Block Load
  expectRecord(r[4],
    Kind::Output,
    Bytes{ 0x01,
      0x01,
      0x01,
      0xFF,
      0xFF,
      0x00,
      0x00,
      0x00,
      0x00,
      0x00,
      0x00,
      0xFF,
      0x00,
      0x01,
      0x28,
      0x23,
      0x00,
      0x00,
      0x00,
      0x00,
      0x00,
      0x00 }); // Set Effect: block 1, X only, 90 deg, infinite
  expectRecord(r[5], Kind::Output, Bytes{ 0x05, 0x01, 0x00, 0x00 }); // Constant Force 0
  expectRecord(r[6], Kind::Output, Bytes{ 0x0A, 0x01, 0x01, 0x01 }); // Start, loop 1
  expectRecord(r[7], Kind::SetFeature, Bytes{ 0x11, 0x01, 0x00, 0x00 });
  expectRecord(r[8], Kind::GetFeature, Bytes{ 0x12 });
  expectRecord(r[9],
    Kind::Output,
    Bytes{ 0x01,
      0x02,
      0x01,
      0xFF,
      0xFF,
      0x00,
      0x00,
      0x00,
      0x00,
      0x00,
      0x00,
      0xFF,
      0x00,
      0x02,
      0x50,
      0x46,
      0x00,
      0x00,
      0x00,
      0x00,
      0x00,
      0x00 }); // block 2, Y only, 180 deg
  expectRecord(r[10], Kind::Output, Bytes{ 0x05, 0x02, 0x00, 0x00 });
  expectRecord(r[11], Kind::Output, Bytes{ 0x0A, 0x02, 0x01, 0x01 });
  expectRecord(r[12], Kind::Output, Bytes{ 0x0C, 0x01 }); // DC Enable Actuators (bit 0)
}

TEST(HidPidDevice, StreamsSignedPerAxisMagnitudesWhenForceChanges)
{
  auto transport = std::make_shared<FakeHidTransport>(std::vector<FakeHidDevice>{ openFfboard() });
  HidPidDevice device(transport, "fake:openffboard");
  device.setCalibration(testCalibration());
  ASSERT_EQ(device.open(), DeviceStatus::Ok);
  transport->clearRecords();
  EXPECT_EQ(device.write(Vec3{ 0.5, 0.25, 0.0 }), DeviceStatus::Ok);
  // +x -> +16384; +y (up) -> HID Y points toward the user -> -8192 = 0xE000.
  auto out = transport->outputs();
  ASSERT_EQ(out.size(), 2u);
  EXPECT_EQ(out[0], (Bytes{ 0x05, 0x01, 0x00, 0x40 }));
  EXPECT_EQ(out[1], (Bytes{ 0x05, 0x02, 0x00, 0xE0 }));
  // Unchanged force: nothing is sent again.
  EXPECT_EQ(device.write(Vec3{ 0.5, 0.25, 0.0 }), DeviceStatus::Ok);
  EXPECT_EQ(transport->outputs().size(), 2u);
  // Beyond full scale: clamped to the logical maximum.
  device.write(Vec3{ -5.0, 0.25, 0.0 });
  out = transport->outputs();
  ASSERT_EQ(out.size(), 3u);
  EXPECT_EQ(out[2], (Bytes{ 0x05, 0x01, 0x01, 0x80 })); // -32767
}

TEST(HidPidDevice, StopsEffectsAndDisablesActuatorsWhenClosed)
{
  auto transport = std::make_shared<FakeHidTransport>(std::vector<FakeHidDevice>{ openFfboard() });
  HidPidDevice device(transport, "fake:openffboard");
  device.setCalibration(testCalibration());
  ASSERT_EQ(device.open(), DeviceStatus::Ok);
  device.write(Vec3{ 0.3, 0.0, 0.0 });
  transport->clearRecords();
  device.close();
  const auto out = transport->outputs();
  ASSERT_EQ(out.size(), 6u);
  EXPECT_EQ(out[0], (Bytes{ 0x0A, 0x01, 0x03, 0x00 })); // Op Effect Stop
  EXPECT_EQ(out[1], (Bytes{ 0x0B, 0x01 }));             // Block Free
  EXPECT_EQ(out[2], (Bytes{ 0x0A, 0x02, 0x03, 0x00 }));
  EXPECT_EQ(out[3], (Bytes{ 0x0B, 0x02 }));
  EXPECT_EQ(out[4], (Bytes{ 0x0C, 0x04 })); // Stop All Effects
  EXPECT_EQ(out[5], (Bytes{ 0x0C, 0x02 })); // Disable Actuators
  EXPECT_FALSE(transport->isOpen());
}

TEST(HidPidDevice, SendsExactPolarReportsWhenShieldLayoutOpensInPolarMode)
{
  auto transport = std::make_shared<FakeHidTransport>(std::vector<FakeHidDevice>{ shield() });
  HidPidDevice device(transport, "fake:shield");
  device.setCalibration(testCalibration(PidEffectMode::Polar));
  ASSERT_EQ(device.open(), DeviceStatus::Ok) << device.lastError();
  EXPECT_EQ(device.effectCount(), 1);
  EXPECT_EQ(device.effectBlockIndex(0), 5);
  auto r = recordsOf(*transport);
  ASSERT_EQ(r.size(), 8u);
  expectRecord(r[0], Kind::Output, Bytes{ 0x0C, 0x03 }); // DC Stop All: array value 3
  expectRecord(r[1], Kind::Output, Bytes{ 0x0D, 0xFF });
  expectRecord(r[2], Kind::SetFeature, Bytes{ 0x09, 0x01, 0x00, 0x00 });
  expectRecord(r[3], Kind::GetFeature, Bytes{ 0x20 });
  const Bytes setEffectNorth{
    0x21, 0x05, 0x01, 0xFF, 0xFF, 0x00, 0x00, 0x00, 0x00, 0xFF, 0x00, 0x07, 0x00, 0x00, 0x00, 0x00
  };
  expectRecord(r[4], Kind::Output, setEffectNorth);
  expectRecord(r[5], Kind::Output, Bytes{ 0x05, 0x05, 0x00, 0x00 });
  expectRecord(r[6], Kind::Output, Bytes{ 0x0A, 0x05, 0x01, 0x01 });
  expectRecord(r[7], Kind::Output, Bytes{ 0x0C, 0x01 }); // DC Enable: array value 1

  transport->clearRecords();
  device.write(Vec3{ 0.0, 0.5, 0.0 }); // up = away from the user = north = 0 degrees
  auto out = transport->outputs();
  ASSERT_EQ(out.size(), 2u);
  EXPECT_EQ(out[0], setEffectNorth);
  EXPECT_EQ(out[1], (Bytes{ 0x05, 0x05, 0x80, 0x00 })); // 0.5 * 255 -> 128
  device.write(Vec3{ 0.5, 0.0, 0.0 });                  // right = east = 90 degrees = 64 of 256
  out = transport->outputs();
  ASSERT_EQ(out.size(), 3u); // direction only: the magnitude did not change
  Bytes east = setEffectNorth;
  east[12] = 0x40;
  EXPECT_EQ(out[2], east);

  transport->clearRecords();
  device.close();
  out = transport->outputs();
  ASSERT_EQ(out.size(), 4u);
  EXPECT_EQ(out[0], (Bytes{ 0x0A, 0x05, 0x03, 0x00 }));
  EXPECT_EQ(out[1], (Bytes{ 0x0B, 0x05 }));
  EXPECT_EQ(out[2], (Bytes{ 0x0C, 0x03 }));
  EXPECT_EQ(out[3], (Bytes{ 0x0C, 0x02 }));
}

TEST(HidPidDevice, RetriesBlockLoadWhenDeviceAnswersLate)
{
  auto transport = std::make_shared<FakeHidTransport>(std::vector<FakeHidDevice>{ shield(3) });
  HidPidDevice device(transport, "fake:shield");
  device.setCalibration(testCalibration(PidEffectMode::Polar));
  ASSERT_EQ(device.open(), DeviceStatus::Ok) << device.lastError();
  int polls = 0;
  for (const auto& r : transport->records())
  {
    polls += r.kind == Kind::GetFeature ? 1 : 0;
  }
  EXPECT_EQ(polls, 4);
}

TEST(HidPidDevice, FailsOpenCleanlyWhenEffectMemoryIsFull)
{
  auto transport =
    std::make_shared<FakeHidTransport>(std::vector<FakeHidDevice>{ shield(0, true) });
  HidPidDevice device(transport, "fake:shield");
  device.setCalibration(testCalibration(PidEffectMode::Polar));
  EXPECT_EQ(device.open(), DeviceStatus::IoError);
  EXPECT_STREQ(device.lastError(), "the device's effect memory is full");
  EXPECT_FALSE(device.isOpen());
  EXPECT_FALSE(transport->isOpen());
  const auto out = transport->outputs();
  ASSERT_FALSE(out.empty());
  EXPECT_EQ(out.back(), (Bytes{ 0x0C, 0x02 })); // actuators disabled on the way out
}

TEST(HidPidDevice, UsesZeroForInfiniteDurationWhenPresetSaysSo)
{
  auto transport = std::make_shared<FakeHidTransport>(std::vector<FakeHidDevice>{ shield() });
  HidPidDevice device(transport, "fake:shield");
  DeviceCalibration c = testCalibration(PidEffectMode::Polar);
  c.infiniteDuration = 0;
  device.setCalibration(c);
  ASSERT_EQ(device.open(), DeviceStatus::Ok);
  const auto out = transport->outputs();
  EXPECT_EQ(out[2][3], 0x00);
  EXPECT_EQ(out[2][4], 0x00);
}

TEST(HidPidDevice, DecodesPositionAndButtonsWhenInputReportArrives)
{
  auto transport = std::make_shared<FakeHidTransport>(std::vector<FakeHidDevice>{ openFfboard() });
  HidPidDevice device(transport, "fake:openffboard");
  device.setPresetDirectory(VTOUCH_TEST_PRESETS_DIR); // Resources/Presets: the OpenFFBoard preset
  ASSERT_EQ(device.open(), DeviceStatus::Ok) << device.lastError();
  EXPECT_EQ(device.calibration().vendorId, 0x1209);
  EXPECT_DOUBLE_EQ(device.capabilities().workspace_mm.x, 160.0);
  DeviceState s;
  EXPECT_EQ(device.read(s), DeviceStatus::Timeout); // nothing received yet
  Bytes report(25, 0);
  report[0] = 0x01;
  report[1] = 0x05; // buttons 1 and 3
  report[9] = 0x00; // X = 16384
  report[10] = 0x40;
  report[11] = 0x00; // Y = -16384 (away from the user)
  report[12] = 0xC0;
  transport->pushInput(Bytes{ 0x02, 0x12 }); // PID State report: not a position, ignored
  transport->pushInput(report);
  ASSERT_EQ(device.read(s), DeviceStatus::Ok);
  EXPECT_NEAR(s.position_Device_mm.x, 0.25 * 160.0, 0.01);
  EXPECT_NEAR(s.position_Device_mm.y, 0.25 * 120.0, 0.01);
  EXPECT_EQ(s.buttons, 0x5u);
  EXPECT_EQ(device.ignoredInputReports(), 1u);
}

TEST(HidPidDevice, KeepsNewestReportWhenSeveralArePending)
{
  auto transport = std::make_shared<FakeHidTransport>(std::vector<FakeHidDevice>{ shield() });
  HidPidDevice device(transport, "fake:shield");
  device.setCalibration(testCalibration(PidEffectMode::Polar));
  ASSERT_EQ(device.open(), DeviceStatus::Ok);
  for (std::uint8_t x : { 10, 20, 255 })
  {
    transport->pushInput(Bytes{ 0x01, x, 0x80, 0x00 });
  }
  DeviceState s;
  ASSERT_EQ(device.read(s), DeviceStatus::Ok);
  EXPECT_NEAR(s.position_Device_mm.x, 50.0, 1e-9); // 255 of 0..255 over the default 100 mm
}

TEST(HidPidDevice, ReportsTheAxisCalibrationItAppliesAndAChangedOneMovesThePositions)
{
  // The SHIELD's X and Y are 8-bit logical values (0..255); the calibration maps them onto the
  // workspace, and what axisCalibration() says is what read() does.
  for (const double width_mm : { 100.0, 40.0 })
  {
    auto transport = std::make_shared<FakeHidTransport>(std::vector<FakeHidDevice>{ shield() });
    HidPidDevice device(transport, "fake:shield");
    DeviceCalibration c = testCalibration(PidEffectMode::Polar);
    c.workspace_mm.x = width_mm;
    device.setCalibration(c);
    EXPECT_EQ(device.axisCalibration().axisCount, 0); // not open yet
    ASSERT_EQ(device.open(), DeviceStatus::Ok) << device.lastError();
    const DeviceAxisCalibration applied = device.axisCalibration();
    ASSERT_EQ(applied.axisCount, 2);
    EXPECT_DOUBLE_EQ(applied.axes[0].rawMinimum, 0.0);
    EXPECT_DOUBLE_EQ(applied.axes[0].rawMaximum, 255.0);
    EXPECT_DOUBLE_EQ(applied.axes[0].minimum_mm, -0.5 * width_mm);
    EXPECT_DOUBLE_EQ(applied.axes[0].maximum_mm, 0.5 * width_mm);
    EXPECT_GT(applied.axes[1].minimum_mm, applied.axes[1].maximum_mm); // HID y grows downward

    transport->pushInput(Bytes{ 0x01, 255, 0x00, 0x00 }); // x at its raw maximum, y at its minimum
    DeviceState s;
    ASSERT_EQ(device.read(s), DeviceStatus::Ok);
    EXPECT_NEAR(s.position_Device_mm.x, applied.axes[0].maximum_mm, 1e-9);
    EXPECT_NEAR(s.position_Device_mm.y, applied.axes[1].minimum_mm, 1e-9);
  }
}

TEST(HidPidDevice, ReportsNoAxisCalibrationForRelativeAxes)
{
  auto transport = std::make_shared<FakeHidTransport>(std::vector<FakeHidDevice>{ mouse() });
  HidPidDevice device(transport, "fake:mouse");
  ASSERT_EQ(device.open(), DeviceStatus::Ok) << device.lastError();
  EXPECT_EQ(device.axisCalibration().axisCount, 0); // a mouse moves by counts per millimetre
}

TEST(HidPidDevice, IgnoresReportWhenTruncatedOrOfUnknownId)
{
  auto transport = std::make_shared<FakeHidTransport>(std::vector<FakeHidDevice>{ shield() });
  HidPidDevice device(transport, "fake:shield");
  device.setCalibration(testCalibration(PidEffectMode::Polar));
  ASSERT_EQ(device.open(), DeviceStatus::Ok);
  transport->pushInput(Bytes{ 0x01, 0x10 });       // truncated
  transport->pushInput(Bytes{ 0x7E, 1, 2, 3, 4 }); // unknown ID
  transport->pushInput(Bytes{ 0x01 });
  DeviceState s;
  EXPECT_EQ(device.read(s), DeviceStatus::Timeout);
  EXPECT_EQ(device.ignoredInputReports(), 3u);
}

TEST(HidPidDevice, WorksAsInputOnlyWhenDeviceHasNoPidReports)
{
  auto transport = std::make_shared<FakeHidTransport>(std::vector<FakeHidDevice>{ mouse() });
  HidPidDevice device(transport, "fake:mouse");
  ASSERT_EQ(device.open(), DeviceStatus::Ok) << device.lastError();
  EXPECT_FALSE(device.forceSupported());
  EXPECT_EQ(device.capabilities().actuatedDof, 0);
  EXPECT_EQ(device.capabilities().buttonCount, 3);
  EXPECT_EQ(device.write(Vec3{ 0.1, 0.0, 0.0 }), DeviceStatus::Unsupported);
  EXPECT_TRUE(transport->outputs().empty());
  transport->pushInput(Bytes{ 0x01, 0x05, 0xFB }); // button 1, dx = +5, dy = -5 counts
  transport->pushInput(Bytes{ 0x00, 0x05, 0x00 }); // dx = +5 again
  DeviceState s;
  ASSERT_EQ(device.read(s), DeviceStatus::Ok);
  EXPECT_NEAR(s.position_Device_mm.x, 10.0 / 16.0, 1e-9); // both deltas count
  EXPECT_NEAR(s.position_Device_mm.y, 5.0 / 16.0, 1e-9);  // HID -y is up
  EXPECT_EQ(s.buttons, 0u);                               // the newest report has no button
}

TEST(HidPidDevice, ReportsDisconnectedWhenUnpluggedMidStream)
{
  auto transport = std::make_shared<FakeHidTransport>(std::vector<FakeHidDevice>{ openFfboard() });
  HidPidDevice device(transport, "fake:openffboard");
  device.setCalibration(testCalibration());
  ASSERT_EQ(device.open(), DeviceStatus::Ok);
  for (int i = 0; i < 10; ++i)
  {
    EXPECT_EQ(device.write(Vec3{ 0.01 * i, 0.0, 0.0 }), DeviceStatus::Ok);
  }
  transport->setUnplugged(true);
  EXPECT_EQ(device.write(Vec3{ 0.5, 0.0, 0.0 }), DeviceStatus::Disconnected);
  DeviceState s;
  EXPECT_EQ(device.read(s), DeviceStatus::Disconnected);
  device.close(); // must not hang or crash
  EXPECT_EQ(device.open(), DeviceStatus::Disconnected);
  transport->setUnplugged(false);
  EXPECT_EQ(device.open(), DeviceStatus::Ok);
}

TEST(HidPidDevice, ReportsIoErrorWhenWriteFails)
{
  auto transport = std::make_shared<FakeHidTransport>(std::vector<FakeHidDevice>{ openFfboard() });
  HidPidDevice device(transport, "fake:openffboard");
  device.setCalibration(testCalibration());
  ASSERT_EQ(device.open(), DeviceStatus::Ok);
  transport->failWritesAfter(0);
  EXPECT_EQ(device.write(Vec3{ 0.5, 0.0, 0.0 }), DeviceStatus::IoError);
}

TEST(HidPidDevice, RejectsDeviceWhenDescriptorIsMalformed)
{
  FakeHidDevice broken = openFfboard();
  broken.descriptor.resize(broken.descriptor.size() / 2); // truncated: unbalanced collections
  auto transport = std::make_shared<FakeHidTransport>(std::vector<FakeHidDevice>{ broken });
  HidPidDevice device(transport, "fake:openffboard");
  EXPECT_EQ(device.open(), DeviceStatus::IoError);
  EXPECT_NE(std::string(device.lastError()).find("unusable report descriptor"), std::string::npos);
  EXPECT_FALSE(transport->isOpen());
}

TEST(HidPidDevice, ReopensThroughSafeDeviceWhenReplugged)
{
  auto transport = std::make_shared<FakeHidTransport>(std::vector<FakeHidDevice>{ openFfboard() });
  auto hid = std::make_unique<HidPidDevice>(transport, "fake:openffboard");
  hid->setCalibration(testCalibration());
  std::atomic<double> now{ 100.0 };
  SafeHapticDeviceParameters p;
  p.watchdogThread = false;
  p.clock_s = [&now]() { return now.load(); };
  p.filter.engageTicks = 2;
  SafeHapticDevice device(std::move(hid), p);
  ASSERT_EQ(device.open(), DeviceStatus::Ok);
  for (int i = 0; i < 5; ++i)
  {
    device.write(Vec3{ i < 2 ? 0.0 : 0.2, 0.0, 0.0 });
    now = now + 0.001;
  }
  transport->setUnplugged(true);
  DeviceState s;
  EXPECT_EQ(device.read(s), DeviceStatus::Disconnected); // the next tick's read sees it first
  EXPECT_EQ(device.fault(), SafetyFault::Disconnected);
  EXPECT_EQ(device.write(Vec3{ 0.2, 0.0, 0.0 }), DeviceStatus::Disconnected);
  now = now + 1.0;
  device.pollWatchdog(now);
  EXPECT_EQ(device.reopenCount(), 0u);
  transport->setUnplugged(false);
  now = now + 1.0;
  device.pollWatchdog(now);
  EXPECT_EQ(device.reopenCount(), 1u);
  EXPECT_EQ(device.fault(), SafetyFault::None);
  EXPECT_EQ(transport->openCount(), 2);
}

TEST(HidPidDevice, WatchdogLatchesAndZeroesWhenUsbWriteStalls)
{
  auto transport = std::make_shared<FakeHidTransport>(std::vector<FakeHidDevice>{ openFfboard() });
  auto hid = std::make_unique<HidPidDevice>(transport, "fake:openffboard");
  hid->setCalibration(testCalibration());
  SafeHapticDeviceParameters p;
  p.filter.engageTicks = 1;
  p.filter.maxSlewRate_N_per_s = 1e9;
  SafeHapticDevice device(std::move(hid), p);
  ASSERT_EQ(device.open(), DeviceStatus::Ok);
  device.write(Vec3{});
  std::atomic<bool> stop{ false };
  std::thread loop(
    [&]()
    {
      for (int i = 0; !stop; ++i)
      {
        device.write(Vec3{ 0.4 + 0.001 * (i % 2), 0.0, 0.0 });
        std::this_thread::sleep_for(std::chrono::microseconds(200));
      }
    });
  auto eventually = [](auto predicate)
  {
    for (int i = 0; i < 5000 && !predicate(); ++i)
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    return predicate();
  };
  ASSERT_TRUE(eventually([&]() { return transport->outputs().size() > 20; }));
  transport->stallWrites(true); // the haptic thread blocks inside hid_write
  ASSERT_TRUE(eventually([&]() { return device.fault() == SafetyFault::Watchdog; }));
  transport->releaseStall();
  // Once the write returns, the zero force reaches the device.
  ASSERT_TRUE(eventually(
    [&]()
    {
      // The newest X magnitude report is zero (Y never left zero, so it is not re-sent).
      const auto out = transport->outputs();
      for (auto it = out.rbegin(); it != out.rend(); ++it)
      {
        if (it->size() == 4 && (*it)[0] == 0x05 && (*it)[1] == 0x01)
          return *it == Bytes({ 0x05, 0x01, 0x00, 0x00 });
      }
      return false;
    }));
  stop = true;
  loop.join();
  EXPECT_EQ(device.fault(), SafetyFault::Watchdog);
}

} // namespace

namespace
{
/// The SHIELD layout with parts cut out, as firmwares that omit them have it (synthetic variants
/// of the real descriptor, still valid HID).
std::string without(std::string text, const std::string& part)
{
  const auto at = text.find(part);
  EXPECT_NE(at, std::string::npos);
  return at == std::string::npos ? text : text.erase(at, part.size());
}
const std::string kDirectionCollection =
  " 09 57 A1 02 0B 01 00 0A 00 0B 02 00 0A 00 66 14 00 55 FE 15 00 26 FF 00 35 00"
  " 47 A0 8C 00 00 66 00 00 75 08 95 02 91 02 55 00 66 00 00 C0";
const std::string kAxesEnableCollection =
  " 09 55 A1 02 05 01 09 30 09 31 15 00 25 01 75 01 95 02 91 02 C0";

FakeHidDevice shieldVariant(const std::string& hex)
{
  FakeHidDevice d = shield();
  d.descriptor = hexBytes(hex.c_str());
  return d;
}
} // namespace

TEST(HidPidDevice, FallsBackToPerAxisWhenDirectionFieldIsMissing)
{
  const std::string hex = without(vtouch::test::kShieldPidSegmentGamepad, kDirectionCollection);
  auto transport =
    std::make_shared<FakeHidTransport>(std::vector<FakeHidDevice>{ shieldVariant(hex) });
  HidPidDevice device(transport, "fake:shield");
  device.setCalibration(testCalibration(PidEffectMode::Polar));
  ASSERT_EQ(device.open(), DeviceStatus::Ok) << device.lastError();
  EXPECT_FALSE(device.layout().seDirection0.valid());
  EXPECT_EQ(device.effectMode(), PidEffectMode::PerAxis);
  EXPECT_EQ(device.effectCount(), 2);
  transport->clearRecords();
  device.write(Vec3{ 0.0, -1.0, 0.0 }); // down = toward the user = +HID Y: +255 on effect 2
  const auto out = transport->outputs();
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0], (Bytes{ 0x05, 0x06, 0xFF, 0x00 })); // effect 2 got block 6
}

TEST(HidPidDevice, DrivesXOnlyWhenNeitherDirectionNorAxesEnableExist)
{
  const std::string hex = without(
    without(vtouch::test::kShieldPidSegmentGamepad, kDirectionCollection), kAxesEnableCollection);
  auto transport =
    std::make_shared<FakeHidTransport>(std::vector<FakeHidDevice>{ shieldVariant(hex) });
  HidPidDevice device(transport, "fake:shield");
  device.setCalibration(testCalibration());
  ASSERT_EQ(device.open(), DeviceStatus::Ok) << device.lastError();
  EXPECT_EQ(device.effectMode(), PidEffectMode::SingleX);
  EXPECT_EQ(device.capabilities().actuatedDof, 1);
  transport->clearRecords();
  device.write(Vec3{ -0.5, 0.7, 0.0 });
  const auto out = transport->outputs();
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0], (Bytes{ 0x05, 0x05, 0x80, 0xFF })); // -128 (y ignored)
}

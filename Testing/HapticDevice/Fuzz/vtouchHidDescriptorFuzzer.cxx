// libFuzzer target: the HID report-descriptor parser, the PID layout finder, field access, and a
// whole HidPidDevice open/write/read/close over a fake transport replaying the fuzzed descriptor.
#include "vtouchFakeHidTransport.h"
#include "vtouchHidPidDevice.h"
#include "vtouchHidPidLayout.h"
#include "vtouchHidReportDescriptor.h"

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

namespace
{
void exerciseFields(const vtouch::HidReportDescriptor& d)
{
  std::vector<std::uint8_t> payload(64, 0xA5);
  for (const vtouch::HidField& f : d.fields())
  {
    const std::uint32_t elements = f.reportCount < 8 ? f.reportCount : 8;
    for (std::uint32_t e = 0; e < elements; ++e)
    {
      std::int64_t v = 0;
      f.read(payload.data(), payload.size(), e, v);
      f.write(payload.data(), payload.size(), e, v + 1);
      (void)d.usageAt(f, e);
    }
    (void)d.usageCount(f);
    (void)d.indexOfUsage(f, vtouch::pid::kEtConstantForce);
    (void)d.enclosingCollection(f.collection, vtouch::pid::kSetEffectReport);
  }
}

void exerciseDevice(const std::uint8_t* data, std::size_t size)
{
  vtouch::FakeHidDevice device;
  device.info.path = "fuzz";
  device.descriptor.assign(data, data + size);
  // Any Block Load request succeeds at once with block 1 (no retry sleeps while fuzzing).
  device.featureResponder = [](std::uint8_t* report, std::size_t n) -> int
  {
    for (std::size_t i = 1; i < n; ++i)
    {
      report[i] = 1;
    }
    return static_cast<int>(n);
  };
  auto transport =
    std::make_shared<vtouch::FakeHidTransport>(std::vector<vtouch::FakeHidDevice>{ device });
  vtouch::HidPidDevice hid(transport, "fuzz");
  vtouch::DeviceCalibration calibration;
  calibration.blockLoadRetries = 1;
  hid.setCalibration(calibration);
  if (hid.open() != vtouch::DeviceStatus::Ok)
  {
    return;
  }
  std::vector<std::uint8_t> input(data, data + (size < 64 ? size : 64));
  transport->pushInput(input);
  vtouch::DeviceState state;
  hid.read(state);
  hid.write(vtouch::Vec3{ 0.3, -0.7, 0.0 });
  hid.write(vtouch::Vec3{ -2.0, 0.1, 0.0 });
  hid.close();
}
} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  vtouch::HidReportDescriptor d;
  if (!d.parse(data, size))
  {
    return 0;
  }
  const vtouch::HidPidLayout layout = vtouch::HidPidLayout::find(d);
  (void)layout.hasConstantForce();
  exerciseFields(d);
  for (int id = 0; id < 256; ++id)
  {
    (void)d.reportBytes(vtouch::HidReportType::Output, static_cast<std::uint8_t>(id));
  }
  exerciseDevice(data, size);
  return 0;
}

// Cost of the real-time calls: read()/write() of the simulated and safety-wrapped devices, the HID
// force path over the fake transport, and the report-descriptor parser.
#include "vtouchFakeHidTransport.h"
#include "vtouchHidInputDecoder.h"
#include "vtouchHidPidDevice.h"
#include "vtouchHidReportDescriptor.h"
#include "vtouchHidTestDescriptors.h"
#include "vtouchSafeHapticDevice.h"
#include "vtouchSimulatedDevice.h"

#include <benchmark/benchmark.h>

#include <memory>

namespace
{
using vtouch::Vec3;

void BM_SimulatedDeviceReadWrite(benchmark::State& state)
{
  vtouch::SimulatedDevice device;
  device.setHandScript(vtouch::HandScript::circle(vtouch::Vec2{}, 20.0, 1.0));
  device.open();
  vtouch::DeviceState s;
  for (auto _ : state)
  {
    device.read(s);
    device.write(Vec3{ -0.1 * s.position_Device_mm.x, -0.1 * s.position_Device_mm.y, 0.0 });
    benchmark::DoNotOptimize(s);
  }
}
BENCHMARK(BM_SimulatedDeviceReadWrite);

void BM_SimulatedDeviceAdvance1ms(benchmark::State& state)
{
  vtouch::SimulatedDevice device;
  device.setHandScript(vtouch::HandScript::circle(vtouch::Vec2{}, 20.0, 1.0));
  device.open();
  for (auto _ : state)
  {
    device.advance(0.001); // ten 0.1 ms sub-steps
  }
}
BENCHMARK(BM_SimulatedDeviceAdvance1ms);

void BM_SafeHapticDeviceReadWrite(benchmark::State& state)
{
  vtouch::SafeHapticDeviceParameters p;
  p.watchdogTimeout_s = 10.0; // the benchmark loop must not be judged by the watchdog
  vtouch::SafeHapticDevice device(std::make_unique<vtouch::SimulatedDevice>(), p);
  device.open();
  vtouch::DeviceState s;
  for (auto _ : state)
  {
    device.read(s);
    device.write(Vec3{ -0.1 * s.position_Device_mm.x, 0.2, 0.0 });
    benchmark::DoNotOptimize(s);
  }
}
BENCHMARK(BM_SafeHapticDeviceReadWrite);

void BM_HidPidDeviceWriteOverFakeTransport(benchmark::State& state)
{
  vtouch::FakeHidDevice fake;
  fake.info.path = "bench";
  fake.descriptor = vtouch::test::hexBytes(vtouch::test::kOpenFfboard2Axis);
  int block = 0;
  fake.featureResponder = [&block](std::uint8_t* r, std::size_t n) -> int
  {
    r[1] = static_cast<std::uint8_t>(++block);
    r[2] = 1;
    return static_cast<int>(n);
  };
  auto transport =
    std::make_shared<vtouch::FakeHidTransport>(std::vector<vtouch::FakeHidDevice>{ fake });
  vtouch::HidPidDevice device(transport, "bench");
  device.open();
  int i = 0;
  for (auto _ : state)
  {
    device.write(Vec3{ 0.001 * (i++ % 500), 0.1, 0.0 });
    if (i % 4096 == 0)
    {
      state.PauseTiming();
      transport->clearRecords(); // the fake records every report; keep memory flat
      state.ResumeTiming();
    }
  }
}
BENCHMARK(BM_HidPidDeviceWriteOverFakeTransport);

void BM_HidInputDecode(benchmark::State& state)
{
  const auto bytes = vtouch::test::hexBytes(vtouch::test::kOpenFfboard2Axis);
  vtouch::HidReportDescriptor d;
  d.parse(bytes.data(), bytes.size());
  const vtouch::HidPidLayout layout = vtouch::HidPidLayout::find(d);
  vtouch::HidInputDecoder decoder;
  decoder.configure(d, layout);
  std::vector<std::uint8_t> report(25, 0x11);
  report[0] = 1;
  vtouch::HidInputSample sample;
  for (auto _ : state)
  {
    benchmark::DoNotOptimize(decoder.decode(report.data(), report.size(), sample));
  }
}
BENCHMARK(BM_HidInputDecode);

void BM_ParseDescriptor(benchmark::State& state, const char* hex)
{
  const auto bytes = vtouch::test::hexBytes(hex);
  for (auto _ : state)
  {
    vtouch::HidReportDescriptor d;
    benchmark::DoNotOptimize(d.parse(bytes.data(), bytes.size()));
  }
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations() * bytes.size()));
}
BENCHMARK_CAPTURE(BM_ParseDescriptor, OpenFFBoard, vtouch::test::kOpenFfboard2Axis);
BENCHMARK_CAPTURE(BM_ParseDescriptor, ShieldPid, vtouch::test::kShieldPidSegmentGamepad);

void BM_FindPidLayout(benchmark::State& state)
{
  const auto bytes = vtouch::test::hexBytes(vtouch::test::kOpenFfboard2Axis);
  vtouch::HidReportDescriptor d;
  d.parse(bytes.data(), bytes.size());
  for (auto _ : state)
  {
    benchmark::DoNotOptimize(vtouch::HidPidLayout::find(d));
  }
}
BENCHMARK(BM_FindPidLayout);

} // namespace

BENCHMARK_MAIN();

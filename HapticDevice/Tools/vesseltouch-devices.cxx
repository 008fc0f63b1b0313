// vesseltouch-devices: lists the haptic devices VesselTouch can use and runs a short, low-force,
// clearly announced self-test on one of them.
//
//   vesseltouch-devices                       list HID devices and the built-in devices
//   vesseltouch-devices --self-test N --yes   push gently left/right on HID device N (or "sim")
//        [--force 0.3]                        peak force in newtons (at most 0.5)
#include "vtouchDeviceCalibration.h"
#include "vtouchHidPidDevice.h"
#include "vtouchHidPidLayout.h"
#include "vtouchHidReportDescriptor.h"
#include "vtouchHidapiTransport.h"
#include "vtouchPointerDevice.h"
#include "vtouchSafeHapticDevice.h"
#include "vtouchSimulatedDevice.h"

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <thread>
#include <vector>

namespace
{
constexpr double kMaxSelfTestForce_N = 0.5;
std::atomic<bool> gInterrupted{ false };

void onSignal(int)
{
  gInterrupted = true;
}

void printCapabilities(const vtouch::DeviceCapabilities& c, const char* indent)
{
  std::printf("%ssenses %d axes, actuates %d, workspace %.0f x %.0f mm, max force %.2f N, "
              "max stiffness %.0f N/m, up to %.0f Hz, pressure %s, %d buttons\n",
    indent,
    c.sensedDof,
    c.actuatedDof,
    c.workspace_mm.x,
    c.workspace_mm.y,
    c.maxContinuousForce_N,
    c.maxStiffness_N_per_m,
    c.maxUpdateRate_Hz,
    c.hasPressure ? "yes" : "no",
    c.buttonCount);
}

/// Reads and parses the descriptor without sending anything to the device.
void describeHid(vtouch::HidapiTransport& transport, const vtouch::HidDeviceInfo& info)
{
  if (!transport.open(info.path))
  {
    std::printf("      cannot open: %s\n", transport.lastError());
    return;
  }
  std::vector<std::uint8_t> raw(vtouch::HidReportDescriptor::kMaxDescriptorBytes);
  const int n = transport.reportDescriptor(raw.data(), raw.size());
  vtouch::HidReportDescriptor d;
  if (n <= 0 || !d.parse(raw.data(), static_cast<std::size_t>(n)))
  {
    std::printf(
      "      report descriptor unusable: %s\n", n <= 0 ? transport.lastError() : d.error());
    transport.close();
    return;
  }
  transport.close();
  const vtouch::HidPidLayout l = vtouch::HidPidLayout::find(d);
  std::printf("      descriptor: %d bytes, %zu fields, report IDs %s\n",
    n,
    d.fields().size(),
    d.usesReportIds() ? "yes" : "no");
  std::printf("      position input: %s\n",
    l.hasPosition()
      ? (std::string("X/Y in input report ") + std::to_string(l.input.reportId)).c_str()
      : "none");
  struct Named
  {
    const char* name;
    const vtouch::HidReportRef& ref;
  };
  const Named reports[] = { { "Set Effect", l.setEffect },
    { "Set Constant Force", l.setConstantForce },
    { "Effect Operation", l.effectOperation },
    { "Device Control", l.deviceControl },
    { "Device Gain", l.deviceGain },
    { "Create New Effect", l.createNewEffect },
    { "Block Load", l.blockLoad },
    { "PID Pool", l.pool },
    { "Block Free", l.blockFree } };
  std::string found;
  for (const Named& r : reports)
  {
    if (r.ref.present)
    {
      found += std::string(found.empty() ? "" : ", ") + r.name + " (" +
               std::to_string(r.ref.reportId) + ")";
    }
  }
  std::printf("      PID reports: %s\n", found.empty() ? "none (input only)" : found.c_str());
  std::printf(
    "      force output: %s\n", l.hasConstantForce() ? "constant force supported" : "unsupported");
  vtouch::DeviceCalibration c;
  const bool preset = vtouch::DeviceCalibration::findPreset(
    vtouch::DeviceCalibration::presetDirectory(), info.vendorId, info.productId, c);
  std::printf(
    "      calibration: %s\n", preset ? c.name.c_str() : "defaults (no preset for these ids)");
}

int list()
{
  std::printf("Built-in devices:\n");
  {
    vtouch::SimulatedDevice sim;
    sim.open();
    std::printf("  sim      %s\n", sim.capabilities().name);
    printCapabilities(sim.capabilities(), "           ");
  }
  {
    vtouch::PointerDevice pointer;
    std::printf(
      "  pointer  %s (mouse + pseudo-haptics, inside the viewer)\n", pointer.capabilities().name);
    printCapabilities(pointer.capabilities(), "           ");
  }
  std::printf("  replay   plays a recorded CSV (time,x,y,pressure,buttons), records forces\n\n");

  vtouch::HidapiTransport transport;
  const std::vector<vtouch::HidDeviceInfo> devices = transport.enumerate();
  if (devices.empty())
  {
    std::printf("No HID devices found (none plugged in, or /dev/hidraw* not visible here).\n");
    return 0;
  }
  std::printf("HID devices:\n");
  for (std::size_t i = 0; i < devices.size(); ++i)
  {
    const vtouch::HidDeviceInfo& d = devices[i];
    std::printf("  [%zu] %04x:%04x %s %s  (%s, usage %04x:%04x, interface %d)\n",
      i,
      d.vendorId,
      d.productId,
      d.manufacturer.c_str(),
      d.product.c_str(),
      d.path.c_str(),
      d.usagePage,
      d.usage,
      d.interfaceNumber);
    describeHid(transport, d);
  }
  return 0;
}

int selfTest(const std::string& which, double peak_N, bool confirmed)
{
  std::unique_ptr<vtouch::HapticDevice> device;
  vtouch::SimulatedDevice* sim = nullptr;
  std::string label;
  if (which == "sim")
  {
    auto s = std::make_unique<vtouch::SimulatedDevice>();
    s->setHandScript(vtouch::HandScript::holdAt(vtouch::Vec2{}, 200.0));
    sim = s.get();
    device = std::move(s);
    label = "the simulated stylus";
  }
  else
  {
    auto transport = std::make_shared<vtouch::HidapiTransport>();
    const std::vector<vtouch::HidDeviceInfo> devices = transport->enumerate();
    char* end = nullptr;
    const unsigned long index = std::strtoul(which.c_str(), &end, 10);
    if (*end != '\0' || index >= devices.size())
    {
      std::fprintf(
        stderr, "No HID device %s (run without arguments to list them).\n", which.c_str());
      return 2;
    }
    label = devices[index].product + " (" + devices[index].path + ")";
    device = std::make_unique<vtouch::HidPidDevice>(transport, devices[index].path);
  }

  std::printf("SELF-TEST on %s: a gentle push of at most %.2f N to the LEFT for 1 s, then to the "
              "RIGHT for 1 s, then zero.\nHold the handle lightly; Ctrl-C stops at once.\n",
    label.c_str(),
    peak_N);
  if (!confirmed)
  {
    std::printf("Not started: add --yes to confirm.\n");
    return 2;
  }

  vtouch::SafeHapticDeviceParameters p;
  p.filter.maxForce_N = peak_N;
  p.filter.maxSlewRate_N_per_s = 2.0; // 0.25 s ramps: no jolt
  p.filter.engageTicks = 5;
  vtouch::SafeHapticDevice safe(std::move(device), p);
  const vtouch::DeviceStatus status = safe.open();
  if (status != vtouch::DeviceStatus::Ok)
  {
    std::fprintf(stderr, "Cannot open: %s (%s)\n", safe.lastError(), vtouch::toString(status));
    return 1;
  }
  printCapabilities(safe.capabilities(), "  ");
  if (safe.capabilities().actuatedDof == 0)
  {
    std::printf("This device has no force output: position check only.\n");
  }
  std::signal(SIGINT, onSignal);
  const auto start = std::chrono::steady_clock::now();
  auto next = start;
  const auto period = std::chrono::milliseconds(2);
  double minX = 1e9, maxX = -1e9;
  int ticks = 0, errors = 0;
  while (!gInterrupted)
  {
    const double t =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (t > 2.5)
    {
      break;
    }
    const double fx = t < 0.05 ? 0.0 : (t < 1.0 ? -peak_N : (t < 2.0 ? peak_N : 0.0));
    vtouch::DeviceState s;
    if (safe.read(s) == vtouch::DeviceStatus::Ok)
    {
      minX = std::min(minX, s.position_Device_mm.x);
      maxX = std::max(maxX, s.position_Device_mm.x);
    }
    const vtouch::DeviceStatus w = safe.write(vtouch::Vec3{ fx, 0.0, 0.0 });
    if (w != vtouch::DeviceStatus::Ok && w != vtouch::DeviceStatus::Unsupported)
    {
      ++errors;
    }
    if (sim)
    {
      sim->advance(0.002);
    }
    if (ticks++ % 250 == 0)
    {
      std::printf("  t=%.2f s  force %+.2f N  x %+.2f mm\n",
        t,
        safe.lastSentForce_N().x,
        s.position_Device_mm.x);
    }
    next += period;
    std::this_thread::sleep_until(next);
  }
  safe.write(vtouch::Vec3{});
  safe.close();
  std::printf("Done%s. Handle moved over %.2f mm in x; %d write errors; fault: %s.\n",
    gInterrupted ? " (interrupted)" : "",
    maxX > minX ? maxX - minX : 0.0,
    errors,
    vtouch::toString(safe.fault()));
  return errors == 0 ? 0 : 1;
}

void usage()
{
  std::printf("usage: vesseltouch-devices [--list]\n"
              "       vesseltouch-devices --self-test <index|sim> --yes [--force N]\n"
              "  --force N   peak self-test force in newtons, at most %.1f (default 0.3)\n",
    kMaxSelfTestForce_N);
}
} // namespace

int main(int argc, char** argv)
{
  std::string selfTestTarget;
  bool confirmed = false;
  double force_N = 0.3;
  for (int i = 1; i < argc; ++i)
  {
    const std::string arg = argv[i];
    if (arg == "--list")
    {
      continue;
    }
    if (arg == "--yes")
    {
      confirmed = true;
    }
    else if (arg == "--self-test" && i + 1 < argc)
    {
      selfTestTarget = argv[++i];
    }
    else if (arg == "--force" && i + 1 < argc)
    {
      force_N = std::atof(argv[++i]);
    }
    else if (arg == "-h" || arg == "--help")
    {
      usage();
      return 0;
    }
    else
    {
      usage();
      return 2;
    }
  }
  if (!(force_N > 0.0) || force_N > kMaxSelfTestForce_N)
  {
    std::fprintf(stderr, "--force must be in (0, %.1f] N\n", kMaxSelfTestForce_N);
    return 2;
  }
  return selfTestTarget.empty() ? list() : selfTest(selfTestTarget, force_N, confirmed);
}

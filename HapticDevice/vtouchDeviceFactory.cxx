#include "vtouchDeviceFactory.h"

#include "vtouchHidPidDevice.h"
#include "vtouchHidapiTransport.h"
#include "vtouchPointerDevice.h"
#include "vtouchReplayDevice.h"
#include "vtouchSafeHapticDevice.h"
#include "vtouchSimulatedDevice.h"

#include <cmath>
#include <utility>

namespace vtouch
{
namespace
{
std::unique_ptr<SimulatedDevice> buildSimulated(const DeviceRequest& r)
{
  SimulatedDeviceParameters dp;
  dp.clock = r.offline ? SimulatedDeviceParameters::Clock::Manual
                       : SimulatedDeviceParameters::Clock::RealTime;
  dp.mass_kg = r.simulatedMass_kg;
  dp.damping_N_s_per_m = r.simulatedDamping_N_s_per_m;
  dp.maxContinuousForce_N = r.simulatedMaxForce_N;
  HandScript hand;
  hand.drive = HandScript::Drive::Position;
  hand.handStiffness_N_per_m = r.handStiffness_N_per_m;
  hand.handDamping_N_s_per_m = r.handDamping_N_s_per_m;
  if (r.hand && !r.hand->empty())
  {
    dp.initialPosition_Device_mm = r.hand->firstPosition_Device_mm();
    // The lambda shares the track (read-only): the request may be dropped after the build.
    std::shared_ptr<const HandTrack> track = r.hand;
    const double pressure = r.handPressure;
    hand.trajectory = [track, pressure](double time_s, HandSample& h)
    {
      track->at(time_s, h.position_Device_mm, h.velocity_Device_mm_per_s);
      h.pressure = pressure;
    };
  }
  auto device = std::make_unique<SimulatedDevice>(dp);
  device->setHandScript(hand);
  return device;
}
} // namespace

BuiltDevice buildDevice(const DeviceRequest& r)
{
  BuiltDevice built;
  if (!(r.maxForce_N > 0.0) || !std::isfinite(r.maxForce_N))
  {
    built.error = "the force limit must be a positive number of newtons";
    return built;
  }
  std::unique_ptr<HapticDevice> inner;
  switch (r.kind)
  {
    case DeviceKind::Simulated:
    {
      auto simulated = buildSimulated(r);
      built.simulated = simulated.get();
      inner = std::move(simulated);
      break;
    }
    case DeviceKind::Pointer:
    {
      auto pointer = std::make_unique<PointerDevice>();
      built.pointer = pointer.get();
      inner = std::move(pointer);
      break;
    }
    case DeviceKind::Replay:
    {
      ReplayDeviceParameters rp;
      rp.clock = ReplayDeviceParameters::Clock::RealTime;
      auto replay = std::make_unique<ReplayDevice>(rp);
      std::string error;
      if (r.replayFile.empty() || !replay->loadCsv(r.replayFile, error))
      {
        built.error =
          "replay device: " + (r.replayFile.empty() ? std::string("no replay file") : error);
        return built;
      }
      inner = std::move(replay);
      break;
    }
    case DeviceKind::Hid:
    {
      if (r.hidPath.empty())
      {
        built.error = "HID device: no device path";
        return built;
      }
      inner = std::make_unique<HidPidDevice>(std::make_shared<HidapiTransport>(), r.hidPath);
      break;
    }
    default:
      built.error = "unknown device kind";
      return built;
  }

  SafeHapticDeviceParameters sp;
  sp.filter.maxForce_N = r.maxForce_N;
  if (r.offline && built.simulated)
  {
    // Simulated time drives the slew limit; no watchdog thread between offline runs.
    SimulatedDevice* simulated = built.simulated;
    sp.watchdogThread = false;
    sp.watchdogTimeout_s = 0.0;
    sp.autoReopen = false;
    sp.clock_s = [simulated]() { return simulated->time_s(); };
  }
  auto device = std::make_shared<SafeHapticDevice>(std::move(inner), sp);
  if (device->open() != DeviceStatus::Ok)
  {
    built.error = std::string("the device did not open: ") + device->lastError();
    built.pointer = nullptr;
    built.simulated = nullptr;
    return built;
  }
  built.device = std::move(device);
  return built;
}

} // namespace vtouch

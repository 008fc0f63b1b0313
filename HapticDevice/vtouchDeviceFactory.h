// Builds the device a session asks for — simulated handle (with a scripted hand), the mouse
// (pseudo-haptics), a replayed recording or a HID PID device — wrapped in the SafeHapticDevice
// (force clamp, slew limit, watchdog) and opened. Hosts (the VTK facade, a Slicer adapter, tools)
// describe the device with a DeviceRequest instead of constructing drivers themselves.
#pragma once

#include "vtouchHandTrack.h"
#include "vtouchVector.h"

#include <memory>
#include <string>

namespace vtouch
{

class PointerDevice;
class SafeHapticDevice;
class SimulatedDevice;

enum class DeviceKind : int
{
  Simulated = 0, ///< a mass-damper handle held by a scripted hand (deterministic offline)
  Pointer = 1,   ///< the mouse, with pseudo-haptic feedback
  Replay = 2,    ///< positions replayed from a CSV recording
  Hid = 3        ///< a HID PID force-feedback device (hidapi)
};

/// What to build. Units in the names; defaults are those of the VTK facade's properties.
struct DeviceRequest
{
  DeviceKind kind = DeviceKind::Simulated;
  /// Offline: the simulated device runs on a manual clock (the caller steps time), the safety
  /// wrapper's slew limit reads that clock, and there is no watchdog thread. Simulated only.
  bool offline = false;
  /// The safety wrapper's force limit, N. Default 3 N.
  double maxForce_N = 3.0;

  // --- Simulated ---
  double simulatedMass_kg = 0.05;
  double simulatedDamping_N_s_per_m = 0.5;
  double simulatedMaxForce_N = 3.0;
  /// The scripted hand's trajectory (device mm); null or empty: a hand that does nothing.
  std::shared_ptr<const HandTrack> hand;
  double handStiffness_N_per_m = 3000.0;
  double handDamping_N_s_per_m = 10.0;
  double handPressure = 1.0; ///< normalized [0, 1]
  // The handle starts where the hand's first sample is (the origin without a hand).

  // --- Replay ---
  std::string replayFile; ///< CSV: time_s, x_mm, y_mm[, pressure, buttons]

  // --- HID ---
  std::string hidPath; ///< the hidapi path (vesseltouch-devices lists them)
};

/// The opened device, or the reason there is none.
struct BuiltDevice
{
  std::shared_ptr<SafeHapticDevice> device; ///< opened; null on failure
  PointerDevice* pointer = nullptr;         ///< the mouse inside `device` (kind Pointer)
  SimulatedDevice* simulated = nullptr;     ///< the handle inside `device` (kind Simulated)
  std::string error;                        ///< why `device` is null ("" on success)
};

/// Builds, wraps and opens the requested device. Never throws for a bad request or a device that
/// will not open: the result then carries no device and says why.
BuiltDevice buildDevice(const DeviceRequest& request);

} // namespace vtouch

// Plain data exchanged with every haptic device: status codes, capabilities and sampled state.
// Units are in the field names; the device frame is the device's own (x right, y up, z toward the
// user when sensed), in millimetres.
#pragma once

#include "vtouchVector.h"

#include <cstdint>

namespace vtouch
{

/// Result of every device call. Nothing in the device layer throws from read()/write().
enum class DeviceStatus : std::uint8_t
{
  Ok = 0,
  NotOpen,         ///< open() was not called or failed
  Disconnected,    ///< the device went away (unplugged); reopen after re-plug
  Unsupported,     ///< the device cannot do this (e.g. force on a position-only joystick)
  InvalidArgument, ///< NaN/Inf or otherwise unusable input (the device was commanded zero force)
  IoError,         ///< a transport read/write failed
  Timeout,         ///< no data in time
  Fault            ///< safety fault (watchdog, limit); force is zero until cleared
};

const char* toString(DeviceStatus status);

/// What a device can sense and render. Filled by open(); constant while open.
struct DeviceCapabilities
{
  static constexpr int kNameLength = 128;
  char name[kNameLength] = {};            ///< human-readable product name (NUL-terminated)
  std::uint16_t vendorId = 0;             ///< USB vendor id, 0 when not a USB device
  std::uint16_t productId = 0;            ///< USB product id, 0 when not a USB device
  int sensedDof = 2;                      ///< position axes sensed (2: x,y; 3: x,y,z)
  int actuatedDof = 2;                    ///< force axes rendered (0: input only)
  Vec3 workspace_mm{ 100.0, 100.0, 0.0 }; ///< extent of the reachable box, per axis
  double maxContinuousForce_N = 0.0;      ///< largest force the device may hold indefinitely
  double maxStiffness_N_per_m = 0.0;      ///< largest stable stiffness at 1 kHz
  double maxUpdateRate_Hz = 1000.0;       ///< fastest useful write rate
  bool hasPressure = false;               ///< a pressure or z input feeds the force zones
  /// Smallest position change the sensor resolves (encoder count, quantization or noise floor),
  /// mm; 0 when unknown. Sets z_max of the change-of-height estimate (Hayward & Yi, App. A).
  double positionResolution_mm = 0.0;
  int buttonCount = 0; ///< number of buttons reported in DeviceState::buttons
};

/// How a device maps its raw absolute axes to millimetres while it is open, as it applies it:
/// per axis, raw readings rawMinimum..rawMaximum map linearly onto minimum_mm..maximum_mm (an
/// inverted axis has minimum_mm > maximum_mm). axisCount 0: the device has no raw-axis
/// calibration (simulated handle, mouse pointer, replay, HID devices with relative axes).
struct DeviceAxisCalibration
{
  struct Axis
  {
    double rawMinimum = 0.0; ///< raw reading (device units, e.g. HID logical value) at one end
    double rawMaximum = 0.0; ///< raw reading at the other end
    double minimum_mm = 0.0; ///< position at rawMinimum, mm (device frame)
    double maximum_mm = 0.0; ///< position at rawMaximum, mm (device frame)
  };
  static constexpr int kMaxAxes = 3;
  int axisCount = 0; ///< axes calibrated: 0 (none), 2 (x, y) or 3
  Axis axes[kMaxAxes];
};

/// One timestamped sample of the device, in the device frame.
struct DeviceState
{
  double timestamp_s = 0.0;      ///< steady-clock time of the sample, seconds
  Vec3 position_Device_mm;       ///< handle position; z is 0 when not sensed
  Vec3 velocity_Device_mm_per_s; ///< estimated from a fixed-size history (never allocates)
  double pressure = 0.0;         ///< normalized pressure/z in [0, 1]; 0 when not sensed
  std::uint32_t buttons = 0;     ///< bit i set when button i is down
};

} // namespace vtouch

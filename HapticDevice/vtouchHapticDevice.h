// The one interface the haptic loop talks to. Every driver (HID PID, simulated, replay, pointer)
// implements it in its own file.
#pragma once

#include "vtouchDeviceTypes.h"

namespace vtouch
{

/// A 2-DOF (or richer) position input with 2D force output.
///
/// Threading: open()/close() are called from a control thread; read()/write() from the haptic
/// thread at up to 10 kHz. read()/write() never allocate, never hold a lock across I/O, never log
/// and never throw: they return a status, and lastError() tells why afterwards.
class HapticDevice
{
public:
  virtual ~HapticDevice() = default;

  HapticDevice() = default;
  HapticDevice(const HapticDevice&) = delete;
  HapticDevice& operator=(const HapticDevice&) = delete;

  /// Connects, queries capabilities and readies force output (forces start at zero).
  virtual DeviceStatus open() = 0;
  /// Commands zero force, stops effects, disables actuators and releases the device. Idempotent.
  virtual void close() = 0;
  virtual bool isOpen() const = 0;

  /// Valid after a successful open().
  virtual const DeviceCapabilities& capabilities() const = 0;
  /// The raw-axis calibration the open device applies (valid after a successful open()). Devices
  /// that read no raw axes have none: the default, axisCount 0.
  virtual DeviceAxisCalibration axisCalibration() const { return DeviceAxisCalibration(); }

  /// Newest sample, without blocking. On failure `state` is left unchanged.
  virtual DeviceStatus read(DeviceState& state) = 0;

  /// Commands a force in newtons in the device frame (z ignored by 2-DOF devices).
  virtual DeviceStatus write(const Vec3& force_Device_N) = 0;

  /// Why the last call failed, as a NUL-terminated string owned by the device (never null).
  virtual const char* lastError() const = 0;
};

} // namespace vtouch

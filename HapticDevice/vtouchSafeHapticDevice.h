// Safety decorator around any device: force filter, watchdog thread, faults, re-plug detection.
#pragma once

#include "vtouchForceSafetyFilter.h"
#include "vtouchHapticDevice.h"
#include "vtouchSafetyFault.h"

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <thread>

namespace vtouch
{

/// Parameters of a SafeHapticDevice.
struct SafeHapticDeviceParameters
{
  /// Clamp, slew and engage settings (maxForce_N is further limited by the device capabilities).
  ForceSafetyParameters filter;
  /// The watchdog zeroes the force and latches SafetyFault::Watchdog when no write() arrived for
  /// this long, s. Default 0.030 s. 0 disables the watchdog.
  double watchdogTimeout_s = 0.030;
  /// Run the watchdog (and auto-reopen) on an owned thread. Default true. When false, the owner
  /// calls pollWatchdog() itself (deterministic offline sessions and tests).
  bool watchdogThread = true;
  /// Try to reopen a disconnected device (re-plug detection). Default true.
  bool autoReopen = true;
  /// Interval between reopen attempts, s. Default 0.25 s.
  double reopenInterval_s = 0.25;
  /// Time source in seconds (steady clock when empty). Called from write() and the watchdog, so it
  /// must be thread-safe and must not allocate.
  std::function<double()> clock_s;
};

/// Wraps a device and makes it safe to drive from a haptic loop.
///
/// - write(): NaN/Inf -> zero force (InvalidArgument, fault NonFiniteForce recorded); engage only
///   after a quiet command; clamp; slew limit. While a fault is latched, zero is sent and Fault is
///   returned until clearFault().
/// - Watchdog: no write() within the timeout -> zero force and SafetyFault::Watchdog.
/// - A failed read/write -> zero force and DeviceError; Disconnected -> Disconnected, then the
///   device is reopened when it comes back (reopenCount() increments) and forces re-engage softly.
///
/// Threading: read()/write() from the haptic thread; open()/close()/clearFault() from a control
/// thread; fault() from anywhere. The haptic thread and the watchdog share the inner device through
/// a try-acquire flag, never a blocking lock: neither ever waits for the other's I/O.
class SafeHapticDevice : public HapticDevice
{
public:
  explicit SafeHapticDevice(std::unique_ptr<HapticDevice> inner,
    SafeHapticDeviceParameters parameters = SafeHapticDeviceParameters{});
  /// Stops the watchdog thread (atomic flag, then join) and closes the device.
  ~SafeHapticDevice() override;

  DeviceStatus open() override;
  void close() override;
  bool isOpen() const override;
  const DeviceCapabilities& capabilities() const override { return this->Inner->capabilities(); }
  DeviceAxisCalibration axisCalibration() const override { return this->Inner->axisCalibration(); }
  DeviceStatus read(DeviceState& state) override;
  DeviceStatus write(const Vec3& force_Device_N) override;
  /// A static string (thread-safe); the inner device's reason when the fault came from it.
  const char* lastError() const override { return this->LastError.load(); }

  /// The latched fault, lock-free.
  SafetyFault fault() const { return this->Fault.load(); }
  /// The last non-finite command seen (not latched: the next finite command re-engages softly).
  std::uint64_t nonFiniteCount() const { return this->NonFiniteCount.load(); }
  /// Clears a latched fault (not Disconnected while the device is still gone). Forces re-engage
  /// through the quiet gate. Returns true when cleared.
  bool clearFault();
  /// Times the device was reopened after a disconnection.
  std::uint32_t reopenCount() const { return this->ReopenCount.load(); }
  /// Times the watchdog fired.
  std::uint32_t watchdogTrips() const { return this->WatchdogTrips.load(); }
  /// The force last sent to the device, N (after the filter).
  Vec3 lastSentForce_N() const;

  /// One watchdog pass at time `now_s` (what the thread does every few ms). Returns true when it
  /// zeroed the force. Call it yourself when parameters.watchdogThread is false.
  bool pollWatchdog(double now_s);

  HapticDevice& inner() { return *this->Inner; }
  const SafeHapticDeviceParameters& parameters() const { return this->Parameters; }

private:
  double now_s() const;
  bool tryAcquireIo();
  void releaseIo();
  void latch(SafetyFault fault, const char* reason);
  void tryReopen(double now_s);
  void watchdogLoop();
  void startThread();
  void stopThread();

  std::unique_ptr<HapticDevice> Inner;
  SafeHapticDeviceParameters Parameters;

  // Haptic-thread state (only touched while holding IoBusy).
  ForceSafetyFilter Filter;
  double LastTick_s = -1.0;

  std::atomic<bool> IoBusy{ false };
  std::atomic<bool> Armed{ false }; // open and at least one write since open/clear
  std::atomic<bool> IsOpenFlag{ false };
  std::atomic<bool> ResetFilter{ false };
  std::atomic<bool> PendingZero{ false };
  std::atomic<SafetyFault> Fault{ SafetyFault::None };
  std::atomic<const char*> LastError{ "" };
  std::atomic<double> LastWrite_s{ 0.0 };
  std::atomic<double> LastReopenAttempt_s{ -1e300 };
  std::atomic<std::uint64_t> NonFiniteCount{ 0 };
  std::atomic<std::uint32_t> ReopenCount{ 0 };
  std::atomic<std::uint32_t> WatchdogTrips{ 0 };
  std::atomic<double> SentX{ 0.0 }, SentY{ 0.0 }, SentZ{ 0.0 };

  std::mutex ControlMutex; // open/close/reopen: control plane only, never taken by read()/write()
  std::thread Watchdog;
  std::atomic<bool> Stop{ false };
  std::mutex WakeMutex;
  std::condition_variable Wake;
};

} // namespace vtouch

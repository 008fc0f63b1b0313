// A device for people with no haptic hardware: the host's mouse moves a cursor, and forces are
// rendered as pseudo-haptics by modulating the cursor's control/display gain.
//
// Lécuyer A., Coquillart S., Kheddar A., Richard P., Coiffet P. (2000), "Pseudo-haptic feedback:
// can isometric input devices simulate force feedback?", Proc. IEEE Virtual Reality 2000, 83-90.
// A cursor that slows down where a force resists the motion is perceived as friction or a slope
// to climb; one that speeds up where the force assists, as descending.
#pragma once

#include "vtouchHapticDevice.h"
#include "vtouchSeqLock.h"
#include "vtouchVelocityEstimator.h"

#include <atomic>
#include <cstdint>
#include <mutex>

namespace vtouch
{

/// Parameters of a PointerDevice.
struct PointerDeviceParameters
{
  /// Cursor box, mm (device frame centred on 0). Default 160 x 120.
  Vec2 workspace_mm{ 160.0, 120.0 };
  /// Gain change per newton of force along the motion, 1/N: gain = 1 + k * (F . direction).
  /// Default 0.3 /N: a 2 N force against the motion moves the cursor at 0.4x the mouse speed.
  double gainPerNewton_per_N = 0.3;
  /// Gain bounds. Defaults 0.2 (never freezes) and 2.0.
  double minimumGain = 0.2;
  double maximumGain = 2.0;
  /// Pressure added per wheel step. Default 0.1.
  double pressurePerWheelStep = 0.1;
  /// Virtual force limit reported in the capabilities, N. Default 3.
  double maxContinuousForce_N = 3.0;
  /// Position resolution reported in the capabilities, mm: one screen pixel of the mouse at the
  /// view binding's default 4 px/mm. Default 0.25 mm.
  double positionResolution_mm = 0.25;
};

/// The host (GUI thread) feeds the mouse; the haptic thread reads the displayed cursor and writes
/// forces; the GUI reads back the cursor and the force to draw them. Host setters and getters are
/// thread-safe; read()/write() belong to the haptic thread and never block on the host.
class PointerDevice : public HapticDevice
{
public:
  explicit PointerDevice(const PointerDeviceParameters& parameters = PointerDeviceParameters{});

  // --- Host side (any thread) ---
  /// Mouse position mapped into the device frame by the view binding, mm.
  void setPointerPosition(const Vec2& pointer_Device_mm);
  /// Pressure while a modifier (e.g. Shift) is held: 1 when pressed. Overrides the wheel level.
  void setModifierPressed(bool pressed);
  /// Mouse wheel: each step adds pressurePerWheelStep (negative steps remove), clamped to [0, 1].
  void addWheelSteps(int steps);
  /// Mouse buttons, bit i for button i (i < kButtonCount). Every press and release edge is
  /// latched and counted here, so a click shorter than one haptic tick is still seen by read():
  /// read() replays the edges in order, one per read (a press and a release within one tick read
  /// as "down" at one tick and "up" at the next).
  void setButtons(std::uint32_t buttons);
  /// Presses of `button` seen by the host since construction (0 for buttons >= kButtonCount).
  std::uint32_t pressCount(int button) const;
  /// Presses of `button` delivered by read() so far (the rest are still latched).
  std::uint32_t deliveredPressCount(int button) const;
  static constexpr int kButtonCount = 8;
  /// Puts the cursor back under the pointer (e.g. when the pointer re-enters the view).
  void recenter();
  /// The cursor to draw, mm (device frame).
  Vec2 displayedCursor_Device_mm() const;
  /// The last force written, N, for an on-screen arrow.
  Vec3 displayedForce_Device_N() const;
  /// The control/display gain used at the last read().
  double currentGain() const { return this->Displayed.load().gain; }

  // --- HapticDevice (haptic thread) ---
  DeviceStatus open() override;
  void close() override;
  bool isOpen() const override { return this->Open.load(); }
  const DeviceCapabilities& capabilities() const override { return this->Capabilities; }
  /// The displayed cursor is the position: the haptic loop must feel what the user sees.
  DeviceStatus read(DeviceState& state) override;
  DeviceStatus write(const Vec3& force_Device_N) override;
  const char* lastError() const override { return this->LastError; }

private:
  /// Host -> haptic: what the GUI thread last said about the mouse, published whole.
  struct HostInput
  {
    Vec2 pointer_mm;
    double wheelPressure = 0.0;
    bool modifier = false;
    std::uint64_t recenter = 0; ///< recenter() requests so far
  };
  /// Haptic -> host: what the GUI draws, published whole after each read() and write().
  struct DisplayedState
  {
    Vec2 cursor_mm;
    Vec3 force_N;
    double gain = 1.0;
  };
  /// Host side: changes the shadow copy under HostMutex and publishes it.
  template<typename Change>
  void publishHost(Change change);
  /// Haptic side: publishes the cursor, force and gain of this tick.
  void publishDisplayed();
  /// Haptic thread: the button state to report, replaying at most one latched edge per button.
  std::uint32_t replayButtons();

  PointerDeviceParameters Parameters;
  DeviceCapabilities Capabilities;
  std::atomic<bool> Open{ false };
  const char* LastError = "";

  // Host -> haptic. Writers are serialized by HostMutex (the SeqLock's single-writer rule); the
  // haptic thread reads without blocking and never sees a torn pointer position.
  std::mutex HostMutex;
  HostInput HostShadow;          // under HostMutex
  std::uint32_t HostButtons = 0; // under HostMutex: the host's last button state (edges)
  SeqLock<HostInput> Host;
  // Button edges are counters, not a snapshot: a press and a release between two reads both count.
  std::atomic<std::uint32_t> Presses[kButtonCount] = {};
  std::atomic<std::uint32_t> Releases[kButtonCount] = {};
  std::atomic<std::uint32_t> DeliveredPresses[kButtonCount] = {};

  // Haptic -> host (single writer: whichever thread drives read()/write(), one at a time).
  SeqLock<DisplayedState> Displayed;

  // Haptic thread only.
  Vec2 Cursor_mm;
  Vec2 LastPointer_mm;
  std::uint64_t SeenRecenter = 0;
  std::uint32_t ReportedButtons = 0;
  std::uint32_t SeenReleases[kButtonCount] = {};
  Vec3 Force_N;
  double Gain = 1.0;
  VelocityEstimator Velocity;
};

} // namespace vtouch

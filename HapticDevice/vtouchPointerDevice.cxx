#include "vtouchPointerDevice.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <thread>

namespace vtouch
{

namespace
{
double steadyNow_s()
{
  using namespace std::chrono;
  return duration<double>(steady_clock::now().time_since_epoch()).count();
}
} // namespace

PointerDevice::PointerDevice(const PointerDeviceParameters& parameters)
  : Parameters(parameters)
{
  std::snprintf(this->Capabilities.name,
    sizeof(this->Capabilities.name),
    "%s",
    "VesselTouch pointer (pseudo-haptic)");
  this->Capabilities.sensedDof = 2;
  this->Capabilities.actuatedDof = 2;
  this->Capabilities.workspace_mm =
    Vec3{ parameters.workspace_mm.x, parameters.workspace_mm.y, 0.0 };
  this->Capabilities.maxContinuousForce_N = parameters.maxContinuousForce_N;
  this->Capabilities.maxStiffness_N_per_m = 1000.0;
  this->Capabilities.maxUpdateRate_Hz = 10000.0;
  this->Capabilities.hasPressure = true;
  this->Capabilities.positionResolution_mm = parameters.positionResolution_mm;
  this->Capabilities.buttonCount = 3;
}

void PointerDevice::setPointerPosition(const Vec2& pointer_Device_mm)
{
  if (!pointer_Device_mm.isFinite())
  {
    return;
  }
  std::lock_guard<std::mutex> lock(this->HostMutex);
  this->HostSequence.fetch_add(1, std::memory_order_acq_rel); // odd: writing
  this->PointerX.store(pointer_Device_mm.x, std::memory_order_relaxed);
  this->PointerY.store(pointer_Device_mm.y, std::memory_order_relaxed);
  this->HostSequence.fetch_add(1, std::memory_order_release); // even: consistent
}

void PointerDevice::setModifierPressed(bool pressed)
{
  this->Modifier.store(pressed);
}

void PointerDevice::addWheelSteps(int steps)
{
  std::lock_guard<std::mutex> lock(this->HostMutex);
  const double p = this->WheelPressure.load() + steps * this->Parameters.pressurePerWheelStep;
  this->WheelPressure.store(std::clamp(p, 0.0, 1.0));
}

void PointerDevice::setButtons(std::uint32_t buttons)
{
  std::lock_guard<std::mutex> lock(this->HostMutex);
  const std::uint32_t changed = buttons ^ this->HostButtons;
  for (int b = 0; b < kButtonCount; ++b)
  {
    const std::uint32_t bit = 1u << b;
    if (changed & bit)
    {
      // Counts, not only the state: a press and a release between two reads are both kept
      // (issue 20: a click shorter than one tick was lost when only the state was kept).
      std::atomic<std::uint32_t>& counter = (buttons & bit) ? this->Presses[b] : this->Releases[b];
      counter.fetch_add(1, std::memory_order_release);
    }
  }
  this->HostButtons = buttons;
}

std::uint32_t PointerDevice::pressCount(int button) const
{
  return (button >= 0 && button < kButtonCount)
           ? this->Presses[button].load(std::memory_order_acquire)
           : 0u;
}

std::uint32_t PointerDevice::deliveredPressCount(int button) const
{
  return (button >= 0 && button < kButtonCount)
           ? this->DeliveredPresses[button].load(std::memory_order_acquire)
           : 0u;
}

std::uint32_t PointerDevice::replayButtons()
{
  // The edges of one button alternate (press, release, press, ...). Each read moves the reported
  // state by at most one edge toward the host's, so every latched press is seen by one read at
  // least, and a double click between two reads reads down, up, down, up over four reads.
  for (int b = 0; b < kButtonCount; ++b)
  {
    const std::uint32_t bit = 1u << b;
    if (this->ReportedButtons & bit)
    {
      if (this->Releases[b].load(std::memory_order_acquire) != this->SeenReleases[b])
      {
        ++this->SeenReleases[b];
        this->ReportedButtons &= ~bit;
      }
    }
    else
    {
      const std::uint32_t delivered = this->DeliveredPresses[b].load(std::memory_order_relaxed);
      if (this->Presses[b].load(std::memory_order_acquire) != delivered)
      {
        this->DeliveredPresses[b].store(delivered + 1, std::memory_order_release);
        this->ReportedButtons |= bit;
      }
    }
  }
  return this->ReportedButtons;
}

void PointerDevice::recenter()
{
  this->RecenterRequests.fetch_add(1);
}

Vec2 PointerDevice::displayedCursor_Device_mm() const
{
  return Vec2{ this->CursorX.load(std::memory_order_relaxed),
    this->CursorY.load(std::memory_order_relaxed) };
}

Vec3 PointerDevice::displayedForce_Device_N() const
{
  return Vec3{ this->ForceX.load(std::memory_order_relaxed),
    this->ForceY.load(std::memory_order_relaxed),
    this->ForceZ.load(std::memory_order_relaxed) };
}

PointerDevice::HostInput PointerDevice::loadHost() const
{
  HostInput in;
  // Seqlock read: retry while a write is in progress or happened during the copy. The writer
  // holds the sequence odd for a handful of stores, so this never spins for long.
  for (int attempt = 0; attempt < 1000; ++attempt)
  {
    const std::uint32_t before = this->HostSequence.load(std::memory_order_acquire);
    if (before & 1u)
    {
      std::this_thread::yield();
      continue;
    }
    // Acquire loads keep the re-check of the sequence after the data (no fence: TSAN-friendly).
    in.pointer_mm = Vec2{ this->PointerX.load(std::memory_order_acquire),
      this->PointerY.load(std::memory_order_acquire) };
    if (this->HostSequence.load(std::memory_order_relaxed) == before)
    {
      break;
    }
  }
  in.pressure = this->Modifier.load() ? 1.0 : this->WheelPressure.load();
  in.recenter = this->RecenterRequests.load();
  return in;
}

DeviceStatus PointerDevice::open()
{
  const HostInput in = this->loadHost();
  this->Cursor_mm = in.pointer_mm;
  this->LastPointer_mm = in.pointer_mm;
  this->SeenRecenter = in.recenter;
  {
    // Edges latched before open() belong to no session: start from the host's current state.
    std::lock_guard<std::mutex> lock(this->HostMutex);
    this->ReportedButtons = this->HostButtons;
    for (int b = 0; b < kButtonCount; ++b)
    {
      this->DeliveredPresses[b].store(this->Presses[b].load());
      this->SeenReleases[b] = this->Releases[b].load();
    }
  }
  this->Force_N = Vec3{};
  this->Velocity.reset();
  this->CursorX.store(this->Cursor_mm.x);
  this->CursorY.store(this->Cursor_mm.y);
  this->ForceX.store(0.0);
  this->ForceY.store(0.0);
  this->ForceZ.store(0.0);
  this->Gain.store(1.0);
  this->LastError = "";
  this->Open.store(true);
  return DeviceStatus::Ok;
}

void PointerDevice::close()
{
  this->Open.store(false);
  this->ForceX.store(0.0);
  this->ForceY.store(0.0);
  this->ForceZ.store(0.0);
}

DeviceStatus PointerDevice::read(DeviceState& state)
{
  if (!this->Open.load())
  {
    this->LastError = "pointer device: not open";
    return DeviceStatus::NotOpen;
  }
  const HostInput in = this->loadHost();
  const PointerDeviceParameters& p = this->Parameters;
  if (in.recenter != this->SeenRecenter)
  {
    this->SeenRecenter = in.recenter;
    this->Cursor_mm = in.pointer_mm;
  }
  else
  {
    const Vec2 delta = in.pointer_mm - this->LastPointer_mm;
    const double distance = delta.norm();
    double gain = 1.0;
    if (distance > 0.0)
    {
      // Force along the motion: negative resists (cursor slows: heavier, climbing),
      // positive assists (cursor speeds up: descending).
      const double along_N = Vec2{ this->Force_N.x, this->Force_N.y }.dot(delta * (1.0 / distance));
      gain = std::clamp(1.0 + p.gainPerNewton_per_N * along_N, p.minimumGain, p.maximumGain);
    }
    this->Gain.store(gain, std::memory_order_relaxed);
    const Vec2 half = p.workspace_mm * 0.5;
    this->Cursor_mm = this->Cursor_mm + delta * gain;
    this->Cursor_mm.x = std::clamp(this->Cursor_mm.x, -half.x, half.x);
    this->Cursor_mm.y = std::clamp(this->Cursor_mm.y, -half.y, half.y);
  }
  this->LastPointer_mm = in.pointer_mm;
  this->CursorX.store(this->Cursor_mm.x, std::memory_order_relaxed);
  this->CursorY.store(this->Cursor_mm.y, std::memory_order_relaxed);

  DeviceState s;
  s.timestamp_s = steadyNow_s();
  s.position_Device_mm = Vec3{ this->Cursor_mm.x, this->Cursor_mm.y, 0.0 };
  s.pressure = in.pressure;
  s.buttons = this->replayButtons();
  this->Velocity.add(s.timestamp_s, s.position_Device_mm);
  s.velocity_Device_mm_per_s = this->Velocity.velocity_mm_per_s();
  state = s;
  return DeviceStatus::Ok;
}

DeviceStatus PointerDevice::write(const Vec3& force_Device_N)
{
  if (!this->Open.load())
  {
    this->LastError = "pointer device: not open";
    return DeviceStatus::NotOpen;
  }
  DeviceStatus status = DeviceStatus::Ok;
  Vec3 f = force_Device_N;
  if (!f.isFinite())
  {
    f = Vec3{};
    status = DeviceStatus::InvalidArgument;
    this->LastError = "pointer device: non-finite force (zero used)";
  }
  const double magnitude = f.norm();
  if (magnitude > this->Parameters.maxContinuousForce_N && magnitude > 0.0)
  {
    f = f * (this->Parameters.maxContinuousForce_N / magnitude);
  }
  this->Force_N = f;
  this->ForceX.store(f.x, std::memory_order_relaxed);
  this->ForceY.store(f.y, std::memory_order_relaxed);
  this->ForceZ.store(f.z, std::memory_order_relaxed);
  return status;
}

} // namespace vtouch

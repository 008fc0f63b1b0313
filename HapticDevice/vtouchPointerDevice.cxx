#include "vtouchPointerDevice.h"

#include "vtouchSteadyClock.h"

#include <algorithm>
#include <cstdio>

namespace vtouch
{

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
  this->publishHost([&](HostInput& in) { in.pointer_mm = pointer_Device_mm; });
}

template<typename Change>
void PointerDevice::publishHost(Change change)
{
  std::lock_guard<std::mutex> lock(this->HostMutex);
  change(this->HostShadow);
  this->Host.store(this->HostShadow);
}

void PointerDevice::setModifierPressed(bool pressed)
{
  this->publishHost([&](HostInput& in) { in.modifier = pressed; });
}

void PointerDevice::addWheelSteps(int steps)
{
  const double step = this->Parameters.pressurePerWheelStep;
  this->publishHost([&](HostInput& in)
    { in.wheelPressure = std::clamp(in.wheelPressure + steps * step, 0.0, 1.0); });
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
  this->publishHost([](HostInput& in) { ++in.recenter; });
}

Vec2 PointerDevice::displayedCursor_Device_mm() const
{
  return this->Displayed.load().cursor_mm;
}

Vec3 PointerDevice::displayedForce_Device_N() const
{
  return this->Displayed.load().force_N;
}

void PointerDevice::publishDisplayed()
{
  this->Displayed.store(DisplayedState{ this->Cursor_mm, this->Force_N, this->Gain });
}

DeviceStatus PointerDevice::open()
{
  const HostInput in = this->Host.load();
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
  this->Gain = 1.0;
  this->Velocity.reset();
  this->publishDisplayed();
  this->LastError = "";
  this->Open.store(true);
  return DeviceStatus::Ok;
}

void PointerDevice::close()
{
  this->Open.store(false);
  this->Force_N = Vec3{};
  this->publishDisplayed();
}

DeviceStatus PointerDevice::read(DeviceState& state)
{
  if (!this->Open.load())
  {
    this->LastError = "pointer device: not open";
    return DeviceStatus::NotOpen;
  }
  const HostInput in = this->Host.load(); // spins only while the GUI stores a few words
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
    this->Gain = gain;
    const Vec2 half = p.workspace_mm * 0.5;
    this->Cursor_mm = this->Cursor_mm + delta * gain;
    this->Cursor_mm.x = std::clamp(this->Cursor_mm.x, -half.x, half.x);
    this->Cursor_mm.y = std::clamp(this->Cursor_mm.y, -half.y, half.y);
  }
  this->LastPointer_mm = in.pointer_mm;
  this->publishDisplayed();

  DeviceState s;
  s.timestamp_s = steadyNow_s();
  s.position_Device_mm = Vec3{ this->Cursor_mm.x, this->Cursor_mm.y, 0.0 };
  s.pressure = in.modifier ? 1.0 : in.wheelPressure;
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
  this->publishDisplayed();
  return status;
}

} // namespace vtouch

#include "vtouchHidPidDevice.h"

#include "vtouchSteadyClock.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <thread>
#include <utility>

namespace vtouch
{

namespace
{
constexpr double kPi = 3.14159265358979323846;

} // namespace

HidPidDevice::HidPidDevice(std::shared_ptr<HidTransport> transport, std::string path)
  : Transport(std::move(transport))
  , Path(std::move(path))
  , PresetDirectory(DeviceCalibration::presetDirectory())
{
}

HidPidDevice::~HidPidDevice()
{
  this->close();
}

void HidPidDevice::setCalibration(const DeviceCalibration& calibration)
{
  this->Calibration = calibration;
  this->HaveCalibration = true;
}

DeviceStatus HidPidDevice::fail(DeviceStatus status, const char* format, const char* detail)
{
  std::snprintf(this->ErrorBuffer.data(), this->ErrorBuffer.size(), format, detail);
  this->LastError = this->ErrorBuffer.data();
  return status;
}

int HidPidDevice::send(HidReportBuffer& report)
{
  // hidapi wants the ID byte first; for devices without IDs a leading 0 that it does not send.
  return this->Transport->writeOutput(report.bytes.data(), report.bytes.size());
}

bool HidPidDevice::sendControl(const HidUsageSelector& control)
{
  if (!this->Layout.deviceControl.present || !control.valid())
  {
    return true; // optional on the device side
  }
  HidReportBuffer report = this->Reports.deviceControl(control);
  return this->send(report) >= 0;
}

bool HidPidDevice::loadBlock(Effect& effect)
{
  const HidPidLayout& l = this->Layout;
  HidReportBuffer create = this->Reports.createConstantForceEffect();
  if (this->Transport->sendFeature(create.bytes.data(), create.bytes.size()) < 0)
  {
    this->fail(DeviceStatus::IoError, "Create New Effect failed: %s", this->Transport->lastError());
    return false;
  }
  if (!l.blockLoad.present || !l.blBlockIndex.valid())
  {
    return true; // the device allocates silently: use the host index
  }
  for (int attempt = 0; attempt < this->Calibration.blockLoadRetries; ++attempt)
  {
    HidReportBuffer answer = this->Reports.blockLoadRequest();
    const int n = this->Transport->getFeature(answer.bytes.data(), answer.bytes.size());
    std::int64_t block = 0;
    const HidBlockLoadStatus status =
      n > 0 ? this->Reports.parseBlockLoad(answer.bytes.data(), static_cast<std::size_t>(n), block)
            : HidBlockLoadStatus::Unreadable;
    if (status == HidBlockLoadStatus::Success)
    {
      effect.block = block;
      return true;
    }
    if (status == HidBlockLoadStatus::Full)
    {
      this->fail(DeviceStatus::IoError, "%s", "the device's effect memory is full");
      return false;
    }
    // Firmwares answer Block Load a little after Create New Effect: poll again shortly.
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  this->fail(DeviceStatus::IoError, "%s", "Block Load never reported success");
  return false;
}

bool HidPidDevice::createEffect(int index, Effect& effect)
{
  const HidPidLayout& l = this->Layout;
  effect.block = index + 1; // host-managed blocks
  if (l.createNewEffect.present && l.cneConstantForce.valid() && !this->loadBlock(effect))
  {
    return false;
  }
  effect.setEffect =
    this->Reports.setEffect(effect.block, this->Mode, index, this->Calibration.infiniteDuration);
  effect.lastDirection = -1;
  if (this->send(effect.setEffect) < 0)
  {
    this->fail(DeviceStatus::IoError, "Set Effect failed: %s", this->Transport->lastError());
    return false;
  }
  effect.constantForce = this->Reports.constantForce(effect.block, 0);
  effect.lastMagnitude = 0;
  effect.lastSent_s = steadyNow_s();
  if (this->send(effect.constantForce) < 0)
  {
    this->fail(
      DeviceStatus::IoError, "Set Constant Force failed: %s", this->Transport->lastError());
    return false;
  }
  HidReportBuffer start = this->Reports.effectOperation(effect.block, true);
  if (this->send(start) < 0)
  {
    this->fail(
      DeviceStatus::IoError, "Effect Operation (start) failed: %s", this->Transport->lastError());
    return false;
  }
  return true;
}

DeviceStatus HidPidDevice::setUpForce()
{
  const HidPidLayout& l = this->Layout;
  const HidField& magnitude =
    this->Descriptor.fields()[static_cast<std::size_t>(l.cfMagnitude.field)];
  this->Mode = this->Calibration.effectMode;
  if (this->Mode == PidEffectMode::Auto)
  {
    this->Mode = magnitude.isSigned() && l.seAxisX.valid() && l.seAxisY.valid()
                   ? PidEffectMode::PerAxis
                 : l.seDirection0.valid() ? PidEffectMode::Polar
                                          : PidEffectMode::SingleX;
  }
  if (this->Mode == PidEffectMode::PerAxis && !(l.seAxisX.valid() && l.seAxisY.valid()))
  {
    this->Mode = l.seDirection0.valid() ? PidEffectMode::Polar : PidEffectMode::SingleX;
  }
  if (this->Mode == PidEffectMode::Polar && !l.seDirection0.valid())
  {
    // The missing-direction quirk: per-axis effects need no direction; else X alone.
    this->Mode = magnitude.isSigned() && l.seAxisX.valid() && l.seAxisY.valid()
                   ? PidEffectMode::PerAxis
                   : PidEffectMode::SingleX;
  }
  this->EffectCount = this->Mode == PidEffectMode::PerAxis ? 2 : 1;

  if (!this->sendControl(l.dcStopAllEffects))
  {
    return this->fail(
      DeviceStatus::IoError, "Device Control (stop all) failed: %s", this->Transport->lastError());
  }
  if (l.deviceGain.present && l.dgGain.valid())
  {
    HidReportBuffer gain = this->Reports.fullDeviceGain();
    if (this->send(gain) < 0)
    {
      return this->fail(
        DeviceStatus::IoError, "Device Gain failed: %s", this->Transport->lastError());
    }
  }
  for (int i = 0; i < this->EffectCount; ++i)
  {
    if (!this->createEffect(i, this->Effects[static_cast<std::size_t>(i)]))
    {
      return DeviceStatus::IoError;
    }
  }
  if (!this->sendControl(l.dcEnableActuators))
  {
    return this->fail(DeviceStatus::IoError,
      "Device Control (enable actuators) failed: %s",
      this->Transport->lastError());
  }
  return DeviceStatus::Ok;
}

DeviceStatus HidPidDevice::open()
{
  this->close();
  if (!this->Transport)
  {
    return this->fail(DeviceStatus::NotOpen, "%s", "no HID transport");
  }
  if (!this->Transport->open(this->Path))
  {
    return this->fail(
      this->Transport->disconnected() ? DeviceStatus::Disconnected : DeviceStatus::NotOpen,
      "%s",
      this->Transport->lastError());
  }
  std::vector<std::uint8_t> raw(HidReportDescriptor::kMaxDescriptorBytes);
  const int n = this->Transport->reportDescriptor(raw.data(), raw.size());
  if (n <= 0 || !this->Descriptor.parse(raw.data(), static_cast<std::size_t>(n)))
  {
    const DeviceStatus s = this->fail(DeviceStatus::IoError,
      "unusable report descriptor: %s",
      n <= 0 ? this->Transport->lastError() : this->Descriptor.error());
    this->Transport->close();
    return s;
  }
  this->Layout = HidPidLayout::find(this->Descriptor);
  this->ForceSupported = this->Layout.hasConstantForce();
  if (!this->Layout.hasPosition() && !this->ForceSupported)
  {
    this->Transport->close();
    return this->fail(DeviceStatus::Unsupported,
      "%s",
      "the device reports neither an X/Y position nor PID constant force");
  }
  this->Decoder.configure(this->Descriptor, this->Layout);

  HidDeviceInfo info;
  for (const HidDeviceInfo& candidate : this->Transport->enumerate())
  {
    if (candidate.path == this->Path)
    {
      info = candidate;
    }
  }
  const bool calibrated =
    this->HaveCalibration ||
    DeviceCalibration::findPreset(
      this->PresetDirectory, info.vendorId, info.productId, this->Calibration);
  const bool relative = this->Decoder.xField().isRelative();
  if (!calibrated)
  {
    this->Calibration = DeviceCalibration{};
    // No preset: when the descriptor gives both axes a physical length (HID 1.11, 6.2.2.7), the
    // workspace is their physical extent, so that the device frame is in real millimetres.
    const Vec2 physical =
      hidPhysicalWorkspace_mm(this->Decoder.xField(), this->Decoder.yField(), this->Calibration);
    if (!relative && physical.x > 0.0 && physical.y > 0.0)
    {
      this->Calibration.workspace_mm = physical;
    }
  }

  DeviceCapabilities caps;
  std::snprintf(caps.name,
    sizeof(caps.name),
    "%s",
    !info.product.empty()
      ? info.product.c_str()
      : (!this->Calibration.name.empty() ? this->Calibration.name.c_str() : "HID device"));
  caps.vendorId = info.vendorId;
  caps.productId = info.productId;
  caps.sensedDof = this->Layout.hasPosition() ? 2 : 0;
  caps.workspace_mm =
    Vec3{ this->Calibration.workspace_mm.x, this->Calibration.workspace_mm.y, 0.0 };
  caps.maxUpdateRate_Hz = this->Calibration.maxUpdateRate_Hz;
  caps.hasPressure = this->Decoder.hasPressure();
  caps.buttonCount = this->Decoder.buttonCount();
  // Sets z_max of the change-of-height estimate (Hayward & Yi, App. A): the descriptor's physical
  // resolution, else one count of the calibrated frame (Docs/HAPTICS.md).
  caps.positionResolution_mm = this->Layout.hasPosition()
                                 ? hidPositionResolution_mm(this->Decoder.xField(),
                                     this->Decoder.yField(),
                                     this->Calibration,
                                     relative,
                                     !calibrated,
                                     &this->ResolutionSource)
                                 : 0.0;

  this->InputBuffer.assign(
    std::max<std::size_t>(64, this->Descriptor.maxReportBytes(HidReportType::Input)), 0);
  this->HaveState = false;
  this->LastState = DeviceState{};
  this->RelativePosition_mm = Vec2{};
  this->Velocity.reset();
  this->IgnoredInputs = 0;
  this->EffectCount = 0;

  if (this->ForceSupported)
  {
    const DeviceStatus s = this->setUpForce();
    if (s != DeviceStatus::Ok)
    {
      this->Open = true; // so that close() stops whatever was started
      this->close();
      return s;
    }
    caps.actuatedDof = this->Mode == PidEffectMode::SingleX ? 1 : 2;
    caps.maxContinuousForce_N =
      std::min(this->Calibration.maxContinuousForce_N, this->Calibration.fullScaleForce_N);
    caps.maxStiffness_N_per_m = this->Calibration.maxStiffness_N_per_m;
  }
  else
  {
    caps.actuatedDof = 0;
    caps.maxContinuousForce_N = 0.0;
    caps.maxStiffness_N_per_m = 0.0;
  }
  this->Capabilities = caps;
  this->LastError = "";
  this->Open = true;
  return DeviceStatus::Ok;
}

void HidPidDevice::close()
{
  if (!this->Open)
  {
    return;
  }
  this->Open = false;
  if (this->ForceSupported && this->Transport->isOpen())
  {
    const HidPidLayout& l = this->Layout;
    for (int i = 0; i < this->EffectCount; ++i)
    {
      const std::int64_t block = this->Effects[static_cast<std::size_t>(i)].block;
      HidReportBuffer stop = this->Reports.effectOperation(block, false);
      this->send(stop);
      if (l.blockFree.present && l.bfBlockIndex.valid())
      {
        HidReportBuffer free = this->Reports.blockFree(block);
        this->send(free);
      }
    }
    this->sendControl(l.dcStopAllEffects);
    this->sendControl(l.dcDisableActuators);
  }
  this->EffectCount = 0;
  this->Transport->close();
}

DeviceAxisCalibration HidPidDevice::axisCalibration() const
{
  DeviceAxisCalibration result;
  const HidField& x = this->Decoder.xField();
  if (!this->Open || !this->Decoder.configured() || x.isRelative())
  {
    return result;
  }
  const DeviceCalibration& c = this->Calibration;
  const auto axis = [](double lo, double hi, const HidField& f, double extent, bool invert)
  {
    DeviceAxisCalibration::Axis a;
    const bool logical = !(hi != lo); // the same rule as toMillimetres()
    a.rawMinimum = logical ? static_cast<double>(f.logicalMinimum) : lo;
    a.rawMaximum = logical ? static_cast<double>(f.logicalMaximum) : hi;
    a.minimum_mm = (invert ? 0.5 : -0.5) * extent;
    a.maximum_mm = -a.minimum_mm;
    return a;
  };
  result.axisCount = 2;
  result.axes[0] = axis(c.rawMinimum.x, c.rawMaximum.x, x, c.workspace_mm.x, c.invertX);
  result.axes[1] =
    axis(c.rawMinimum.y, c.rawMaximum.y, this->Decoder.yField(), c.workspace_mm.y, c.invertY);
  return result;
}

Vec3 HidPidDevice::toMillimetres(const HidInputSample& sample)
{
  const DeviceCalibration& c = this->Calibration;
  Vec2 p;
  if (sample.relative)
  {
    const Vec2 delta{ static_cast<double>(sample.x) / c.countsPerMm,
      static_cast<double>(sample.y) / c.countsPerMm };
    const Vec2 half = c.workspace_mm * 0.5;
    this->RelativePosition_mm.x =
      std::clamp(this->RelativePosition_mm.x + (c.invertX ? -delta.x : delta.x), -half.x, half.x);
    this->RelativePosition_mm.y =
      std::clamp(this->RelativePosition_mm.y + (c.invertY ? -delta.y : delta.y), -half.y, half.y);
    p = this->RelativePosition_mm;
  }
  else
  {
    auto axis = [](double raw, double lo, double hi, const HidField& f, double extent, bool invert)
    {
      if (!(hi != lo))
      {
        lo = static_cast<double>(f.logicalMinimum);
        hi = static_cast<double>(f.logicalMaximum);
      }
      const double normalized = hi != lo ? (raw - lo) / (hi - lo) : 0.5;
      const double mm = (normalized - 0.5) * extent;
      return invert ? -mm : mm;
    };
    p.x = axis(static_cast<double>(sample.x),
      c.rawMinimum.x,
      c.rawMaximum.x,
      this->Decoder.xField(),
      c.workspace_mm.x,
      c.invertX);
    p.y = axis(static_cast<double>(sample.y),
      c.rawMinimum.y,
      c.rawMaximum.y,
      this->Decoder.yField(),
      c.workspace_mm.y,
      c.invertY);
  }
  return Vec3{ p.x, p.y, 0.0 };
}

DeviceStatus HidPidDevice::read(DeviceState& state)
{
  if (!this->Open)
  {
    this->LastError = "HID device: not open";
    return DeviceStatus::NotOpen;
  }
  if (!this->Decoder.configured())
  {
    this->LastError = "HID device: no position input (force-only device)";
    return DeviceStatus::Unsupported;
  }
  // Drain what is pending and keep the newest position report (bounded: never spin forever).
  bool fresh = false;
  HidInputSample newest;
  for (int i = 0; i < 64; ++i)
  {
    const int n = this->Transport->readInput(this->InputBuffer.data(), this->InputBuffer.size());
    if (n < 0)
    {
      this->LastError = this->Transport->disconnected() ? "HID device: disconnected"
                                                        : "HID device: input report read failed";
      return this->Transport->disconnected() ? DeviceStatus::Disconnected : DeviceStatus::IoError;
    }
    if (n == 0)
    {
      break;
    }
    HidInputSample sample;
    if (this->Decoder.decode(this->InputBuffer.data(), static_cast<std::size_t>(n), sample))
    {
      if (sample.relative && fresh)
      {
        // Deltas add up; keep every one of them.
        this->toMillimetres(newest);
      }
      newest = sample;
      fresh = true;
    }
    else
    {
      ++this->IgnoredInputs;
    }
  }
  if (fresh)
  {
    DeviceState s;
    s.timestamp_s = steadyNow_s();
    s.position_Device_mm = this->toMillimetres(newest);
    s.pressure = newest.pressure;
    s.buttons = newest.buttons;
    this->Velocity.add(s.timestamp_s, s.position_Device_mm);
    s.velocity_Device_mm_per_s = this->Velocity.velocity_mm_per_s();
    this->LastState = s;
    this->HaveState = true;
  }
  if (!this->HaveState)
  {
    this->LastError = "HID device: no input report yet";
    return DeviceStatus::Timeout;
  }
  state = this->LastState;
  return DeviceStatus::Ok;
}

DeviceStatus HidPidDevice::writeFailed()
{
  const bool gone = this->Transport->disconnected();
  this->LastError = gone ? "HID device: disconnected" : "HID device: output report write failed";
  return gone ? DeviceStatus::Disconnected : DeviceStatus::IoError;
}

DeviceStatus HidPidDevice::sendEffect(Effect& effect,
  std::int64_t magnitude,
  std::int64_t direction,
  double now)
{
  const bool keepAlive = now - effect.lastSent_s >= this->Calibration.keepAlive_s;
  if (direction >= 0 && direction != effect.lastDirection)
  {
    this->Reports.set(effect.setEffect, this->Layout.seDirection0, direction);
    if (this->send(effect.setEffect) < 0)
    {
      return this->writeFailed();
    }
    effect.lastDirection = direction;
  }
  if (magnitude != effect.lastMagnitude || keepAlive)
  {
    this->Reports.set(effect.constantForce, this->Layout.cfMagnitude, magnitude);
    if (this->send(effect.constantForce) < 0)
    {
      return this->writeFailed();
    }
    effect.lastMagnitude = magnitude;
    effect.lastSent_s = now;
  }
  return DeviceStatus::Ok;
}

DeviceStatus HidPidDevice::write(const Vec3& force_Device_N)
{
  if (!this->Open)
  {
    this->LastError = "HID device: not open";
    return DeviceStatus::NotOpen;
  }
  if (!this->ForceSupported)
  {
    this->LastError = "HID device: force output not supported (no PID constant-force reports)";
    return DeviceStatus::Unsupported;
  }
  Vec3 f = force_Device_N;
  DeviceStatus status = DeviceStatus::Ok;
  if (!f.isFinite())
  {
    f = Vec3{};
    status = DeviceStatus::InvalidArgument;
  }
  const DeviceCalibration& c = this->Calibration;
  // Device frame (x right, y up) -> HID frame of the axes.
  const double hx = (c.invertX ? -f.x : f.x) / c.fullScaleForce_N;
  const double hy = (c.invertY ? -f.y : f.y) / c.fullScaleForce_N;
  const double now = steadyNow_s();
  DeviceStatus sent = DeviceStatus::Ok;
  switch (this->Mode)
  {
    case PidEffectMode::PerAxis:
      sent = this->sendEffect(this->Effects[0], this->Reports.magnitude(hx), -1, now);
      if (sent == DeviceStatus::Ok)
      {
        sent = this->sendEffect(this->Effects[1], this->Reports.magnitude(hy), -1, now);
      }
      break;
    case PidEffectMode::Polar:
    {
      // DirectInput polar: 0 degrees toward -Y of the HID frame (away from the user), clockwise.
      const double magnitude = std::min(1.0, std::hypot(hx, hy));
      const double angle = magnitude > 0.0 ? std::atan2(hx, -hy) * 180.0 / kPi : 0.0;
      const std::int64_t direction = magnitude > 0.0
                                       ? this->Reports.direction(angle + c.directionOffset_deg)
                                       : this->Effects[0].lastDirection;
      sent = this->sendEffect(this->Effects[0], this->Reports.magnitude(magnitude), direction, now);
      break;
    }
    default:
    {
      // An unsigned magnitude cannot push left along a fixed direction: clamp at zero.
      const double fx = this->Reports.signedMagnitude() ? hx : std::max(0.0, hx);
      sent = this->sendEffect(this->Effects[0], this->Reports.magnitude(fx), -1, now);
      break;
    }
  }
  if (sent != DeviceStatus::Ok)
  {
    return sent;
  }
  if (status != DeviceStatus::Ok)
  {
    this->LastError = "HID device: non-finite force (zero force sent)";
  }
  return status;
}

} // namespace vtouch

// A HID device through a HidTransport: position from Generic Desktop X/Y, force through USB HID
// PID constant-force effects (PID 1.0). Devices without PID reports work as input only.
#pragma once

#include "vtouchDeviceCalibration.h"
#include "vtouchHapticDevice.h"
#include "vtouchHidInputDecoder.h"
#include "vtouchHidPidLayout.h"
#include "vtouchHidPidReports.h"
#include "vtouchHidReportDescriptor.h"
#include "vtouchHidTransport.h"
#include "vtouchHidUnits.h"
#include "vtouchVelocityEstimator.h"

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace vtouch
{

/// Drives one HID interface.
///
/// open(): fetches and parses the report descriptor, finds the PID reports by usage, loads the
/// calibration preset of the vendor/product id, then (force devices) stops all effects, sets the
/// device gain, creates one constant-force effect per axis (or one polar effect), each with
/// infinite duration and started, and enables the actuators.
/// write(): scales the force to each magnitude field's logical range and sends only what changed
/// (plus a keep-alive). read(): drains pending input reports and decodes the newest.
/// close(): stops the effects, frees them, stops all, disables actuators.
class HidPidDevice : public HapticDevice
{
public:
  /// `transport` is shared so that tests (and the CLI) can keep watching it; `path` as enumerated.
  HidPidDevice(std::shared_ptr<HidTransport> transport, std::string path);
  ~HidPidDevice() override;

  /// Uses this calibration instead of looking up a preset (call before open()).
  void setCalibration(const DeviceCalibration& calibration);
  /// Folder of presets to search (default DeviceCalibration::presetDirectory()).
  void setPresetDirectory(const std::string& directory) { this->PresetDirectory = directory; }

  DeviceStatus open() override;
  void close() override;
  bool isOpen() const override { return this->Open; }
  const DeviceCapabilities& capabilities() const override { return this->Capabilities; }
  /// x and y as toMillimetres() maps them: the preset's raw range (or the fields' logical range)
  /// onto the workspace, centred, inverted axes flipped. None for relative axes (mice).
  DeviceAxisCalibration axisCalibration() const override;
  DeviceStatus read(DeviceState& state) override;
  DeviceStatus write(const Vec3& force_Device_N) override;
  const char* lastError() const override { return this->LastError; }

  /// What open() found (valid after open()).
  const HidReportDescriptor& descriptor() const { return this->Descriptor; }
  const HidPidLayout& layout() const { return this->Layout; }
  const DeviceCalibration& calibration() const { return this->Calibration; }
  bool forceSupported() const { return this->ForceSupported; }
  PidEffectMode effectMode() const { return this->Mode; }
  int effectCount() const { return this->EffectCount; }
  /// Effect block index of effect `i` (as the device assigned it).
  std::int64_t effectBlockIndex(int i) const
  {
    return this->Effects[static_cast<std::size_t>(i)].block;
  }
  /// Reports dropped by read() because they were malformed or of another kind.
  std::uint64_t ignoredInputReports() const { return this->IgnoredInputs; }
  /// Where capabilities().positionResolution_mm came from (valid after open()).
  HidResolutionSource resolutionSource() const { return this->ResolutionSource; }

private:
  struct Effect
  {
    std::int64_t block = 0;
    HidReportBuffer setEffect;
    HidReportBuffer constantForce;
    std::int64_t lastMagnitude = 0;
    std::int64_t lastDirection = -1;
    double lastSent_s = -1.0;
  };

  DeviceStatus fail(DeviceStatus status, const char* format, const char* detail = "");
  int send(HidReportBuffer& report);
  bool sendControl(const HidUsageSelector& control);
  DeviceStatus setUpForce();
  bool loadBlock(Effect& effect);
  bool createEffect(int index, Effect& effect);
  DeviceStatus sendEffect(Effect& effect,
    std::int64_t magnitude,
    std::int64_t direction,
    double now);
  DeviceStatus writeFailed();
  Vec3 toMillimetres(const HidInputSample& sample);

  std::shared_ptr<HidTransport> Transport;
  std::string Path;
  std::string PresetDirectory;
  bool HaveCalibration = false;
  DeviceCalibration Calibration;
  HidResolutionSource ResolutionSource = HidResolutionSource::Calibration;
  DeviceCapabilities Capabilities;
  HidReportDescriptor Descriptor;
  HidPidLayout Layout;
  HidPidReports Reports{ this->Descriptor, this->Layout }; // refers to the two members above
  HidInputDecoder Decoder;
  bool Open = false;
  bool ForceSupported = false;
  PidEffectMode Mode = PidEffectMode::Auto;
  int EffectCount = 0;
  std::array<Effect, 2> Effects;
  std::vector<std::uint8_t> InputBuffer;
  DeviceState LastState;
  bool HaveState = false;
  Vec2 RelativePosition_mm;
  VelocityEstimator Velocity;
  std::uint64_t IgnoredInputs = 0;
  const char* LastError = "";
  std::array<char, 256> ErrorBuffer{};
};

} // namespace vtouch

// Where the PID force-feedback reports and fields of one device are, found by HID usage
// (USB HID PID 1.0, usage page 0x0F) and never by report ID, which differs per device.
#pragma once

#include "vtouchHidReportDescriptor.h"

#include <cstdint>
#include <vector>

namespace vtouch
{

/// Usages of the Physical Interface Device page (PID 1.0, section 5) and the few others we use.
namespace pid
{
constexpr std::uint16_t kPage = 0x0F;
constexpr std::uint32_t kSetEffectReport = hidUsage(kPage, 0x21);
constexpr std::uint32_t kEffectBlockIndex = hidUsage(kPage, 0x22);
constexpr std::uint32_t kEffectType = hidUsage(kPage, 0x25);
constexpr std::uint32_t kEtConstantForce = hidUsage(kPage, 0x26);
constexpr std::uint32_t kDuration = hidUsage(kPage, 0x50);
constexpr std::uint32_t kSamplePeriod = hidUsage(kPage, 0x51);
constexpr std::uint32_t kGain = hidUsage(kPage, 0x52);
constexpr std::uint32_t kTriggerButton = hidUsage(kPage, 0x53);
constexpr std::uint32_t kTriggerRepeatInterval = hidUsage(kPage, 0x54);
constexpr std::uint32_t kAxesEnable = hidUsage(kPage, 0x55);
constexpr std::uint32_t kDirectionEnable = hidUsage(kPage, 0x56);
constexpr std::uint32_t kDirection = hidUsage(kPage, 0x57);
constexpr std::uint32_t kMagnitude = hidUsage(kPage, 0x70);
constexpr std::uint32_t kSetConstantForceReport = hidUsage(kPage, 0x73);
constexpr std::uint32_t kEffectOperationReport = hidUsage(kPage, 0x77);
constexpr std::uint32_t kEffectOperation = hidUsage(kPage, 0x78);
constexpr std::uint32_t kOpEffectStart = hidUsage(kPage, 0x79);
constexpr std::uint32_t kOpEffectStartSolo = hidUsage(kPage, 0x7A);
constexpr std::uint32_t kOpEffectStop = hidUsage(kPage, 0x7B);
constexpr std::uint32_t kLoopCount = hidUsage(kPage, 0x7C);
constexpr std::uint32_t kDeviceGainReport = hidUsage(kPage, 0x7D);
constexpr std::uint32_t kDeviceGain = hidUsage(kPage, 0x7E);
constexpr std::uint32_t kPoolReport = hidUsage(kPage, 0x7F);
constexpr std::uint32_t kRamPoolSize = hidUsage(kPage, 0x80);
constexpr std::uint32_t kSimultaneousEffectsMax = hidUsage(kPage, 0x83);
constexpr std::uint32_t kBlockLoadReport = hidUsage(kPage, 0x89);
constexpr std::uint32_t kBlockLoadStatus = hidUsage(kPage, 0x8B);
constexpr std::uint32_t kBlockLoadSuccess = hidUsage(kPage, 0x8C);
constexpr std::uint32_t kBlockLoadFull = hidUsage(kPage, 0x8D);
constexpr std::uint32_t kBlockLoadError = hidUsage(kPage, 0x8E);
constexpr std::uint32_t kBlockFreeReport = hidUsage(kPage, 0x90);
constexpr std::uint32_t kDeviceControlReport = hidUsage(kPage, 0x95);
constexpr std::uint32_t kDeviceControl = hidUsage(kPage, 0x96);
constexpr std::uint32_t kDcEnableActuators = hidUsage(kPage, 0x97);
constexpr std::uint32_t kDcDisableActuators = hidUsage(kPage, 0x98);
constexpr std::uint32_t kDcStopAllEffects = hidUsage(kPage, 0x99);
constexpr std::uint32_t kDcDeviceReset = hidUsage(kPage, 0x9A);
constexpr std::uint32_t kStartDelay = hidUsage(kPage, 0xA7);
constexpr std::uint32_t kDeviceManagedPool = hidUsage(kPage, 0xA9);
constexpr std::uint32_t kCreateNewEffectReport = hidUsage(kPage, 0xAB);
constexpr std::uint32_t kRamPoolAvailable = hidUsage(kPage, 0xAC);

constexpr std::uint32_t kGenericDesktopX = hidUsage(0x01, 0x30);
constexpr std::uint32_t kGenericDesktopY = hidUsage(0x01, 0x31);
constexpr std::uint32_t kTipPressure = hidUsage(0x0D, 0x30);
constexpr std::uint16_t kButtonPage = 0x09;
} // namespace pid

/// One element of one field: where a value goes or comes from.
struct HidValueRef
{
  int field = -1;            ///< index in HidReportDescriptor::fields(), -1 when absent
  std::uint32_t element = 0; ///< element within the field
  bool valid() const { return this->field >= 0; }
};

/// Writing `value` into (field, element) selects a usage: for an array field the value is the
/// usage's index plus the logical minimum; for a variable (bit) field it is 1 in that usage's bit.
struct HidUsageSelector
{
  int field = -1;
  std::uint32_t element = 0;
  std::int64_t value = 0;
  bool valid() const { return this->field >= 0; }
};

/// A report located by the usage of its collection.
struct HidReportRef
{
  bool present = false;
  HidReportType type = HidReportType::Output;
  std::uint8_t reportId = 0;
  std::size_t bytes = 0; ///< whole report through hidapi, id byte included when used
};

/// Every report and field the HidPidDevice needs, found by usage.
struct HidPidLayout
{
  // Position input (Generic Desktop X/Y, Button page, Digitizer tip pressure).
  HidReportRef input;
  HidValueRef x, y, pressure;
  std::vector<HidValueRef> buttons; ///< button i (0-based) -> its element, at most 32

  // Set Effect (output).
  HidReportRef setEffect;
  HidValueRef seBlockIndex, seDuration, seTriggerRepeat, seSamplePeriod, seStartDelay, seGain,
    seTriggerButton, seAxisX, seAxisY, seDirectionEnable, seDirection0, seDirection1;
  HidUsageSelector seConstantForce; ///< Effect Type = ET Constant Force

  // Set Constant Force (output).
  HidReportRef setConstantForce;
  HidValueRef cfBlockIndex, cfMagnitude;

  // Effect Operation (output).
  HidReportRef effectOperation;
  HidValueRef eoBlockIndex, eoLoopCount;
  HidUsageSelector eoStart, eoStop;

  // Device Control (output); a selector array in some devices, a bit field in others.
  HidReportRef deviceControl;
  HidUsageSelector dcEnableActuators, dcDisableActuators, dcStopAllEffects, dcReset;

  // Device Gain (output).
  HidReportRef deviceGain;
  HidValueRef dgGain;

  // Block Free (output).
  HidReportRef blockFree;
  HidValueRef bfBlockIndex;

  // Create New Effect (feature, device-managed effect blocks).
  HidReportRef createNewEffect;
  HidUsageSelector cneConstantForce;

  // Block Load (feature, answers Create New Effect).
  HidReportRef blockLoad;
  HidValueRef blBlockIndex;
  HidUsageSelector blSuccess, blFull, blError;

  // PID Pool (feature).
  HidReportRef pool;
  HidValueRef ppSimultaneousEffectsMax;

  /// Position input usable (X and Y in one input report).
  bool hasPosition() const { return this->input.present && this->x.valid() && this->y.valid(); }
  /// Enough PID reports to play a constant force.
  bool hasConstantForce() const
  {
    return this->setEffect.present && this->seBlockIndex.valid() && this->seConstantForce.valid() &&
           this->setConstantForce.present && this->cfMagnitude.valid() &&
           this->effectOperation.present && this->eoStart.valid();
  }
  /// Any PID report at all (a PID device even if we cannot use it).
  bool hasAnyPidReport() const
  {
    return this->setEffect.present || this->setConstantForce.present ||
           this->effectOperation.present || this->deviceControl.present || this->pool.present;
  }

  /// Finds everything in a parsed descriptor. Never fails: absent parts are left invalid.
  static HidPidLayout find(const HidReportDescriptor& descriptor);
};

} // namespace vtouch

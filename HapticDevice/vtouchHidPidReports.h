// Builds the PID output and feature reports of one device from its layout: every byte placed by
// usage, every value scaled to its field's logical range.
#pragma once

#include "vtouchDeviceCalibration.h"
#include "vtouchHidPidLayout.h"
#include "vtouchHidReportDescriptor.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace vtouch
{

/// A report as it goes through hidapi: the ID byte first (0 for devices without report IDs, which
/// hidapi then does not send), then the payload. Allocated when built (open()), rewritten in place
/// while streaming.
struct HidReportBuffer
{
  std::vector<std::uint8_t> bytes;
  std::uint8_t* payload() { return this->bytes.data() + 1; }
  std::size_t payloadSize() const { return this->bytes.empty() ? 0 : this->bytes.size() - 1; }
};

/// What a Block Load feature report said.
enum class HidBlockLoadStatus : std::uint8_t
{
  Unreadable, ///< too short, or no status and no block index
  Pending,    ///< no success yet (some firmwares answer a moment later)
  Success,
  Full,
  Error
};

/// Report builder over a parsed descriptor and its layout (both must outlive it).
class HidPidReports
{
public:
  HidPidReports(const HidReportDescriptor& descriptor, const HidPidLayout& layout);

  /// A zeroed report of the given kind (empty when the device lacks it).
  HidReportBuffer make(const HidReportRef& ref) const;
  /// Writes a value / selects a usage; false when the field is absent or outside the report.
  bool set(HidReportBuffer& report, const HidValueRef& ref, std::int64_t value) const;
  bool select(HidReportBuffer& report, const HidUsageSelector& selector) const;

  /// Magnitude for a fraction of full scale in [-1, 1], rounded and clamped to the logical range.
  std::int64_t magnitude(double fraction) const;
  /// True when the magnitude field can carry a sign.
  bool signedMagnitude() const;
  /// Direction value for an angle in degrees (DirectInput polar: 0 = -Y of the HID frame,
  /// clockwise), wrapped into the logical range, which spans one turn.
  std::int64_t direction(double angle_deg) const;
  /// Raw "infinite duration": `quirk` >= 0 is used as is; -1 means all ones in the field.
  std::int64_t infiniteDuration(std::int64_t quirk) const;

  /// Set Effect for a constant force with infinite duration, full gain, no trigger button.
  /// `axis` selects the effect's axis in PerAxis mode (0 = X, 1 = Y).
  HidReportBuffer setEffect(std::int64_t block,
    PidEffectMode mode,
    int axis,
    std::int64_t infiniteDurationQuirk) const;
  HidReportBuffer constantForce(std::int64_t block, std::int64_t magnitude) const;
  /// Effect Operation: start (loop count 1) or stop (loop count 0).
  HidReportBuffer effectOperation(std::int64_t block, bool start) const;
  HidReportBuffer blockFree(std::int64_t block) const;
  HidReportBuffer deviceControl(const HidUsageSelector& control) const;
  /// Device Gain at the logical maximum.
  HidReportBuffer fullDeviceGain() const;
  /// Create New Effect (feature) of type constant force.
  HidReportBuffer createConstantForceEffect() const;
  /// A Block Load feature request (ID set, payload zero) to pass to getFeature().
  HidReportBuffer blockLoadRequest() const;
  /// Reads a Block Load answer of `size` bytes (as getFeature returned it).
  HidBlockLoadStatus parseBlockLoad(const std::uint8_t* report,
    std::size_t size,
    std::int64_t& block) const;

private:
  const HidField& field(int index) const
  {
    return this->Descriptor.fields()[static_cast<std::size_t>(index)];
  }

  const HidReportDescriptor& Descriptor;
  const HidPidLayout& Layout;
};

} // namespace vtouch

// Decodes position input reports (Generic Desktop X/Y, tip pressure, buttons) without allocating.
#pragma once

#include "vtouchHidField.h"
#include "vtouchHidPidLayout.h"

#include <array>
#include <cstddef>
#include <cstdint>

namespace vtouch
{

/// Raw values of one input report.
struct HidInputSample
{
  std::int64_t x = 0;        ///< raw X (logical units; a delta when relative)
  std::int64_t y = 0;        ///< raw Y
  bool relative = false;     ///< X/Y are deltas (mice)
  double pressure = 0.0;     ///< tip pressure normalized to [0, 1]; 0 when not sensed
  std::uint32_t buttons = 0; ///< bit i: button i+1 down
};

/// Keeps copies of the few fields it needs, so it outlives nothing and shares nothing: the haptic
/// thread owns it. Fuzzed together with the descriptor parser.
class HidInputDecoder
{
public:
  /// Takes the position report of `layout`. Returns false when the layout has no position.
  bool configure(const HidReportDescriptor& descriptor, const HidPidLayout& layout);

  /// Decodes one report as hidapi returns it (ID byte first when the device numbers reports).
  /// Returns false for another report ID, a report too short, or before configure().
  bool decode(const std::uint8_t* report, std::size_t size, HidInputSample& sample) const;

  bool configured() const { return this->Configured; }
  std::uint8_t reportId() const { return this->ReportId; }
  /// Logical ranges of X and Y, for calibration defaults.
  const HidField& xField() const { return this->X; }
  const HidField& yField() const { return this->Y; }
  int buttonCount() const { return this->ButtonCount; }
  bool hasPressure() const { return this->HasPressure; }

private:
  struct Element
  {
    HidField field;
    std::uint32_t element = 0;
  };
  bool Configured = false;
  bool UsesReportIds = false;
  std::uint8_t ReportId = 0;
  std::size_t PayloadBytes = 0;
  HidField X, Y;
  std::uint32_t XElement = 0, YElement = 0;
  bool HasPressure = false;
  Element Pressure;
  int ButtonCount = 0;
  std::array<Element, 32> Buttons{};
};

} // namespace vtouch

#include "vtouchHidInputDecoder.h"

#include <algorithm>

namespace vtouch
{

bool HidInputDecoder::configure(const HidReportDescriptor& descriptor, const HidPidLayout& layout)
{
  this->Configured = false;
  if (!layout.hasPosition())
  {
    return false;
  }
  const auto& fields = descriptor.fields();
  auto field = [&](const HidValueRef& ref) { return fields[static_cast<std::size_t>(ref.field)]; };
  this->UsesReportIds = descriptor.usesReportIds();
  this->ReportId = layout.input.reportId;
  this->PayloadBytes = descriptor.payloadBytes(HidReportType::Input, this->ReportId);
  this->X = field(layout.x);
  this->XElement = layout.x.element;
  this->Y = field(layout.y);
  this->YElement = layout.y.element;
  this->HasPressure = layout.pressure.valid();
  if (this->HasPressure)
  {
    this->Pressure = Element{ field(layout.pressure), layout.pressure.element };
  }
  this->ButtonCount = static_cast<int>(std::min<std::size_t>(layout.buttons.size(), 32));
  for (int i = 0; i < this->ButtonCount; ++i)
  {
    const HidValueRef& ref = layout.buttons[static_cast<std::size_t>(i)];
    this->Buttons[static_cast<std::size_t>(i)] =
      ref.valid() ? Element{ field(ref), ref.element } : Element{};
  }
  this->Configured = true;
  return true;
}

bool HidInputDecoder::decode(const std::uint8_t* report,
  std::size_t size,
  HidInputSample& sample) const
{
  if (!this->Configured || !report)
  {
    return false;
  }
  const std::uint8_t* payload = report;
  std::size_t payloadSize = size;
  if (this->UsesReportIds)
  {
    if (size < 1 || report[0] != this->ReportId)
    {
      return false;
    }
    ++payload;
    --payloadSize;
  }
  // A short report would leave stale or zero axes: reject it whole.
  if (payloadSize < this->PayloadBytes)
  {
    return false;
  }
  HidInputSample s;
  if (!this->X.read(payload, payloadSize, this->XElement, s.x) ||
      !this->Y.read(payload, payloadSize, this->YElement, s.y))
  {
    return false;
  }
  s.relative = this->X.isRelative();
  if (this->HasPressure)
  {
    std::int64_t raw = 0;
    const HidField& f = this->Pressure.field;
    if (f.read(payload, payloadSize, this->Pressure.element, raw) &&
        f.logicalMaximum > f.logicalMinimum)
    {
      const double p = static_cast<double>(raw - f.logicalMinimum) /
                       static_cast<double>(f.logicalMaximum - f.logicalMinimum);
      s.pressure = std::clamp(p, 0.0, 1.0);
    }
  }
  for (int i = 0; i < this->ButtonCount; ++i)
  {
    const Element& b = this->Buttons[static_cast<std::size_t>(i)];
    std::int64_t down = 0;
    if (b.field.reportCount > 0 && b.field.read(payload, payloadSize, b.element, down) && down != 0)
    {
      s.buttons |= 1u << i;
    }
  }
  sample = s;
  return true;
}

} // namespace vtouch

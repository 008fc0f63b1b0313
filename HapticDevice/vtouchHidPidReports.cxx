#include "vtouchHidPidReports.h"

#include <algorithm>
#include <cmath>

namespace vtouch
{

HidPidReports::HidPidReports(const HidReportDescriptor& descriptor, const HidPidLayout& layout)
  : Descriptor(descriptor)
  , Layout(layout)
{
}

HidReportBuffer HidPidReports::make(const HidReportRef& ref) const
{
  HidReportBuffer report;
  if (ref.present)
  {
    report.bytes.assign(this->Descriptor.payloadBytes(ref.type, ref.reportId) + 1, 0);
    report.bytes[0] = ref.reportId; // 0 when the device has no report IDs
  }
  return report;
}

bool HidPidReports::set(HidReportBuffer& report, const HidValueRef& ref, std::int64_t value) const
{
  if (!ref.valid() || report.bytes.empty())
  {
    return false;
  }
  return this->field(ref.field).write(report.payload(), report.payloadSize(), ref.element, value);
}

bool HidPidReports::select(HidReportBuffer& report, const HidUsageSelector& selector) const
{
  return this->set(report, HidValueRef{ selector.field, selector.element }, selector.value);
}

std::int64_t HidPidReports::magnitude(double fraction) const
{
  if (!this->Layout.cfMagnitude.valid())
  {
    return 0;
  }
  const HidField& f = this->field(this->Layout.cfMagnitude.field);
  fraction = std::clamp(std::isfinite(fraction) ? fraction : 0.0, -1.0, 1.0);
  const auto value =
    static_cast<std::int64_t>(std::lround(fraction * static_cast<double>(f.logicalMaximum)));
  return std::clamp(value, f.logicalMinimum, f.logicalMaximum);
}

bool HidPidReports::signedMagnitude() const
{
  return this->Layout.cfMagnitude.valid() && this->field(this->Layout.cfMagnitude.field).isSigned();
}

std::int64_t HidPidReports::direction(double angle_deg) const
{
  if (!this->Layout.seDirection0.valid())
  {
    return 0;
  }
  const HidField& f = this->field(this->Layout.seDirection0.field);
  double a = std::fmod(std::isfinite(angle_deg) ? angle_deg : 0.0, 360.0);
  if (a < 0.0)
  {
    a += 360.0;
  }
  // The logical range spans one turn: 0..255 is 256 steps of 1.41 degrees (255 is just short of
  // a turn), while 0..36000 or 0..360 name the closed range 0..360 degrees.
  const std::int64_t span = f.logicalMaximum - f.logicalMinimum;
  const double steps = static_cast<double>(span > 0 && span % 360 == 0 ? span : span + 1);
  std::int64_t v = static_cast<std::int64_t>(std::lround(a / 360.0 * steps));
  if (v >= static_cast<std::int64_t>(steps))
  {
    v = 0;
  }
  return f.logicalMinimum + v;
}

std::int64_t HidPidReports::infiniteDuration(std::int64_t quirk) const
{
  if (quirk >= 0 || !this->Layout.seDuration.valid())
  {
    return std::max<std::int64_t>(0, quirk);
  }
  const std::uint32_t bits =
    std::min<std::uint32_t>(this->field(this->Layout.seDuration.field).reportSize, 32);
  return static_cast<std::int64_t>((std::uint64_t{ 1 } << bits) - 1); // 0xFFFF for 16 bits
}

HidReportBuffer HidPidReports::setEffect(std::int64_t block,
  PidEffectMode mode,
  int axis,
  std::int64_t infiniteDurationQuirk) const
{
  const HidPidLayout& l = this->Layout;
  HidReportBuffer se = this->make(l.setEffect);
  this->set(se, l.seBlockIndex, block);
  this->select(se, l.seConstantForce);
  this->set(se, l.seDuration, this->infiniteDuration(infiniteDurationQuirk));
  this->set(se, l.seTriggerRepeat, 0);
  this->set(se, l.seSamplePeriod, 0);
  this->set(se, l.seStartDelay, 0);
  if (l.seGain.valid())
  {
    this->set(se, l.seGain, this->field(l.seGain.field).logicalMaximum);
  }
  this->set(se, l.seTriggerButton, 0); // out of the 1..n range: no trigger button
  switch (mode)
  {
    case PidEffectMode::PerAxis:
      this->set(se, axis == 0 ? l.seAxisX : l.seAxisY, 1);
      this->set(se, l.seDirectionEnable, 0);
      // Along +X (east, 90 degrees) or +Y of the HID frame (south, 180 degrees): a positive
      // magnitude pushes toward the positive axis whichever way the firmware reads it.
      this->set(se, l.seDirection0, this->direction(axis == 0 ? 90.0 : 180.0));
      break;
    case PidEffectMode::Polar:
      this->set(se, l.seAxisX, 1);
      this->set(se, l.seAxisY, 1);
      this->set(se, l.seDirectionEnable, 1);
      this->set(se, l.seDirection0, this->direction(0.0));
      break;
    default:
      this->set(se, l.seAxisX, 1);
      this->set(se, l.seDirection0, this->direction(90.0));
      break;
  }
  return se;
}

HidReportBuffer HidPidReports::constantForce(std::int64_t block, std::int64_t magnitude) const
{
  HidReportBuffer cf = this->make(this->Layout.setConstantForce);
  this->set(cf, this->Layout.cfBlockIndex, block);
  this->set(cf, this->Layout.cfMagnitude, magnitude);
  return cf;
}

HidReportBuffer HidPidReports::effectOperation(std::int64_t block, bool start) const
{
  const HidPidLayout& l = this->Layout;
  HidReportBuffer op = this->make(l.effectOperation);
  this->set(op, l.eoBlockIndex, block);
  this->select(op, start ? l.eoStart : l.eoStop);
  this->set(op, l.eoLoopCount, start ? 1 : 0);
  return op;
}

HidReportBuffer HidPidReports::blockFree(std::int64_t block) const
{
  HidReportBuffer free = this->make(this->Layout.blockFree);
  this->set(free, this->Layout.bfBlockIndex, block);
  return free;
}

HidReportBuffer HidPidReports::deviceControl(const HidUsageSelector& control) const
{
  HidReportBuffer dc = this->make(this->Layout.deviceControl);
  this->select(dc, control);
  return dc;
}

HidReportBuffer HidPidReports::fullDeviceGain() const
{
  HidReportBuffer gain = this->make(this->Layout.deviceGain);
  if (this->Layout.dgGain.valid())
  {
    this->set(gain, this->Layout.dgGain, this->field(this->Layout.dgGain.field).logicalMaximum);
  }
  return gain;
}

HidReportBuffer HidPidReports::createConstantForceEffect() const
{
  HidReportBuffer create = this->make(this->Layout.createNewEffect);
  this->select(create, this->Layout.cneConstantForce);
  return create;
}

HidReportBuffer HidPidReports::blockLoadRequest() const
{
  return this->make(this->Layout.blockLoad);
}

HidBlockLoadStatus HidPidReports::parseBlockLoad(const std::uint8_t* report,
  std::size_t size,
  std::int64_t& block) const
{
  const HidPidLayout& l = this->Layout;
  const bool ids = this->Descriptor.usesReportIds();
  if (!report || size < (ids ? 2u : 1u) || !l.blBlockIndex.valid())
  {
    return HidBlockLoadStatus::Unreadable;
  }
  const std::uint8_t* payload = ids ? report + 1 : report;
  const std::size_t payloadSize = ids ? size - 1 : size;
  std::int64_t status = 0;
  const bool haveStatus =
    l.blSuccess.valid() &&
    this->field(l.blSuccess.field).read(payload, payloadSize, l.blSuccess.element, status);
  std::int64_t index = 0;
  if (!this->field(l.blBlockIndex.field).read(payload, payloadSize, l.blBlockIndex.element, index))
  {
    return HidBlockLoadStatus::Unreadable;
  }
  if (haveStatus && l.blFull.valid() && status == l.blFull.value)
  {
    return HidBlockLoadStatus::Full;
  }
  if (haveStatus && l.blError.valid() && status == l.blError.value)
  {
    return HidBlockLoadStatus::Error;
  }
  if (index > 0 && (!haveStatus || status == l.blSuccess.value))
  {
    block = index;
    return HidBlockLoadStatus::Success;
  }
  return HidBlockLoadStatus::Pending;
}

} // namespace vtouch

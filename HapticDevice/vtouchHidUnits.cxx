#include "vtouchHidUnits.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace vtouch
{

namespace
{
/// Signed four-bit nibble `index` of a Unit item (HID 1.11, 6.2.2.7).
int unitNibble(std::uint32_t unit, int index)
{
  const int n = static_cast<int>((unit >> (4 * index)) & 0xFu);
  return n >= 8 ? n - 16 : n;
}

/// The raw range the calibration maps onto its workspace (the logical range when it sets none).
double rawRange(const HidField& f, double rawMinimum, double rawMaximum)
{
  if (rawMinimum != rawMaximum)
  {
    return std::abs(rawMaximum - rawMinimum);
  }
  return std::abs(static_cast<double>(f.logicalMaximum) - static_cast<double>(f.logicalMinimum));
}
} // namespace

double hidLengthPerCount_mm(const HidField& field)
{
  const std::uint32_t unit = field.unit;
  const int system = unitNibble(unit, 0);
  // System 1: SI Linear (length in centimetres); 3: English Linear (inches).
  double unit_mm = 0.0;
  if (system == 1)
  {
    unit_mm = 10.0;
  }
  else if (system == 3)
  {
    unit_mm = 25.4;
  }
  // Length to the first power and no mass, time, temperature, current or luminous intensity.
  if (unit_mm == 0.0 || unitNibble(unit, 1) != 1 || (unit >> 8) != 0)
  {
    return 0.0;
  }
  const double logical =
    static_cast<double>(field.logicalMaximum) - static_cast<double>(field.logicalMinimum);
  const double physical =
    static_cast<double>(field.physicalMaximum) - static_cast<double>(field.physicalMinimum);
  if (!(std::abs(logical) > 0.0) || !(std::abs(physical) > 0.0) || field.unitExponent < -15 ||
      field.unitExponent > 15)
  {
    return 0.0;
  }
  const double perCount =
    std::abs(physical / logical) * unit_mm * std::pow(10.0, field.unitExponent);
  return std::isfinite(perCount) ? perCount : 0.0;
}

Vec2 hidPhysicalWorkspace_mm(const HidField& x, const HidField& y, const DeviceCalibration& c)
{
  const double rx = hidLengthPerCount_mm(x);
  const double ry = hidLengthPerCount_mm(y);
  if (!(rx > 0.0) || !(ry > 0.0))
  {
    return Vec2{};
  }
  return Vec2{ rx * rawRange(x, c.rawMinimum.x, c.rawMaximum.x),
    ry * rawRange(y, c.rawMinimum.y, c.rawMaximum.y) };
}

double hidPositionResolution_mm(const HidField& x,
  const HidField& y,
  const DeviceCalibration& calibration,
  bool relative,
  bool usePhysicalUnits,
  HidResolutionSource* source)
{
  auto report = [source](HidResolutionSource s)
  {
    if (source)
    {
      *source = s;
    }
  };
  if (relative)
  {
    report(HidResolutionSource::Relative);
    return calibration.countsPerMm > 0.0 ? 1.0 / calibration.countsPerMm : 0.0;
  }
  const double rx = hidLengthPerCount_mm(x);
  const double ry = hidLengthPerCount_mm(y);
  if (usePhysicalUnits && rx > 0.0 && ry > 0.0)
  {
    report(HidResolutionSource::Descriptor);
    return std::max(rx, ry);
  }
  // Fallback: no physical units (most game controllers and FFB firmwares declare none), or a
  // preset fixes the frame: the positions the device reports are quantized to one count of the
  // calibrated frame, whatever that count is physically.
  report(HidResolutionSource::Calibration);
  const double cx = rawRange(x, calibration.rawMinimum.x, calibration.rawMaximum.x);
  const double cy = rawRange(y, calibration.rawMinimum.y, calibration.rawMaximum.y);
  const double ax = cx > 0.0 ? std::abs(calibration.workspace_mm.x) / cx : 0.0;
  const double ay = cy > 0.0 ? std::abs(calibration.workspace_mm.y) / cy : 0.0;
  return std::max(ax, ay);
}

} // namespace vtouch

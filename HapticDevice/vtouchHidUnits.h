// Physical units of a HID field (HID 1.11, sections 6.2.2.7 "Global Items": Physical Minimum and
// Maximum, Unit, Unit Exponent) and the position resolution of a device they imply.
#pragma once

#include "vtouchDeviceCalibration.h"
#include "vtouchHidField.h"

namespace vtouch
{

/// Millimetres per logical count of `field` when its Unit is a length: SI Linear (centimetre) or
/// English Linear (inch) with length exponent 1 and no other dimension (HID 1.11, 6.2.2.7).
/// resolution = (Physical Maximum − Physical Minimum) / (Logical Maximum − Logical Minimum),
/// scaled by the unit and by 10^(Unit Exponent). Returns 0 when the field gives no physical
/// length (Unit none, another dimension, an empty logical range).
double hidLengthPerCount_mm(const HidField& field);

/// How a HidPidDevice's position resolution was found (DeviceCapabilities::positionResolution_mm).
enum class HidResolutionSource : unsigned char
{
  Descriptor,  ///< the report descriptor's physical units (the frame is physical millimetres)
  Calibration, ///< no physical units: one count of the calibrated frame (workspace / raw range)
  Relative     ///< relative axes (mice): 1 / countsPerMm
};

/// The position resolution of a HID device in its device frame, mm: the larger (coarser) of the
/// X and Y axes. `calibration` maps counts onto millimetres (HidPidDevice::toMillimetres), so one
/// count of the frame is workspace_mm / raw range; when `usePhysicalUnits` is true and both axes
/// carry a physical length, the descriptor's resolution is used instead (the caller then sizes
/// the workspace from it, see physicalWorkspace_mm()). Never 0 for a usable axis.
double hidPositionResolution_mm(const HidField& x,
  const HidField& y,
  const DeviceCalibration& calibration,
  bool relative,
  bool usePhysicalUnits,
  HidResolutionSource* source = nullptr);

/// The physical extent of the calibrated raw range of both axes, mm, when both give a physical
/// length; {0, 0} otherwise.
Vec2 hidPhysicalWorkspace_mm(const HidField& x, const HidField& y, const DeviceCalibration& c);

} // namespace vtouch

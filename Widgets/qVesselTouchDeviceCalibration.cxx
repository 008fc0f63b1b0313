#include "qVesselTouchDeviceCalibration.h"

bool qVesselTouchDeviceCalibration::Axis::operator==(const Axis& o) const
{
  return this->rawMinimum == o.rawMinimum && this->rawMaximum == o.rawMaximum &&
         this->minimum_mm == o.minimum_mm && this->maximum_mm == o.maximum_mm;
}

double qVesselTouchDeviceCalibration::toMillimetres(int axis, double raw) const
{
  if (axis < 0 || axis >= kAxisCount)
  {
    return 0.0;
  }
  const Axis& a = this->axes[axis];
  const double span = a.rawMaximum - a.rawMinimum;
  if (span == 0.0)
  {
    return 0.0;
  }
  return a.minimum_mm + (raw - a.rawMinimum) * (a.maximum_mm - a.minimum_mm) / span;
}

bool qVesselTouchDeviceCalibration::operator==(const qVesselTouchDeviceCalibration& o) const
{
  for (int i = 0; i < kAxisCount; ++i)
  {
    if (!(this->axes[i] == o.axes[i]))
    {
      return false;
    }
  }
  return true;
}

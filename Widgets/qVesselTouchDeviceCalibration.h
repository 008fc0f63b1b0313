// Calibration of a device's raw axes to millimetres: per axis, a raw range mapped linearly
// onto a millimetre range. Plain data; the device widget edits it.
#ifndef qVesselTouchDeviceCalibration_h
#define qVesselTouchDeviceCalibration_h

struct qVesselTouchDeviceCalibration
{
  struct Axis
  {
    /// Raw reading (device units: HID logical value, pixels, ...) at the low end. Default -32768.
    double rawMinimum = -32768.0;
    /// Raw reading at the high end (!= rawMinimum). Default 32767.
    double rawMaximum = 32767.0;
    /// Position at the low end, mm. Default -50 mm.
    double minimum_mm = -50.0;
    /// Position at the high end, mm. Default +50 mm.
    double maximum_mm = 50.0;

    bool operator==(const Axis& o) const;
  };

  static constexpr int kAxisCount = 3;
  /// x, y, z. The z axis is used only by devices that sense 3 DOF.
  Axis axes[kAxisCount];

  /// Raw reading of `axis` (0 x, 1 y, 2 z) to millimetres, linear, not clamped. 0 for a bad axis
  /// index or an empty raw range.
  double toMillimetres(int axis, double raw) const;

  bool operator==(const qVesselTouchDeviceCalibration& o) const;
  bool operator!=(const qVesselTouchDeviceCalibration& o) const { return !(*this == o); }
};

#endif

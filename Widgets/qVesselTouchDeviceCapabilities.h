// What a device can do, as the device widget shows it. Mirrors vtouch::DeviceCapabilities
// (HapticDevice/) field for field, in Qt types, so the widgets need no device headers.
#ifndef qVesselTouchDeviceCapabilities_h
#define qVesselTouchDeviceCapabilities_h

#include <QString>
#include <QVariantMap>

struct qVesselTouchDeviceCapabilities
{
  /// Product name. Default empty.
  QString name;
  /// Position axes sensed (2: x, y; 3: x, y, z). Default 2.
  int sensedDof = 2;
  /// Force axes rendered (0: input only). Default 2.
  int actuatedDof = 2;
  /// Extent of the reachable box per axis x, y, z, mm (0 for an axis not sensed).
  /// Default 100 x 100 x 0 mm.
  double workspaceX_mm = 100.0;
  double workspaceY_mm = 100.0;
  double workspaceZ_mm = 0.0;
  /// Largest force the device may hold indefinitely, N. Default 0 (unknown).
  double maxContinuousForce_N = 0.0;
  /// Largest stable stiffness at 1 kHz, N/m. Default 0 (unknown).
  double maxStiffness_N_per_m = 0.0;
  /// Fastest useful update rate, Hz. Default 1000 Hz.
  double maxUpdateRate_Hz = 1000.0;
  /// A pressure or z input feeds the force zones. Default false.
  bool hasPressure = false;
  /// Number of buttons. Default 0.
  int buttonCount = 0;

  /// From a map whose keys are the field names above ("sensedDof", "maxContinuousForce_N", ...);
  /// missing keys keep their defaults. "workspace_mm" may also be a list of three numbers.
  static qVesselTouchDeviceCapabilities fromVariantMap(const QVariantMap& map);
  QVariantMap toVariantMap() const;
};

#endif

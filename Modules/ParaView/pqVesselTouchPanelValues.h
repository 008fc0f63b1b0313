// What the VesselTouch panel edits (the haptic parameters: force law and its parameters, haptic
// zoom, force zones...; the per-law gains; the device), in one plain struct that travels between
// the widgets, the session proxy and the user's settings ("VesselTouch/..." keys). The haptic
// parameters are written, read, saved and loaded by looping over their one table
// (vtouchHapticParameters.def): no parameter is named here.
#ifndef pqVesselTouchPanelValues_h
#define pqVesselTouchPanelValues_h

#include "qVesselTouchForceLawParameters.h"

#include <QString>

class QSettings;
class vtkSMProxy;

struct pqVesselTouchPanelValues
{
  /// Every haptic parameter (law.haptic, the table's defaults) and the gain of each law.
  qVesselTouchForceLawParameters law;
  /// Device id as the device widget names it: "simulated", "pointer", "replay" or
  /// "hid:<hidapi path>". Default "simulated".
  QString deviceId = QStringLiteral("simulated");

  /// The force law, the session's ForceLaw value (law.haptic.forceLaw).
  int forceLaw() const;
  /// The gain k of the current law, N (the session's ZoneGain); the constraint proxy has no gain
  /// of its own and keeps `fallback_N`.
  double activeGain_N(double fallback_N) const;
  /// Sets the gain of the current law (no-op for the constraint proxy).
  void setActiveGain_N(double gain_N);

  /// Writes every haptic parameter and the device into the session proxy's properties (no
  /// UpdateVTKObjects); the session's ZoneGain is `zoneGain_N`.
  void writeToProxy(vtkSMProxy* session, double zoneGain_N) const;
  /// Reads them from the session proxy's properties; returns its ZoneGain (N).
  double readFromProxy(vtkSMProxy* session);

  /// Saves under "VesselTouch/" in `settings` (a haptic parameter under its property name);
  /// load() leaves values without a key, or out of their range, unchanged.
  void save(QSettings& settings) const;
  void load(const QSettings& settings);

  /// Whether every session property these values map to is at its XML default (a fresh
  /// session, which then takes the panel's saved settings rather than showing its defaults).
  static bool proxyHasDefaults(vtkSMProxy* session);

  /// Session DeviceType (0 simulated, 1 pointer, 2 replay, 3 HID) and HID path of `deviceId`.
  static int deviceType(const QString& deviceId);
  static QString hidPath(const QString& deviceId);
};

#endif

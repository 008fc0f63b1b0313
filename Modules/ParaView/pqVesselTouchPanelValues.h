// What the VesselTouch panel edits (force law and its parameters, haptic zoom, force zones,
// device), in one plain struct that travels between the widgets, the session proxy and the
// user's settings ("VesselTouch/..." keys), so that each mapping is written once.
#ifndef pqVesselTouchPanelValues_h
#define pqVesselTouchPanelValues_h

#include "qVesselTouchForceLawParameters.h"
#include "qVesselTouchTickOptionsWidget.h"

#include <QString>

class QSettings;
class vtkSMProxy;

struct pqVesselTouchPanelValues
{
  /// Force law, the session's ForceLaw value (0 LDGF, 1 change of height, 2 lateral gradient,
  /// 3 constraint proxy). Default 0.
  int forceLaw = 0;
  /// Every law's parameters (the widget's struct and defaults).
  qVesselTouchForceLawParameters law;
  /// Haptic zoom r, [0.1, 10]. Default 1.
  double zoom = 1.0;
  /// Force zones thresholds (normalized pressure). Defaults 0.05 and 0.5.
  double zoneZeroBelow = 0.05;
  double zoneSaturateAbove = 0.5;
  /// The haptic tick's options (the Advanced section; the widget's struct and defaults).
  qVesselTouchTickOptions tick;
  /// Device id as the device widget names it: "simulated", "pointer", "replay" or
  /// "hid:<hidapi path>". Default "simulated".
  QString deviceId = QStringLiteral("simulated");

  /// The gain k of the current law, N (the session's ZoneGain); the constraint proxy has no gain
  /// of its own and keeps `fallback_N`.
  double activeGain_N(double fallback_N) const;
  /// Sets the gain of the current law (no-op for the constraint proxy).
  void setActiveGain_N(double gain_N);

  /// Writes every value into the session proxy's properties (no UpdateVTKObjects).
  /// `zoneGain_N` is the session's ZoneGain.
  void writeToProxy(vtkSMProxy* session, double zoneGain_N) const;
  /// Reads the values from the session proxy's properties; returns its ZoneGain (N).
  double readFromProxy(vtkSMProxy* session);

  /// Saves under "VesselTouch/" in `settings`; load() leaves values without a key unchanged.
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

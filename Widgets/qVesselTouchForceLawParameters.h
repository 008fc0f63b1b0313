// Every parameter the force law widget edits, in one plain struct. The law parameters ARE the
// haptic logic's (vtouch::HapticParameters, generated from
// Logic/Haptics/vtouchHapticParameters.def, whose table gives each one's default, range and unit),
// so the panel, Python and the haptic thread agree by construction.
//
// The gains k of LDGF, change of height and the lateral gradient multiply a slope (mm/mm), so
// they are in newtons (per unit slope), not N/m. Logic/Haptics takes k(P) from the force zones
// (HapticParameters::zoneGain_N); the widget remembers one gain per law, each with ZoneGain's
// default and range, and the module glue maps the active law's k onto that gain.
#ifndef qVesselTouchForceLawParameters_h
#define qVesselTouchForceLawParameters_h

#include "vtouchHapticParameterTable.h"

struct qVesselTouchForceLawParameters
{
  /// The haptic parameters (every law's, and the rest: zoom, zones, tracer...). The widget edits
  /// the force laws' rows; the defaults are the table's.
  vtouch::HapticParameters haptic;

  /// Gain k of LDGF, change of height and the lateral gradient at full pressure, newtons per unit
  /// slope: ZoneGain's default and range (vtouchHapticParameters.def).
  double ldgfGain_N = defaultGain_N();
  double cohGain_N = defaultGain_N();
  double lateralGain_N = defaultGain_N();

  static constexpr double defaultGain_N()
  {
    return vtouch::hapticParameter(vtouch::HapticParameterId::ZoneGain).defaultValue;
  }

  /// Equal when every haptic parameter and gain agrees to the spin boxes' precision.
  bool operator==(const qVesselTouchForceLawParameters& other) const;
  bool operator!=(const qVesselTouchForceLawParameters& other) const { return !(*this == other); }
};

#endif

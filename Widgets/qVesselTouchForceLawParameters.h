// Every parameter the force law widget edits, in one plain struct with documented defaults.
// The names and defaults follow Logic/Haptics (vtouch::HapticParameters) so the module glue can
// copy fields one to one; this header stays free of Logic so the widgets build alone.
//
// The gains k of LDGF, change of height and the lateral gradient multiply a slope (mm/mm), so
// they are in newtons (per unit slope), not N/m. Logic/Haptics takes k(P) from the force zones
// (HapticParameters::zoneGain_N); the module glue maps the active law's k onto that gain.
#ifndef qVesselTouchForceLawParameters_h
#define qVesselTouchForceLawParameters_h

struct qVesselTouchForceLawParameters
{
  // --- LDGF (Yi & Hayward eq. 2): F = k(P) dz / (dl + lambda) eta ---
  /// LDGF gain k at full pressure, newtons per unit slope. Default 1 N, range [0, 20] N.
  double ldgfGain_N = 1.0;
  /// LDGF regularization lambda, mm of screen arc length: bounds the force to k |dz| / lambda
  /// where the vessel runs along the view direction. Default 0.01 mm, range [0.001, 10] mm.
  double ldgfLambda_mm = 0.01;

  // --- change of height (Hayward & Yi eq. 3): f = -k dz/dl mu, robust mu (Appendix A) ---
  /// Change-of-height gain k, newtons per unit slope. Default 1 N, range [0, 20] N.
  double cohGain_N = 1.0;
  /// Change-of-height regularization lambda, mm. Default 0.01 mm, range [0.001, 10] mm.
  double cohLambda_mm = 0.01;
  /// Motion window saturation length z_max, mm of hand travel: |mu| reaches 1 after z_max of
  /// deliberate motion. 0 (default) = from the device ("set according to the resolution of a
  /// particular device", Hayward & Yi App. A: two counts of its position resolution). Range
  /// [0, 20] mm.
  double cohZMax_mm = 0.0;
  /// Motion window forgetting time constant T, seconds. Default 0.1 s, range [0.005, 5] s.
  double cohForgetTime_s = 0.1;

  // --- lateral surface gradient (baseline): f = -k grad(h) ---
  /// Lateral gradient gain k, newtons per unit slope. Default 1 N, range [0, 20] N.
  double lateralGain_N = 1.0;
  /// Half-width of the central difference, pixels. Default 2 px, range [1, 20] px.
  double lateralProbe_px = 2.0;

  // --- constraint proxy (Ikits et al.) with a virtual coupler F = k_c (x - p) - b_c xdot ---
  /// Coupler stiffness k_c, N/m. Default 300 N/m, range [0, 5000] N/m, clamped to the device.
  double proxyStiffness_N_per_m = 300.0;
  /// Coupler damping b_c, N·s/m. Default 0.1 N·s/m, range [0, 10] N·s/m, clamped to the device.
  double proxyDamping_N_s_per_m = 0.1;
  /// Tangent axis rule: false = free (no force along the vessel), true = drag (eq. 8). Default
  /// free.
  bool proxyTangentDrag = false;
  /// Drag threshold tau_t along the tangent, N. Default 0.3 N, range [0, 10] N.
  double proxyTangentThreshold_N = 0.3;
  /// Normal axis rule: false = rigid, true = snap-drag (eq. 11). Default rigid.
  bool proxySnapDrag = false;
  /// Snap threshold tau_n along the normal, N. Default 1.5 N, range [0, 20] N.
  double proxySnapThreshold_N = 1.5;
  /// Stiffness transfer function kappa (eq. 12) lower knee s0 on the frame strength, [0, 1].
  /// Default 0.15.
  double proxyKappaLow = 0.15;
  /// Stiffness transfer function kappa upper knee s1 (> s0), [0, 1]. Default 0.5.
  double proxyKappaHigh = 0.5;

  bool operator==(const qVesselTouchForceLawParameters& other) const;
  bool operator!=(const qVesselTouchForceLawParameters& other) const { return !(*this == other); }
};

#endif

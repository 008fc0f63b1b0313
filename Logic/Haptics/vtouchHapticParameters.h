// Every run-time setting of the haptic pipeline in one trivially copyable struct, so the GUI can
// publish it to the haptic thread through a SeqLock.
#pragma once

#include "vtouchForceLaw.h"

#include <cstdint>

namespace vtouch
{

struct HapticParameters
{
  // --- force law selection ---
  /// The active force law. Default LDGF.
  ForceLawId forceLaw = ForceLawId::Ldgf;
  /// Crossfade duration when the law changes, s (no force jump). Default 0.005 s.
  double crossfade_s = 0.005;

  // --- LDGF and change of height (see their headers) ---
  double ldgfLambda_mm = 0.005; ///< LDGF lambda, mm. Default 0.005 mm
  double cohLambda_mm = 0.005;  ///< change-of-height lambda, mm. Default 0.005 mm
  /// Both lambdas are at least zoneGain x window / (budget x the device's force limit), so the
  /// slope laws stay within budget x that limit where dl -> 0 (Yi & Hayward §4.1: lambda bounds
  /// the force, not a clamp). 0 disables. Default 0.9.
  double slopeForceBudget = 0.9;
  /// (the dz/dl stencil window is a scene setting: HapticSession::setSlopeWindow_mm, default 1 mm)
  /// Change of height z_max (Hayward & Yi eq. 8), mm; 0 (default) = cohZMaxPerResolution x the
  /// device's position resolution ("set according to the resolution of a particular device").
  double cohZMax_mm = 0.0;
  double cohZMaxPerResolution = 2.0; ///< z_max in device resolution counts. Default 2
  // --- lateral gradient baseline ---
  double lateralProbe_px = 2.0; ///< central difference half-width, px. Default 2 px
  // --- constraint proxy (Ikits) ---
  double proxyStiffness_N_per_m = 200.0; ///< k_c, N/m. Default 200
  double proxyDamping_N_s_per_m = 0.1;   ///< b_c on xdot - pdot, N s/m (0: none). Default 0.1
  bool proxyTangentDrag = false;         ///< tangent rule Drag (Ikits eq. 8). Default Free
  bool proxyTangentSnap = false;         ///< tangent rule SnapDrag (eq. 11 steps; wins over Drag)
  double proxyTangentThreshold_N = 0.3;  ///< drag / snap threshold tau_t, N. Default 0.3
  bool proxySnapDrag = false;            ///< normal rule PopOver (to the vessel under the cursor)
  bool proxyNormalUnilateral = false;    ///< normal rule Unilateral (eq. 10; PopOver wins)
  double proxySnapThreshold_N = 1.5;     ///< pop-over threshold, N. Default 1.5
  bool proxyThresholdFromData = false;   ///< eq. 16: pop-over threshold x frame strength
  double proxyFriction = 0.0;            ///< mu in the constraint subspace. Default 0
  double proxyTickSpacing_mm = 0.0;      ///< tick marks every ... mm of arc; 0 none. Default 0
  double proxyTickForce_N = 0.3;         ///< tick-mark peak force, N. Default 0.3
  bool proxyTickAtBifurcations = false;  ///< a tick mark where a branch joins. Default off
  bool proxyFieldForce = false;          ///< add the depth slope (eq. 2) along the vessel
  double proxyKappaLow = 0.15;           ///< stiffness transfer knee s0. Default 0.15
  double proxyKappaHigh = 0.5;           ///< stiffness transfer knee s1. Default 0.5

  // --- force zones k(P) ---
  double zoneGain_N = 1.0;        ///< gain k in the saturation zone, N. Default 1 N
  double zoneZeroBelow = 0.05;    ///< end of the zero-force zone (normalized pressure). 0.05
  double zoneSaturateAbove = 0.5; ///< start of the saturation zone. Default 0.5
  /// Zero-force zone of devices without pressure/z (IdleGate): a handle resting within
  /// idleRadius_mm for idleDwell_s is silenced (fade idleRamp_s); moving out restores the force.
  double idleRadius_mm = 1.0; ///< Default 1 mm
  double idleDwell_s = 1.5;   ///< 0 disables. Default 1.5 s
  double idleRamp_s = 0.05;   ///< Default 0.05 s

  // --- cursor mapping, zoom, re-indexing ---
  /// Cursor pixels per hand millimetre at zoom 1. Default 4 px/mm (a 160 mm device sweeps 640 px).
  double pixelsPerDeviceMm = 4.0;
  /// Haptic zoom r = cursor movement / hand movement, clamped to [0.1, 10]. Default 1.
  /// The felt slope stays the same at any zoom: the slope laws (LDGF, change of height, lateral
  /// gradient) render the geometric slope tan(beta) = dz/dl, which does not depend on r, and the
  /// proxy coupler measures the hand-proxy offset in hand millimetres (pixels / (r x mapping)), so
  /// its stiffness is felt the same too. Only the cursor's travel per hand millimetre changes.
  double zoom = 1.0;
  /// With a pressure input: below this pressure the stylus is lifted and the cursor is frozen
  /// while the hand moves (re-indexing). Default 0.02.
  double reindexPressure = 0.02;
  /// Buttons that re-index while held (devices without z). Default button 1 (mask 0x2).
  std::uint32_t reindexButtonMask = 0x2;
  /// Buttons whose press returns from tracing to exploring. Default button 0 (mask 0x1).
  std::uint32_t releaseButtonMask = 0x1;
  /// Contact (ContactGate, Yi & Hayward §3.2): the cursor must stay within the capture radius this
  /// long before the agent is captured, s. A vessel crossed faster than 2 r / dwell does not take
  /// the agent. 0 = the paper's immediate capture. Default 0.05 s.
  double contactDwell_s = 0.05;
  /// At start, contact waits until the cursor has been outside every capture radius (no capture
  /// before any input). After a click it always does. Default true.
  bool contactApproachAtStart = true;

  // --- tracing and smoothing ---
  double tracerDeadBand_px = 0.25;     ///< the agent stays still below this projection, px. 0.25
  double maxForceRate_N_per_s = 100.0; ///< time-domain interpolation bound, N/s. Default 100
  /// Fig. 5's per-axis threshold and step count instead of the Euclidean bound. Default false
  bool forceInterpolationPerAxis = false;
  /// Direction hysteresis at projection cusps, fraction of |cursor - agent| (Tracer). 0.1
  double tracerDirectionHysteresis = 0.1;
  /// Screen arc searched ahead for a fold before reversing, px (Tracer). Default 3 px
  double tracerFoldLookAhead_px = 3.0;
  /// The tracing rule: 0 = offset (default: the cursor-to-agent offset is projected, with dead
  /// band, cusp hysteresis and fold look-ahead; Tracer::follow), 1 = movement (Yi & Hayward
  /// §3.2.1 as written: each tick's cursor movement is projected; Tracer::followMovement).
  int tracerRule = 0;
  /// Movement rule: per-tick projections below this leave the agent still, px. Default 0.01 px
  double tracerMovementThreshold_px = 0.01;
  /// Both rules: within this screen arc of the last junction passed, the branch choice follows
  /// the hand (Tracer::junctionWindow_px); 0 = the choice at the junction is final. Default 24 px
  double tracerJunctionWindow_px = 24.0;
  /// ...re-routing when the cursor is this much closer to another branch, px. Default 1 px
  double tracerJunctionMargin_px = 1.0;

  static constexpr double kMinZoom = 0.1;
  static constexpr double kMaxZoom = 10.0;
};

} // namespace vtouch

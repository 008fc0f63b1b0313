// Ikits, Brederson, Hansen & Johnson's constraint-based proxy, on the centerline.
#pragma once

#include "vtouchForceLaw.h"

namespace vtouch
{

/// A proxy point p sits on the centerline at the tracing agent (Ikits eq. 4: the proxy moves along
/// the axes of a local frame), with the frame: the projected tangent t and the in-plane normal n
/// (the third axis, the view direction, is not actuated by a planar device). Each axis has a
/// motion rule (Ikits §4); thresholds are given as coupler forces, tau (distance) = tau_N / k_c:
/// - tangent: Free (eq. 9: the proxy follows the hand along the vessel, no force); Drag (eq. 8:
///   the proxy moves only when the coupler force along t exceeds tau_t, then trails the hand so
///   that the force stays tau_t; realised by the tracer's trail, Tracer::trail_px, so the proxy
///   never leaves the centerline); SnapDrag (eq. 11: the proxy stands still until the hand leads
///   it by more than tau_t / k_c along t, then steps by exactly that distance: ForceRequest::
///   agentStep_px).
/// - normal: Rigid (a bilateral spring toward the vessel); Unilateral (eq. 10: no force on the +n
///   side, the spring on the -n side: the vessel is a wall the hand leans on from one side);
///   PopOver (Ikits §5.1's "pop through": when the normal force exceeds tau_snap the proxy jumps
///   to the vessel under the cursor, if any; our earlier "snap-drag").
/// Transfer functions (eq. 12, and eq. 16 driven by the data): kappa(s) = smoothstep(s0, s1, s) of
/// the frame strength s = |projected tangent| weighs the anisotropic coupler,
///   K = k_c [ (1 - kappa) I + kappa (n n^T + c_t t t^T) ],  c_t = 1 for Drag, else 0,
/// so a degenerate frame (a vessel seen end-on: s -> 0) degenerates to an isotropic point
/// constraint (Ikits §3, ill-defined frames); with `thresholdFromData` the pop-over threshold is
/// tau_snap x s (eq. 16's tau(c_l) with a linear ramp: a line constraint where the frame is
/// reliable, no pop-over resistance where it is not).
/// Coupler (eq. 7): F = -K (x - p) - b_c (xdot - pdot), x the cursor mapped back to hand
/// millimetres (the zoom does not change the felt stiffness), pdot the proxy's velocity from its
/// screen motion: moving along a free vessel (pdot = xdot) feels no drag. b_c = 0 drops the term
/// as Ikits do. k_c <= maxStiffness_N_per_m x (rate / 1 kHz), b_c <= maxStiffness_N_per_m x 1 ms.
/// Secondary effects (Ikits §1, §3): friction in the constraint subspace (a friction point on t,
/// Salisbury et al.: the tangent drag threshold grows by mu |F_n|), tick-mark texture (a detent
/// every tickSpacing_mm of 3D arc and/or at every bifurcation of the traced path:
/// F_t = -A (u/w) exp((1 - (u/w)^2) / 2), u the signed arc distance to the nearest mark, w its
/// half width; a well the hand feels as a click), and a field force along the vessel (the
/// depth slope, Yi & Hayward eq. 2, added to the coupler).
class ConstraintProxyForceLaw final : public ForceLaw
{
public:
  enum class TangentRule : std::uint8_t
  {
    Free = 0,
    Drag = 1,
    SnapDrag = 2
  };
  enum class NormalRule : std::uint8_t
  {
    Rigid = 0,
    PopOver = 1,
    Unilateral = 2
  };

  /// Coupler stiffness k_c, N/m. Default 200 N/m: below the largest stable value the tests find
  /// for the default simulated device (0.05 kg, 0.5 N s/m) at 250 Hz (~250 N/m), 1 kHz (~1100 N/m)
  /// and 4 kHz (~6300 N/m).
  double stiffness_N_per_m = 200.0;
  /// Coupler damping b_c on the relative velocity xdot - pdot, N s/m. Default 0.1 N s/m.
  double damping_N_s_per_m = 0.1;
  TangentRule tangentRule = TangentRule::Free;
  /// Drag / snap threshold tau_t along the tangent, N. Default 0.3 N.
  double tangentThreshold_N = 0.3;
  NormalRule normalRule = NormalRule::Rigid;
  /// Pop-over threshold tau_snap along the normal, N. Default 1.5 N.
  double snapThreshold_N = 1.5;
  /// Eq. 16: scale the pop-over threshold by the frame strength. Default false.
  bool thresholdFromData = false;
  /// Stiffness transfer function knees on the frame strength, [0, 1]. Defaults 0.15 and 0.5.
  double kappaLow = 0.15;
  double kappaHigh = 0.5;
  /// Friction coefficient mu in the constraint subspace (tangent drag threshold + mu |F_n|).
  /// Default 0 (none).
  double friction = 0.0;
  /// Tick marks every this many mm of 3D arc; 0 = none. Default 0.
  double tickSpacing_mm = 0.0;
  /// Tick-mark peak force A, N, and half width w, mm. Defaults 0.3 N, 0.25 mm.
  double tickForce_N = 0.3;
  double tickWidth_mm = 0.25;
  /// A tick mark (the same detent) at every bifurcation of the traced path, where a branch
  /// joins (Ikits §1's tick marks "at bifurcations" too). Default false.
  bool tickAtBifurcations = false;
  /// Add the depth slope (LDGF) along the vessel as a field force. Default false.
  bool fieldForce = false;
  /// Lambda of the field force, mm (as LdgfForceLaw, device-sized). Default 0.005 mm.
  double fieldLambda_mm = 0.005;

  ForceLawId id() const override { return ForceLawId::ConstraintProxy; }
  void reset() noexcept override;
  Vec2 compute(const ForceInput& in, ForceRequest& request) noexcept override;

  /// kappa(s) of eq. 12 with the current knees.
  double kappa(double frameStrength) const;
  /// k_c and b_c after the device bounds.
  /// `dt_s` is the tick period (the stiffness bound scales with the rate).
  double effectiveStiffness_N_per_m(const DeviceCapabilities* caps, double dt_s = 0.001) const;
  double effectiveDamping_N_s_per_m(const DeviceCapabilities* caps) const;
  /// The tracer trailing distance that realizes the tangent drag threshold (with friction),
  /// pixels. Infinite for SnapDrag (the proxy moves only in the law's steps).
  double tangentTrail_px(const DeviceCapabilities* caps,
    double pixelsPerHandMm,
    double dt_s = 0.001) const;
  /// The tick-mark texture force along increasing arc for an arc position, N.
  double tickForce(double arc_mm) const;
  /// One detent: the force along increasing arc at signed arc offset u from its mark, N
  /// (-A (u/w) exp((1 - (u/w)^2) / 2); 0 for a non-finite u).
  double detentForce(double offset_mm) const;
  /// The frame used in the last tick (tangent), for display and tests.
  Vec2 frameTangent() const { return this->Tangent; }

private:
  Vec2 Tangent{ 1.0, 0.0 };
  bool HasFrame = false;
  Vec2 LastAgent_px;
  bool HasLastAgent = false;
  double LastNormalForce_N = 0.0;
};

} // namespace vtouch

// Ikits, Brederson, Hansen & Johnson's constraint-based proxy, on the centerline.
#pragma once

#include "vtouchForceLaw.h"

namespace vtouch
{

/// A proxy point p sits on the centerline at the tracing agent, with a local frame: the projected
/// tangent t and the in-plane normal n (the third axis, the view direction, is not actuated by a
/// planar device). Each axis has a motion rule:
/// - tangent: Free (the proxy follows the hand along the vessel, no force) or Drag: the proxy moves
///   only when the coupler force along t exceeds tau_t and then trails the hand so that the force
///   stays tau_t (their eq. 8). The trailing is done by the tracer (Tracer::trail_px, set from
///   tangentTrail_px()), so the proxy never leaves the centerline.
/// - normal: Rigid (a spring toward the vessel) or SnapDrag: when the normal force exceeds
///   tau_snap the proxy pops over to the vessel under the cursor (their eq. 11), if any.
/// The stiffness transfer function kappa (their eq. 12) maps the local frame strength s (|projected
/// tangent|, 0 along the view direction) to the weight of the anisotropic part:
///   kappa(s) = smoothstep(s0, s1, s),  K = k_c [ (1 - kappa) I + kappa (n n^T + c_t t t^T) ]
/// with c_t = 1 for Drag and 0 for Free. Where the frame is degenerate (s < s0) the coupler is an
/// isotropic spring to p, whatever the (noisy) tangent does: no jitter.
/// Virtual coupler (force on the hand): F = -K (x - p) - b_c xdot, x the cursor mapped back to hand
/// millimetres (so the zoom does not change the felt stiffness). k_c and b_c are bounded by the
/// device: k_c <= maxStiffness_N_per_m * (rate / 1 kHz) (the capability is stated at 1 kHz and the
/// stable stiffness of a sampled spring scales with the rate), b_c <= maxStiffness_N_per_m * 1 ms.
class ConstraintProxyForceLaw final : public ForceLaw
{
public:
  enum class TangentRule : std::uint8_t
  {
    Free = 0,
    Drag = 1
  };
  enum class NormalRule : std::uint8_t
  {
    Rigid = 0,
    SnapDrag = 1
  };

  /// Coupler stiffness k_c, N/m. Default 200 N/m: below the largest stable value the tests find
  /// for the default simulated device (0.05 kg, 0.5 N s/m) at 250 Hz (~250 N/m), 1 kHz (~1100 N/m)
  /// and 4 kHz (~6300 N/m).
  double stiffness_N_per_m = 200.0;
  /// Coupler damping b_c on the hand velocity, N s/m. Default 0.1 N s/m.
  double damping_N_s_per_m = 0.1;
  TangentRule tangentRule = TangentRule::Free;
  /// Drag threshold tau_t along the tangent, N. Default 0.3 N.
  double tangentThreshold_N = 0.3;
  NormalRule normalRule = NormalRule::Rigid;
  /// Snap threshold tau_snap along the normal, N. Default 1.5 N.
  double snapThreshold_N = 1.5;
  /// Stiffness transfer function knees on the frame strength, [0, 1]. Defaults 0.15 and 0.5.
  double kappaLow = 0.15;
  double kappaHigh = 0.5;

  ForceLawId id() const override { return ForceLawId::ConstraintProxy; }
  void reset() noexcept override;
  Vec2 compute(const ForceInput& in, ForceRequest& request) noexcept override;

  /// kappa(s) of eq. 12 with the current knees.
  double kappa(double frameStrength) const;
  /// k_c and b_c after the device bounds.
  /// `dt_s` is the tick period (the stiffness bound scales with the rate).
  double effectiveStiffness_N_per_m(const DeviceCapabilities* caps, double dt_s = 0.001) const;
  double effectiveDamping_N_s_per_m(const DeviceCapabilities* caps) const;
  /// The tracer trailing distance that realizes the tangent drag threshold, pixels.
  double tangentTrail_px(const DeviceCapabilities* caps,
    double pixelsPerHandMm,
    double dt_s = 0.001) const;
  /// The frame used in the last tick (tangent), for display and tests.
  Vec2 frameTangent() const { return this->Tangent; }

private:
  Vec2 Tangent{ 1.0, 0.0 };
  bool HasFrame = false;
};

} // namespace vtouch

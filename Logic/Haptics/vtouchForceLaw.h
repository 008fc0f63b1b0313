// The one interface every force law implements, and what the haptic tick hands to it.
#pragma once

#include "vtouchDeviceTypes.h"
#include "vtouchTracer.h"
#include "vtouchViewModel.h"

#include <cstdint>
#include <limits>

namespace vtouch
{

/// The force laws, switchable at run time (values are stable: they are stored in settings/Python).
enum class ForceLawId : std::uint8_t
{
  Ldgf = 0,            ///< Yi & Hayward lateral depth gradient force, eq. 2
  ChangeOfHeight = 1,  ///< Hayward & Yi change of height, eq. 3, robust mu (Appendix A)
  LateralGradient = 2, ///< baseline: f = -k grad(height) of the centerline depth map, in the plane
  ConstraintProxy = 3, ///< Ikits et al.: proxy on a local frame + virtual coupler
  None = 4             ///< no force (free cursor everywhere)
};
constexpr int kForceLawCount = 5;
const char* toString(ForceLawId id);

/// Everything a force law may read in one tick. Frames: screen/device plane, x right, y up.
struct ForceInput
{
  const ViewModel* view = nullptr; ///< never null when a law is called
  InteractionState state = InteractionState::Exploring;
  AgentSample agent; ///< valid only while tracing
  /// Where the slope laws read dz, dl and eta (valid only while tracing, when hasSlope): the
  /// cursor's projection on the vessel within the tracer's dead band of the agent
  /// (Tracer::locationToward), so the slope field is a function of the hand's position and not
  /// of the dead band's history. Without it (hasSlope false) the agent's sample is used.
  AgentSample slope;
  bool hasSlope = false;
  const AgentSample& slopeSample() const { return this->hasSlope ? this->slope : this->agent; }
  Vec2 cursor_px;                    ///< cursor on the screen, pixels
  Vec2 handDelta_Device_mm;          ///< hand motion since the previous tick (device plane)
  Vec2 handVelocity_Device_mm_per_s; ///< from the device's velocity estimator
  double pixelsPerHandMm = 1.0;      ///< cursor pixels per hand millimetre (includes the zoom)
  double zoneGain_N = 0.0;           ///< k(P) from the force zones, newtons per unit slope
  double maxZoneGain_N = 0.0;        ///< k(P) in the saturation zone (its largest value), N
  double slopeWindow_mm = 1.0;       ///< the dz/dl stencil's 3D arc length w (SceneTopology)
  double agentArc_mm = 0.0;          ///< the agent's signed 3D arc position (Tracer::arcLength_mm)
  /// Signed 3D arc from the nearest bifurcation of the agent's path to the agent, mm (positive
  /// toward increasing index; NaN when the path has none). SceneTopology::bifurcationOffset_mm.
  double bifurcationOffset_mm = std::numeric_limits<double>::quiet_NaN();
  double zoneFraction = 0.0;                        ///< k(P) / gain in [0, 1] (scales spring laws)
  double dt_s = 0.001;                              ///< tick period
  const DeviceCapabilities* capabilities = nullptr; ///< may be null (no bounds applied)
};

/// What a law may ask of the tick besides a force.
struct ForceRequest
{
  int snapToPoint = -1; ///< >= 0: move the agent to this global point (pop-over to a vessel)
  /// Non-zero: move the agent along the vessel by this screen vector's projected arc (Ikits'
  /// eq. 11 snap-drag steps), pixels.
  Vec2 agentStep_px;
};

/// A force law. compute() runs in the haptic tick: it must not allocate, lock, log or throw.
/// Parameters are plain public fields documented in each law, set between ticks by the owner.
class ForceLaw
{
public:
  virtual ~ForceLaw() = default;
  virtual ForceLawId id() const = 0;
  /// Clears internal state (estimators, proxy offsets), e.g. on a new contact.
  virtual void reset() noexcept = 0;
  /// The force on the user's hand in the device plane, newtons.
  virtual Vec2 compute(const ForceInput& in, ForceRequest& request) noexcept = 0;
};

} // namespace vtouch

// One haptic tick, from a device sample to a force, as a plain deterministic object. The real-time
// loop and the offline session both call this (the same code path).
#pragma once

#include "vtouchAgentFrame.h"
#include "vtouchChangeOfHeightForceLaw.h"
#include "vtouchConstraintProxyForceLaw.h"
#include "vtouchContactGate.h"
#include "vtouchForceInterpolator.h"
#include "vtouchForceZones.h"
#include "vtouchIdleGate.h"
#include "vtouchHapticParameters.h"
#include "vtouchLateralGradientForceLaw.h"
#include "vtouchLdgfForceLaw.h"
#include "vtouchTracer.h"

#include <cstdint>

namespace vtouch
{

/// What the haptic thread publishes for the GUI (and records in the offline log).
struct AgentState
{
  double time_s = 0.0;
  std::uint64_t tick = 0;
  InteractionState state = InteractionState::Exploring;
  ForceLawId forceLaw = ForceLawId::Ldgf;
  bool reindexing = false;
  bool idle = false;         ///< a device without pressure left resting: force silenced (IdleGate)
  int path = -1;             ///< agent path (-1 when exploring)
  int point = -1;            ///< nearest point index within the path
  Vec2 cursor_px;            ///< cursor on screen (bottom-left origin)
  Vec2 agentScreen_px;       ///< agent on screen
  Vec3 position_World_mm;    ///< agent on the centerline, world frame
  Vec3 tangent_World;        ///< unit tangent at the agent
  int directionOfTravel = 0; ///< +1 toward increasing index, -1 decreasing, 0 at rest
  double torsionAngle_rad = 0.0; ///< accumulated torsion angle along the travelled arc
  /// The cone's roll about its apex (relative to agentConeMatrix()'s zero-roll reference): a
  /// rotation-minimising frame carried along the agent's path, rolled by the torsion angle
  /// accumulated since contact (Yi & Hayward §7; AgentFrame). 0 when exploring.
  double coneRoll_rad = 0.0;
  Vec3 coneNormal_World;   ///< the cone's rolled normal (unit; zero when exploring)
  double zoneGain_N = 0.0; ///< k(P)
  Vec2 targetForce_N;      ///< force law output (after crossfade), before interpolation
  Vec2 force_N;            ///< force sent to the device, device frame
  Vec2 hand_Device_mm;     ///< hand position as read
};

struct TickInput
{
  DeviceState device;
  const DeviceCapabilities* capabilities = nullptr;
  const ViewModel* view = nullptr; ///< may be null (no scene yet: exploring, zero force)
  double time_s = 0.0;
  double dt_s = 0.001;
};

/// Not thread-safe: owned by the one thread that ticks it. step() never allocates, locks, logs or
/// throws.
class HapticPipeline
{
public:
  HapticPipeline();

  /// One tick. The returned state carries the force to send (force_N; finite by construction).
  AgentState step(const TickInput& in, const HapticParameters& params) noexcept;
  /// Back to the initial state (cursor re-centred at the next tick, exploring, zero force).
  void reset() noexcept;
  /// Zero force at once (after a fault); keeps the cursor and agent.
  void zeroForce() noexcept;

  Tracer& tracer() { return this->Trace; }
  const ContactGate& contactGate() const { return this->Contact; }
  const Tracer& tracer() const { return this->Trace; }
  const ForceLaw& law(ForceLawId id) const { return *this->Laws[static_cast<int>(id)]; }
  ForceLaw& law(ForceLawId id) { return *this->Laws[static_cast<int>(id)]; }
  Vec2 cursor_px() const { return this->Cursor; }
  /// Places the cursor (scripting/tests); the next hand motion moves it from there.
  void setCursor_px(const Vec2& c)
  {
    this->Cursor = c;
    this->HasCursor = true;
  }

private:
  void applyParameters(const HapticParameters& p);
  Vec2 renderLaws(const ForceInput& fin, const HapticParameters& p, ForceRequest& req) noexcept;

  void release() noexcept;

  Tracer Trace;
  AgentFrame Frame;
  int LastApexSign = 1; // as agentApexDirection(): the last non-zero direction of travel
  ContactGate Contact;
  bool ContactNeedsReset = true;
  LdgfForceLaw Ldgf;
  ChangeOfHeightForceLaw ChangeOfHeight;
  LateralGradientForceLaw Lateral;
  ConstraintProxyForceLaw Proxy;
  ForceLaw* Laws[kForceLawCount] = {};
  ForceZones Zones;
  IdleGate Idle; // the zero-force zone of devices without pressure
  ForceInterpolator Interpolator;

  ForceLawId Active = ForceLawId::Ldgf;
  ForceLawId Previous = ForceLawId::Ldgf;
  double Fade = 1.0; // crossfade progress in [0, 1]
  Vec2 Cursor;
  bool HasCursor = false;
  Vec2 LastHand;
  bool HasHand = false;
  std::uint32_t LastButtons = 0;
  std::uint64_t Ticks = 0;
};

} // namespace vtouch

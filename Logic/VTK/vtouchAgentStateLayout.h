// The one layout of the agent state that vtkVesselTouchHapticSession::GetAgentState() publishes
// (a flat array of doubles, for the client-server wrapping) and every reader decodes: the panel's
// status, the agent display in C++, and vesseltouch.HapticSession.GetAgentState() in Python,
// which reads the same table as text (GetAgentStateLayout: "name:components:kind ...").
#pragma once

#include <cstddef>
#include <string>

namespace vtouch
{

/// First index of each field in the agent-state array.
enum AgentField : int
{
  AgentFieldTime_s = 0,            ///< tick time, s
  AgentFieldTick = 1,              ///< tick count
  AgentFieldState = 2,             ///< 0 exploring, 1 tracing
  AgentFieldForceLaw = 3,          ///< ForceLawId of the active law
  AgentFieldPath = 4,              ///< path traced (-1 none)
  AgentFieldPoint = 5,             ///< point index on that path
  AgentFieldCursor_px = 6,         ///< x, y: the cursor, px (bottom-left origin)
  AgentFieldPosition_World_mm = 8, ///< x, y, z: the agent, world mm
  AgentFieldTangent_World = 11,    ///< x, y, z: unit tangent of the path there
  AgentFieldDirection = 14,        ///< +1 along the path's point order, -1 against
  AgentFieldConeRoll_rad =
    15,                      ///< the cone's roll (rotation-minimising frame + integral of torsion)
  AgentFieldZoneGain_N = 16, ///< k(P) of the force zones
  AgentFieldForce_N = 17,    ///< x, y: force sent (screen = device axes), N
  AgentFieldTargetForce_N = 19,  ///< x, y: force before time-domain smoothing, N
  AgentFieldHand_Device_mm = 21, ///< x, y: the handle, device mm
  AgentFieldCount = 23
};

/// One field of the layout: its Python name, first index, component count and whether its
/// values are integers (counts, states, ids).
struct AgentStateField
{
  const char* name;
  int index;
  int components;
  bool integer;
};

inline constexpr AgentStateField kAgentStateFields[] = {
  { "time", AgentFieldTime_s, 1, false },
  { "tick", AgentFieldTick, 1, true },
  { "state", AgentFieldState, 1, true },
  { "force_law", AgentFieldForceLaw, 1, true },
  { "path", AgentFieldPath, 1, true },
  { "point", AgentFieldPoint, 1, true },
  { "cursor", AgentFieldCursor_px, 2, false },
  { "position", AgentFieldPosition_World_mm, 3, false },
  { "tangent", AgentFieldTangent_World, 3, false },
  { "direction", AgentFieldDirection, 1, true },
  { "torsion_angle", AgentFieldConeRoll_rad, 1, false },
  { "zone_gain", AgentFieldZoneGain_N, 1, false },
  { "force", AgentFieldForce_N, 2, false },
  { "target_force", AgentFieldTargetForce_N, 2, false },
  { "hand", AgentFieldHand_Device_mm, 2, false },
};

/// The table as text, "name:components:i|f" separated by spaces, in index order.
inline std::string agentStateLayoutText()
{
  std::string text;
  for (const AgentStateField& f : kAgentStateFields)
  {
    if (!text.empty())
    {
      text += ' ';
    }
    text +=
      std::string(f.name) + ':' + std::to_string(f.components) + ':' + (f.integer ? 'i' : 'f');
  }
  return text;
}

/// The fields tile [0, AgentFieldCount) in order, without gaps or overlaps (checked at compile
/// time).
constexpr bool agentStateFieldsTile()
{
  int next = 0;
  for (const AgentStateField& f : kAgentStateFields)
  {
    if (f.index != next || f.components < 1)
    {
      return false;
    }
    next += f.components;
  }
  return next == AgentFieldCount;
}
static_assert(agentStateFieldsTile(), "agent-state fields must tile the array in index order");

} // namespace vtouch

// The tracing agent of Yi & Hayward: exploring (free cursor) / tracing (agent on the centerline).
#pragma once

#include "vtouchViewModel.h"

#include <cstdint>

namespace vtouch
{

enum class InteractionState : std::uint8_t
{
  Exploring = 0, ///< the cursor moves freely; contact when within the capture radius of a vessel
  Tracing = 1    ///< the agent is constrained to the centerline and follows the cursor along it
};

/// Where the agent is: on the graph edge from point `from` to point `to`, at fraction `t` in [0, 1)
/// (t == 0 means exactly at `from`; `to` is then -1 or the last edge taken).
struct AgentLocation
{
  int from = -1;
  int to = -1;
  double t = 0.0;
  bool valid() const { return from >= 0; }
};

/// Interpolated view-model quantities at the agent (see ViewModel for conventions).
struct AgentSample
{
  Vec2 screen_px;
  Vec3 position_World_mm;
  Vec3 tangent_World;
  Vec2 eta; ///< unit, toward increasing point index
  double dz_mm =
    0.0; ///< stencil depth change toward increasing index (positive = away from viewer)
  double dl_mm = 0.0; ///< stencil screen arc length in mm
  double frameStrength = 0.0;
  double mmPerPixel = 0.0;
  double torsion_per_mm = 0.0;
  int point = -1; ///< nearest global point index
};

/// Not thread-safe; lives in the haptic tick. Never allocates, locks or throws.
class Tracer
{
public:
  /// Dead band (pixels): the agent stays still while the cursor's largest projection on the
  /// candidate directions is below it; once moving it trails the cursor's projection by this much
  /// (hysteresis: no stick-slip steps). Default 0.25 px.
  double deadBand_px = 0.25;
  /// Trailing distance (pixels, >= 0): the agent stops this far behind the cursor's projection
  /// (the drag threshold of Ikits' eq. 8 along the tangent; 0 = the agent catches up fully).
  double trail_px = 0.0;
  /// Direction hysteresis at projection cusps (a spiral seen edge-on, a vessel turning back in
  /// screen space), as a fraction of the cursor's distance to the agent, [0, 1]. When reversing
  /// would beat continuing in the current direction of travel by no more than this fraction of
  /// |cursor - agent| (the projections are nearly equal: the candidate directions nearly
  /// coincide on screen), the agent keeps its direction instead of flip-flopping. 0 = plain
  /// largest projection. Default 0.1 (directions within ~6 deg of each other).
  double directionHysteresis = 0.1;
  /// Screen arc length (pixels) searched ahead for a fold before a reversal is accepted: when the
  /// path within it turns back to the cursor (a smooth cusp sampled by many points), the agent
  /// crosses the fold instead of reversing. 0 disables. Default 3 px.
  double foldLookAhead_px = 3.0;
  /// Safety bound on graph steps per tick (a long jump is finished over the next ticks).
  int maxStepsPerTick = 4096;
  /// Contact refinement: after the O(1) contact-map lookup, the nearest point within this many
  /// points along the path is chosen. Default 16.
  int refineWindow = 16;

  InteractionState state() const { return this->State; }
  const AgentLocation& location() const { return this->Location; }
  /// +1 when the last motion went toward increasing point index, -1 toward decreasing, 0 at rest.
  int directionOfTravel() const { return this->Direction; }
  /// Accumulated torsion angle (radians): integral of torsion over the travelled 3D arc length.
  double torsionAngle_rad() const { return this->TorsionAngle; }
  /// Signed 3D arc length travelled (mm, + toward increasing index): where the agent is along the
  /// vessel, for tick-mark texture.
  double arcLength_mm() const { return this->ArcLength; }
  /// The topology the location refers to (0 when none).
  std::uint64_t topologyId() const { return this->TopologyId; }

  /// Returns to exploring (button click, new skeleton).
  void release();
  /// Exploring: makes contact when the contact map has a vessel under the cursor. Returns true
  /// when tracing starts.
  bool tryContact(const ViewModel& vm, const Vec2& cursor_px);
  /// Puts the agent on a given point (tests, scripting, snap-drag). Starts tracing.
  void placeAt(const ViewModel& vm, int globalPoint);
  /// Tracing: moves the agent along the centerline toward the cursor (see the .cxx for the rule).
  /// Returns the 2D screen arc length travelled this tick (pixels).
  double follow(const ViewModel& vm, const Vec2& cursor_px);
  /// Tracing, Yi & Hayward §3.2.1 as written: this tick's cursor-movement vector (previous to
  /// updated cursor, pixels) is projected on the candidate directions at the agent (lower and
  /// higher index, and every branch joining there); the agent takes the largest projection, stays
  /// put when it is below `movementThreshold_px`, and travels the screen arc length the projection
  /// subtends, point by point (at each point it goes on along the candidate best aligned with the
  /// movement, never straight back). Returns the screen arc length travelled (pixels).
  double followMovement(const ViewModel& vm, const Vec2& movement_px);
  /// Threshold of followMovement(): smaller per-tick projections leave the agent still, px.
  double movementThreshold_px = 0.01;
  /// The branch choice at a junction follows the hand (both rules). Yi & Hayward §3.2.1 project
  /// each tick's cursor movement on the candidate directions at the junction; for a shallow
  /// branch the projections differ by less than the hand's tremor (10 degrees: cos 10 = 0.985),
  /// so the choice made in the tick the agent passes the junction is a guess. While the agent is
  /// within this screen arc of the last junction it passed, the cursor's movement since that tick
  /// is projected on every candidate leaving the junction (all but the one the agent came in on;
  /// each candidate's direction is its chord from the junction to where the movement has reached
  /// along it); when another candidate beats the one taken, its perpendicular residual smaller
  /// by junctionMargin_px, the agent goes back through the junction and on along it, as far from
  /// the junction as it was. Movement, not position, decides (as in the paper): a hand that runs
  /// alongside the parent a few pixels off it does not fall into a shallow branch on that side.
  /// 0 disables (the choice at the junction is final). Default 24 px.
  double junctionWindow_px = 24.0;
  /// How much smaller the other candidate's residual must be to re-route, px (a hysteresis
  /// against the hand's tremor). Default 1 px.
  double junctionMargin_px = 1.0;
  /// The last junction passed and the branch taken there (-1 when none is within the window).
  int lastJunction() const { return this->Junction.point; }
  /// Re-routes the agent when the cursor follows another candidate of the last junction (see
  /// junctionWindow_px). follow() and followMovement() call it; returns the screen arc travelled.
  double reconsiderJunction(const ViewModel& vm, const Vec2& cursor_px);

  /// Interpolated quantities at the agent. Requires a valid location.
  AgentSample sample(const ViewModel& vm) const;
  /// Where the cursor projects on the vessel, within `reach_px` of screen arc of the agent: the
  /// agent's location moved along the path (straight on through points, never into a branch) by
  /// the cursor offset's projection on the local screen tangent, clamped to `reach_px`. With
  /// reach_px = deadBand_px this is the agent without the dead band's backlash: the offset rule's
  /// agent trails the cursor's projection by the dead band once moving and stays still within
  /// it, so the agent is a hysteretic function of the hand, while this location is a function of
  /// the cursor alone. The slope laws sample dz, dl and eta here (HapticPipeline): a force field
  /// read through a lag that reverses with the hand's direction does net work on the hand every
  /// back-and-forth cycle (a negative Coulomb friction of 2 x dead band x the field's gradient)
  /// and sustains a limit cycle against a soft grip where the field is steep. Requires a valid
  /// location. `arcOffset_mm` (optional): the signed 3D arc from the agent to it (+ toward
  /// increasing index, as arcLength_mm()).
  AgentLocation locationToward(const ViewModel& vm,
    const Vec2& cursor_px,
    double reach_px,
    double* arcOffset_mm = nullptr) const;
  /// Interpolated quantities at a location on the graph (as sample() at the agent).
  static AgentSample sampleAt(const ViewModel& vm, const AgentLocation& location);

private:
  Vec2 directionTo(const ViewModel& vm, int a, int m) const;
  double advance(const ViewModel& vm, int a, int b, double fromT, double toT);
  /// A reversal of `reverseProj_px` is requested: looks ahead along the direction of travel
  /// (no junction, at most foldLookAhead_px of screen arc) for a point where the path has folded
  /// back to the cursor. True with that point and its neighbour behind it.
  bool foldAhead(const ViewModel& vm,
    const Vec2& cursor_px,
    const Vec2& here_px,
    double reverseProj_px,
    int* pointOut,
    int* behindOut) const;
  /// Moves the agent forward along the chain to `point` (found by foldAhead()).
  double crossFold(const ViewModel& vm, int point, int behind);

  /// A chain of points leaving junction `point` through `first` (straight on, up to `window_px` of
  /// screen arc, stopping at another junction or a path end), written to `out` (capacity `cap`):
  /// its length and screen arc, and the agent's segment on it (-1 when the agent is not on it).
  struct ChainFit
  {
    int count = 0;
    double arc_px = 0.0;
    int agentSegment = -1;
    double agentFraction = 0.0;
    double agentArc_px = 0.0;
  };
  ChainFit fitChain(const ViewModel& vm, int point, int first, double window_px, int* out, int cap)
    const;
  /// Where screen arc `arc_px` falls on a chain: segment index and fraction.
  static void chainAt(const ViewModel& vm,
    const int* chain,
    int count,
    double arc_px,
    int* segment,
    double* fraction);
  struct JunctionChoice
  {
    int point = -1; ///< the junction (a point with more than two neighbours)
    int entry = -1; ///< the neighbour the agent came in from (-1 unknown)
    int taken = -1; ///< the neighbour it left through
    bool hasCursor = false;
    Vec2 cursor_px; ///< the cursor in the tick the agent passed it
  };
  JunctionChoice Junction;
  int ArrivedAt = -1;   ///< the last point the agent reached...
  int ArrivedFrom = -1; ///< ...and the neighbour it came from

  InteractionState State = InteractionState::Exploring;
  AgentLocation Location;
  int Direction = 0;
  double TorsionAngle = 0.0;
  double ArcLength = 0.0;
  std::uint64_t TopologyId = 0;
};

} // namespace vtouch

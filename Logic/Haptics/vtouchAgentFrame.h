// The cone's roll about the vessel (Yi & Hayward §7: "the torsion can be provided to the user
// graphically by a rotation of the agent along the local tangent"), from a rotation-minimising
// frame carried along the agent's path and the integrated torsion.
#pragma once

#include "vtouchVector.h"

namespace vtouch
{

/// Carries a rotation-minimising frame (RMF) along the agent's positions by the double reflection
/// method (Wang, Juettler, Zheng, Liu 2008, "Computation of rotation minimizing frames", ACM TOG
/// 27(1)), and rolls it by the accumulated torsion angle theta = integral of tau ds. An RMF has no
/// twist of its own, so the rolled normal turns about the tangent at exactly the rate tau, which is
/// what the cone shows. (Measuring the roll from a fixed world axis, as before, adds the world
/// frame's own rotation about the tangent: on a helix it counted the twist twice.)
///
/// Not thread-safe; lives in the haptic tick. Never allocates, locks or throws.
class AgentFrame
{
public:
  /// Forget the frame (a new contact starts a new one).
  void reset() noexcept { this->Valid = false; }
  /// One agent sample: position, unit tangent toward increasing index, torsion angle (Tracer),
  /// and the sign of the cone's apex along the tangent (+1 or -1, see agentApexDirection()).
  void update(const Vec3& position_World_mm,
    const Vec3& tangent_World,
    double torsionAngle_rad,
    int apexSign) noexcept;

  bool valid() const { return this->Valid; }
  /// The RMF normal (unit, perpendicular to the tangent), before the torsion roll.
  const Vec3& rmfNormal_World() const { return this->Normal; }
  /// The cone's normal: the RMF normal rolled by the torsion angle accumulated since contact.
  const Vec3& coneNormal_World() const { return this->ConeNormal; }
  /// The same as a roll about the apex, relative to the zero-roll reference of agentConeMatrix()
  /// (Logic/View): the angle to pass it so that the cone's first axis is coneNormal_World().
  double coneRoll_rad() const { return this->ConeRoll; }

  /// agentConeMatrix()'s zero-roll reference for an apex direction d (unit): world +Z made
  /// perpendicular to d, or +X when d is within ~25 degrees of Z. Kept identical to it (test
  /// AgentFrame.ConeRollReproducesConeNormalThroughAgentConeMatrix).
  static Vec3 zeroRollReference(const Vec3& d);

private:
  bool Valid = false;
  Vec3 Position;
  Vec3 Tangent;
  Vec3 Normal;
  Vec3 ConeNormal;
  double Theta0 = 0.0;
  double ConeRoll = 0.0;
};

} // namespace vtouch

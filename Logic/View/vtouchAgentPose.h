// The pose of the tracing agent drawn over the MIP: a cone whose apex points along the direction
// of travel (so its blue base shows when the vessel runs away from the viewer), rolled about its
// axis by the torsion angle, sized to a constant height on screen. Plain C++17 so that it is
// tested alone; the ParaView agent display writes the matrix into a vtkMatrix4x4.
#pragma once

#include "vtouchVector.h"

#include <array>

namespace vtouch
{

/// Row-major 4x4 matrix (as vtkMatrix4x4 stores it).
using Matrix4x4 = std::array<double, 16>;

/// The model matrix of the unit agent cone (axis +Z, centre at the origin, height 1) placed at
/// `centre_World_mm`, its apex along `direction_World` (any non-zero length), rolled by
/// `roll_rad` about it, scaled to `height_mm` (the session publishes as roll a rotation-minimising
/// frame rolled by the integrated torsion, vtouch::AgentFrame, expressed against this function's
/// reference, so the cone turns about the vessel at the rate tau). The zero-roll reference is world
/// +Z made perpendicular to the axis (+X when the axis is within ~25 degrees of Z), as in
/// vesseltouch.agent_view.agent_matrix. Returns false (and leaves `matrix` unchanged) for a zero
/// or non-finite direction, a non-finite centre or roll, or a height that is not > 0.
bool agentConeMatrix(const Vec3& centre_World_mm,
  const Vec3& direction_World,
  double roll_rad,
  double height_mm,
  Matrix4x4& matrix);

/// The apex direction of the agent from the session's published state: the centerline tangent
/// times the direction of travel (+1 toward increasing point index, -1 decreasing). A direction of
/// travel of 0 (at rest) keeps `lastDirectionOfTravel` (+1 or -1), which it updates otherwise.
Vec3 agentApexDirection(const Vec3& tangent_World,
  int directionOfTravel,
  int& lastDirectionOfTravel);

/// Camera description enough to size things on screen.
struct ScreenScale
{
  bool parallelProjection = true;
  double parallelScale_mm = 1.0; ///< half the view height, mm (parallel projection)
  double viewAngle_deg = 30.0;   ///< vertical view angle (perspective)
  double viewportHeight_px = 600.0;
};

/// World millimetres per screen pixel at `depth_mm` from the camera (ignored for a parallel
/// projection). Returns 0 for an unusable description.
double millimetresPerPixel(const ScreenScale& scale, double depth_mm);

/// Tip of the on-screen force arrow, px: the arrow starts at `origin_px` and is `pixelsPerNewton`
/// long per newton of `force_Device_N` (device x right, y up, as the screen), clamped to
/// `maximumLength_px`.
Vec2 forceArrowTip_px(const Vec2& origin_px,
  const Vec2& force_Device_N,
  double pixelsPerNewton,
  double maximumLength_px);

} // namespace vtouch

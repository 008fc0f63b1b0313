#include "vtouchAgentPose.h"

#include <cmath>

namespace vtouch
{
namespace
{
constexpr double kPi = 3.14159265358979323846;

bool isUsable(const Vec3& v)
{
  const double n = v.norm();
  return std::isfinite(n) && n > 0.0;
}
} // namespace

bool agentConeMatrix(const Vec3& centre_World_mm,
  const Vec3& direction_World,
  double roll_rad,
  double height_mm,
  Matrix4x4& matrix)
{
  if (!isUsable(direction_World) || !centre_World_mm.isFinite() || !std::isfinite(roll_rad) ||
      !(height_mm > 0.0) || !std::isfinite(height_mm))
  {
    return false;
  }
  const Vec3 d = direction_World * (1.0 / direction_World.norm());
  const Vec3 reference = std::abs(d.z) < 0.9 ? Vec3{ 0.0, 0.0, 1.0 } : Vec3{ 1.0, 0.0, 0.0 };
  const Vec3 r = reference - d * reference.dot(d);
  const Vec3 u0 = r * (1.0 / r.norm());
  const Vec3 v0 = d.cross(u0);
  const double c = std::cos(roll_rad);
  const double s = std::sin(roll_rad);
  const Vec3 u = u0 * c + v0 * s;
  const Vec3 v = d.cross(u);
  const double columns[3][3] = { { u.x, u.y, u.z }, { v.x, v.y, v.z }, { d.x, d.y, d.z } };
  const double centre[3] = { centre_World_mm.x, centre_World_mm.y, centre_World_mm.z };
  for (int row = 0; row < 3; ++row)
  {
    for (int column = 0; column < 3; ++column)
    {
      matrix[4 * row + column] = height_mm * columns[column][row];
    }
    matrix[4 * row + 3] = centre[row];
  }
  matrix[12] = matrix[13] = matrix[14] = 0.0;
  matrix[15] = 1.0;
  return true;
}

Vec3 agentApexDirection(const Vec3& tangent_World,
  int directionOfTravel,
  int& lastDirectionOfTravel)
{
  if (directionOfTravel != 0)
  {
    lastDirectionOfTravel = directionOfTravel > 0 ? 1 : -1;
  }
  const double sign = lastDirectionOfTravel < 0 ? -1.0 : 1.0;
  return tangent_World * sign;
}

double millimetresPerPixel(const ScreenScale& scale, double depth_mm)
{
  if (!(scale.viewportHeight_px > 0.0))
  {
    return 0.0;
  }
  double viewHeight_mm = 0.0;
  if (scale.parallelProjection)
  {
    viewHeight_mm = 2.0 * scale.parallelScale_mm;
  }
  else
  {
    viewHeight_mm = 2.0 * depth_mm * std::tan(0.5 * scale.viewAngle_deg * kPi / 180.0);
  }
  const double mmPerPx = viewHeight_mm / scale.viewportHeight_px;
  return std::isfinite(mmPerPx) && mmPerPx > 0.0 ? mmPerPx : 0.0;
}

Vec2 forceArrowTip_px(const Vec2& origin_px,
  const Vec2& force_Device_N,
  double pixelsPerNewton,
  double maximumLength_px)
{
  if (!force_Device_N.isFinite() || !std::isfinite(pixelsPerNewton))
  {
    return origin_px;
  }
  Vec2 arrow = force_Device_N * pixelsPerNewton;
  const double length = arrow.norm();
  if (length > maximumLength_px && length > 0.0)
  {
    arrow = arrow * (maximumLength_px / length);
  }
  return origin_px + arrow;
}

} // namespace vtouch

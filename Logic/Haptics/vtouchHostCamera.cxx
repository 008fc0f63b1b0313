#include "vtouchHostCamera.h"

#include <cmath>

namespace vtouch
{

Mat4 identityMatrix()
{
  return { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 };
}

Mat4 multiply(const Mat4& a, const Mat4& b)
{
  Mat4 c{};
  for (int col = 0; col < 4; ++col)
  {
    for (int row = 0; row < 4; ++row)
    {
      double s = 0.0;
      for (int k = 0; k < 4; ++k)
      {
        s += a[k * 4 + row] * b[col * 4 + k];
      }
      c[col * 4 + row] = s;
    }
  }
  return c;
}

bool HostCamera::isOrthographic() const
{
  const Mat4& p = this->projection_EyeToClip;
  return p[3] == 0.0 && p[7] == 0.0 && p[11] == 0.0 && p[15] == 1.0;
}

Vec3 HostCamera::worldToEye(const Vec3& p) const
{
  const Mat4& m = this->view_WorldToEye;
  return { m[0] * p.x + m[4] * p.y + m[8] * p.z + m[12],
    m[1] * p.x + m[5] * p.y + m[9] * p.z + m[13],
    m[2] * p.x + m[6] * p.y + m[10] * p.z + m[14] };
}

bool HostCamera::eyeToScreen(const Vec3& e, Vec2& screen_px) const
{
  const Mat4& m = this->projection_EyeToClip;
  const double cx = m[0] * e.x + m[4] * e.y + m[8] * e.z + m[12];
  const double cy = m[1] * e.x + m[5] * e.y + m[9] * e.z + m[13];
  const double cw = m[3] * e.x + m[7] * e.y + m[11] * e.z + m[15];
  if (!(cw > 0.0))
  {
    return false;
  }
  screen_px.x = (cx / cw * 0.5 + 0.5) * this->viewportWidth_px;
  screen_px.y = (cy / cw * 0.5 + 0.5) * this->viewportHeight_px;
  return true;
}

double HostCamera::mmPerPixelAt(double distance_mm) const
{
  const Mat4& m = this->projection_EyeToClip;
  // Clip y per eye y is m[5]; for a perspective camera w = -z_eye = distance.
  const double w = this->isOrthographic() ? 1.0 : distance_mm;
  return 2.0 * w / (m[5] * this->viewportHeight_px);
}

const char* HostCamera::validate() const
{
  for (int i = 0; i < 16; ++i)
  {
    if (!std::isfinite(this->view_WorldToEye[i]) || !std::isfinite(this->projection_EyeToClip[i]))
    {
      return "camera matrices contain non-finite values";
    }
  }
  if (this->viewportWidth_px <= 0 || this->viewportHeight_px <= 0)
  {
    return "viewport must be at least one pixel";
  }
  if (this->projection_EyeToClip[0] == 0.0 || this->projection_EyeToClip[5] == 0.0)
  {
    return "projection matrix is singular";
  }
  return "";
}

namespace
{
Vec3 normalized(const Vec3& v)
{
  const double n = v.norm();
  return n > 0.0 ? v * (1.0 / n) : v;
}
} // namespace

Mat4 lookAt(const Vec3& position, const Vec3& focalPoint, const Vec3& viewUp)
{
  const Vec3 f = normalized(focalPoint - position); // view direction, becomes -z
  const Vec3 s = normalized(f.cross(viewUp));       // right, becomes +x
  const Vec3 u = s.cross(f);                        // up, becomes +y
  Mat4 m = identityMatrix();
  m[0] = s.x;
  m[4] = s.y;
  m[8] = s.z;
  m[1] = u.x;
  m[5] = u.y;
  m[9] = u.z;
  m[2] = -f.x;
  m[6] = -f.y;
  m[10] = -f.z;
  m[12] = -s.dot(position);
  m[13] = -u.dot(position);
  m[14] = f.dot(position);
  return m;
}

Mat4 orthographic(double parallelScale_mm, double aspect, double near_mm, double far_mm)
{
  Mat4 m = identityMatrix();
  m[0] = 1.0 / (parallelScale_mm * aspect);
  m[5] = 1.0 / parallelScale_mm;
  m[10] = -2.0 / (far_mm - near_mm);
  m[14] = -(far_mm + near_mm) / (far_mm - near_mm);
  return m;
}

Mat4 perspective(double viewAngle_deg, double aspect, double near_mm, double far_mm)
{
  const double f = 1.0 / std::tan(viewAngle_deg * 3.14159265358979323846 / 360.0);
  Mat4 m{};
  m[0] = f / aspect;
  m[5] = f;
  m[10] = (far_mm + near_mm) / (near_mm - far_mm);
  m[11] = -1.0;
  m[14] = 2.0 * far_mm * near_mm / (near_mm - far_mm);
  return m;
}

HostCamera makeOrthographicCamera(const Vec3& focalPoint,
  const Vec3& directionOfProjection,
  const Vec3& viewUp,
  double parallelScale_mm,
  int width_px,
  int height_px)
{
  HostCamera cam;
  const double distance = 1000.0;
  const Vec3 dop = normalized(directionOfProjection);
  cam.view_WorldToEye = lookAt(focalPoint - dop * distance, focalPoint, viewUp);
  cam.projection_EyeToClip = orthographic(parallelScale_mm,
    static_cast<double>(width_px) / static_cast<double>(height_px),
    1.0,
    2.0 * distance);
  cam.viewportWidth_px = width_px;
  cam.viewportHeight_px = height_px;
  return cam;
}

} // namespace vtouch

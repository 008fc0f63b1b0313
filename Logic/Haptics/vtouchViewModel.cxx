#include "vtouchViewModel.h"

#include <algorithm>
#include <cmath>

namespace vtouch
{

void ViewModel::setCamera(const HostCamera& camera)
{
  this->Camera = camera;
  const Mat4& v = camera.view_WorldToEye;
  this->EyeX = { v[0], v[4], v[8] };
  this->EyeY = { v[1], v[5], v[9] };
  this->EyeZ = { v[2], v[6], v[10] };
  this->EyeZOffset = v[14];
  this->MmPerPixelOrtho = camera.isOrthographic() ? camera.mmPerPixelAt(1.0) : 0.0;
  this->Window_mm = this->Topology ? this->Topology->slopeWindow_mm() : 1.0;
}

Vec2 ViewModel::eta(int g) const
{
  const Vec3& d = this->Topology->tangentEstimate(g);
  const double dx = this->EyeX.dot(d);
  const double dy = this->EyeY.dot(d);
  const double n = std::hypot(dx, dy);
  if (n > 1e-9)
  {
    return { dx / n, dy / n };
  }
  const Vec3& t = this->Topology->tangent_World(g);
  const double tx = this->EyeX.dot(t);
  const double ty = this->EyeY.dot(t);
  const double tn = std::hypot(tx, ty);
  return tn > 1e-9 ? Vec2{ tx / tn, ty / tn } : Vec2{};
}

double ViewModel::frameStrength(int g) const
{
  const Vec3& t = this->Topology->tangent_World(g);
  const double n = t.norm();
  if (!(n > 0.0))
  {
    return 0.0;
  }
  return std::min(1.0, std::hypot(this->EyeX.dot(t), this->EyeY.dot(t)) / n);
}

double ViewModel::mmPerPixel(int g) const
{
  if (this->MmPerPixelOrtho > 0.0)
  {
    return this->MmPerPixelOrtho;
  }
  return this->Camera.mmPerPixelAt(this->depth_mm(g));
}

} // namespace vtouch

#include "vtouchAgentFrame.h"

#include <cmath>

namespace vtouch
{
namespace
{
Vec3 unit(const Vec3& v, const Vec3& fallback)
{
  const double n = v.norm();
  return (std::isfinite(n) && n > 1e-12) ? v * (1.0 / n) : fallback;
}

/// v made perpendicular to the unit t, normalised (fallback: any perpendicular).
Vec3 perpendicular(const Vec3& v, const Vec3& t)
{
  const Vec3 r = v - t * v.dot(t);
  if (r.norm() > 1e-9)
  {
    return r * (1.0 / r.norm());
  }
  return AgentFrame::zeroRollReference(t);
}
} // namespace

Vec3 AgentFrame::zeroRollReference(const Vec3& d)
{
  const Vec3 reference = std::abs(d.z) < 0.9 ? Vec3{ 0.0, 0.0, 1.0 } : Vec3{ 1.0, 0.0, 0.0 };
  const Vec3 r = reference - d * reference.dot(d);
  return unit(r, Vec3{ 1.0, 0.0, 0.0 });
}

void AgentFrame::update(const Vec3& x, const Vec3& tangent, double theta, int apexSign) noexcept
{
  if (!x.isFinite() || !tangent.isFinite() || !std::isfinite(theta) || !(tangent.norm() > 0.0))
  {
    return;
  }
  const Vec3 t = tangent * (1.0 / tangent.norm());
  if (!this->Valid)
  {
    // A new contact: the RMF starts at the cone's zero-roll reference, the roll at zero.
    this->Normal = zeroRollReference(t);
    this->Theta0 = theta;
    this->Valid = true;
  }
  else
  {
    // Double reflection: reflect (r, t) in the plane bisecting the chord x_i -> x_{i+1}, then in
    // the plane that maps the reflected tangent onto t_{i+1}.
    Vec3 r = this->Normal;
    Vec3 tl = this->Tangent;
    const Vec3 v1 = x - this->Position;
    const double c1 = v1.dot(v1);
    if (c1 > 1e-18)
    {
      r = r - v1 * (2.0 / c1 * v1.dot(r));
      tl = tl - v1 * (2.0 / c1 * v1.dot(tl));
    }
    const Vec3 v2 = t - tl;
    const double c2 = v2.dot(v2);
    if (c2 > 1e-18)
    {
      r = r - v2 * (2.0 / c2 * v2.dot(r));
    }
    this->Normal = perpendicular(r, t); // removes rounding drift
  }
  this->Position = x;
  this->Tangent = t;
  const double angle = theta - this->Theta0;
  const Vec3 b = t.cross(this->Normal);
  this->ConeNormal = this->Normal * std::cos(angle) + b * std::sin(angle);
  // The roll agentConeMatrix() needs: the angle from its reference u0 to the cone normal about
  // the apex d (its second axis is v0 = d x u0).
  const Vec3 d = apexSign < 0 ? t * -1.0 : t;
  const Vec3 u0 = zeroRollReference(d);
  const Vec3 v0 = d.cross(u0);
  this->ConeRoll = std::atan2(this->ConeNormal.dot(v0), this->ConeNormal.dot(u0));
}

} // namespace vtouch

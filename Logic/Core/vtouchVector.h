// Small fixed-size vectors shared by every layer. Plain aggregates: no allocation, trivially
// copyable, safe to publish between threads by value.
#pragma once

#include <cmath>

namespace vtouch
{

struct Vec2
{
  double x = 0.0;
  double y = 0.0;

  constexpr Vec2 operator+(const Vec2& o) const { return { x + o.x, y + o.y }; }
  constexpr Vec2 operator-(const Vec2& o) const { return { x - o.x, y - o.y }; }
  constexpr Vec2 operator*(double s) const { return { x * s, y * s }; }
  constexpr double dot(const Vec2& o) const { return x * o.x + y * o.y; }
  double norm() const { return std::hypot(x, y); }
  bool isFinite() const { return std::isfinite(x) && std::isfinite(y); }
};

struct Vec3
{
  double x = 0.0;
  double y = 0.0;
  double z = 0.0;

  constexpr Vec3 operator+(const Vec3& o) const { return { x + o.x, y + o.y, z + o.z }; }
  constexpr Vec3 operator-(const Vec3& o) const { return { x - o.x, y - o.y, z - o.z }; }
  constexpr Vec3 operator*(double s) const { return { x * s, y * s, z * s }; }
  constexpr double dot(const Vec3& o) const { return x * o.x + y * o.y + z * o.z; }
  constexpr Vec3 cross(const Vec3& o) const
  {
    return { y * o.z - z * o.y, z * o.x - x * o.z, x * o.y - y * o.x };
  }
  double norm() const { return std::sqrt(x * x + y * y + z * z); }
  bool isFinite() const { return std::isfinite(x) && std::isfinite(y) && std::isfinite(z); }
};

} // namespace vtouch

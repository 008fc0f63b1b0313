#include "vtouchPhantomClutter.h"

#include "vtouchPhantomRandom.h"

#include <algorithm>
#include <cmath>

namespace vtouch
{
namespace
{
constexpr double kPi = 3.14159265358979323846;

Vec3 normalized(const Vec3& v)
{
  const double n = v.norm();
  return n > 0.0 ? v * (1.0 / n) : Vec3{ 1.0, 0.0, 0.0 };
}

struct Local
{
  double c[3];
};

Local toLocal(const PhantomClutter::Object& o, const Vec3& p)
{
  const Vec3 d = p - o.centre_World_mm;
  return { { d.dot(o.axes[0]), d.dot(o.axes[1]), d.dot(o.axes[2]) } };
}
} // namespace

bool PhantomClutter::Object::contains(const Vec3& p) const
{
  const Local l = toLocal(*this, p);
  if (this->plate)
  {
    return std::abs(l.c[0]) <= this->halfSize_mm[0] && std::abs(l.c[1]) <= this->halfSize_mm[1] &&
           std::abs(l.c[2]) <= this->halfSize_mm[2];
  }
  double k2 = 0.0;
  for (int a = 0; a < 3; ++a)
  {
    const double q = l.c[a] / this->halfSize_mm[a];
    k2 += q * q;
  }
  return k2 <= 1.0;
}

double PhantomClutter::Object::signedDistanceBound_mm(const Vec3& p) const
{
  const Local l = toLocal(*this, p);
  if (this->plate)
  {
    // Exact signed distance to a box.
    double outside2 = 0.0;
    double inside = -1e300;
    for (int a = 0; a < 3; ++a)
    {
      const double q = std::abs(l.c[a]) - this->halfSize_mm[a];
      outside2 += q > 0.0 ? q * q : 0.0;
      inside = std::max(inside, q);
    }
    return outside2 > 0.0 ? std::sqrt(outside2) : inside;
  }
  double k2 = 0.0;
  double smallest = this->halfSize_mm[0];
  for (int a = 0; a < 3; ++a)
  {
    const double q = l.c[a] / this->halfSize_mm[a];
    k2 += q * q;
    smallest = std::min(smallest, this->halfSize_mm[a]);
  }
  return (std::sqrt(k2) - 1.0) * smallest;
}

void PhantomClutter::Object::bounds(Vec3& lo, Vec3& hi) const
{
  Vec3 reach{ 0, 0, 0 };
  for (int a = 0; a < 3; ++a)
  {
    const Vec3& u = this->axes[a];
    reach = reach + Vec3{ std::abs(u.x), std::abs(u.y), std::abs(u.z) } * this->halfSize_mm[a];
  }
  lo = this->centre_World_mm - reach;
  hi = this->centre_World_mm + reach;
}

PhantomClutter::PhantomClutter(const PhantomSpec& spec, const QSkeleton& tree)
{
  if (spec.clutterCount <= 0 || tree.empty())
  {
    return;
  }
  const double voxel = std::min({ spec.spacing_mm[0], spec.spacing_mm[1], spec.spacing_mm[2] });
  const double n = spec.referenceLength_mm();
  const double overlap = 0.5 * voxel;

  // Candidate contacts (every point of a vessel of radius >= 0.75 voxel: uniform in arc length)
  // and the test points (about one per voxel of every vessel).
  struct Point
  {
    Vec3 p;
    Vec3 t;
    double r;
    int path;
  };
  std::vector<Point> contacts;
  std::vector<Point> tests;
  for (const SkeletonPath& path : tree.paths)
  {
    const int stride = std::max(1, static_cast<int>(path.points.size() / 4096));
    for (std::size_t i = 0; i < path.points.size(); i += stride)
    {
      const SkeletonPoint& s = path.points[i];
      const Point pt{ s.position_World_mm, s.tangent_World, s.radius_mm, path.id };
      if (s.radius_mm >= 0.75 * voxel)
      {
        contacts.push_back(pt);
      }
      if (i % 4 == 0 || i + 1 == path.points.size())
      {
        tests.push_back(pt);
      }
    }
  }
  if (contacts.empty())
  {
    return;
  }
  const SkeletonPoint& seed = tree.paths.front().points.front();

  PhantomRandom random(0xC1A7u + 104729ull * spec.seed);
  for (int rank = 0; rank < spec.clutterCount; ++rank)
  {
    for (int attempt = 0; attempt < 200; ++attempt)
    {
      const Point& c = contacts[random.index(static_cast<int>(contacts.size()))];
      // A random direction perpendicular to the vessel: from the object toward the vessel.
      Vec3 side = random.direction();
      side = normalized(side - c.t * side.dot(c.t));
      Object o;
      o.plate = rank % 2 == 0;
      o.touchedPath = c.path;
      o.contact_World_mm = c.p;
      o.axes[0] = side * -1.0;
      const Vec3 roll = normalized(c.t - side * c.t.dot(side));
      const double angle = random.uniform(0.0, kPi);
      o.axes[1] = normalized(roll * std::cos(angle) + side.cross(roll) * std::sin(angle));
      o.axes[2] = o.axes[0].cross(o.axes[1]);
      if (o.plate)
      {
        o.halfSize_mm[0] = random.uniform(1.5, 3.0) * voxel;
        o.halfSize_mm[1] = std::min(random.uniform(6.0, 16.0) * voxel, 0.15 * n);
        o.halfSize_mm[2] = std::min(random.uniform(6.0, 16.0) * voxel, 0.15 * n);
      }
      else
      {
        o.halfSize_mm[0] = random.uniform(2.5, 6.0) * voxel;
        o.halfSize_mm[1] = o.halfSize_mm[0] * random.uniform(1.0, 1.8);
        o.halfSize_mm[2] = o.halfSize_mm[0] * random.uniform(1.0, 1.8);
      }
      o.centre_World_mm = c.p + side * (c.r - overlap + o.halfSize_mm[0]);
      bool ok = o.signedDistanceBound_mm(seed.position_World_mm) >= seed.radius_mm + 2.0 * voxel;
      for (std::size_t i = 0; ok && i < tests.size(); ++i)
      {
        const Point& q = tests[i];
        const double d = o.signedDistanceBound_mm(q.p);
        ok = q.path == c.path ? d >= q.r - overlap - 0.25 * voxel : d >= q.r + voxel;
      }
      for (std::size_t i = 0; ok && i < this->Objects.size(); ++i)
      {
        // Objects do not pile on each other (each is its own piece of clutter).
        Vec3 lo1, hi1, lo2, hi2;
        o.bounds(lo1, hi1);
        this->Objects[i].bounds(lo2, hi2);
        ok = lo1.x > hi2.x || lo2.x > hi1.x || lo1.y > hi2.y || lo2.y > hi1.y || lo1.z > hi2.z ||
             lo2.z > hi1.z;
      }
      if (ok)
      {
        this->Objects.push_back(o);
        break;
      }
    }
  }
}

bool PhantomClutter::contains(const Vec3& p) const
{
  return std::any_of(
    this->Objects.begin(), this->Objects.end(), [&](const Object& o) { return o.contains(p); });
}

} // namespace vtouch

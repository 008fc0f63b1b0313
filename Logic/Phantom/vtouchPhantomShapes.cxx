#include "vtouchPhantomShapes.h"

#include "vtouchArcLengthTable.h"
#include "vtouchVascularTreeGenerator.h"

#include <algorithm>
#include <cmath>
#include <functional>

namespace vtouch
{
namespace
{
constexpr double kPi = 3.14159265358979323846;

using CurveFunction = std::function<Vec3(double)>;

Vec3 normalized(const Vec3& v)
{
  const double n = v.norm();
  return n > 0.0 ? v * (1.0 / n) : Vec3{ 1.0, 0.0, 0.0 };
}

/// Rotates v about the unit axis by angle (Rodrigues).
Vec3 rotate(const Vec3& v, const Vec3& axis, double angle)
{
  const double c = std::cos(angle);
  const double s = std::sin(angle);
  return v * c + axis.cross(v) * s + axis * (axis.dot(v) * (1.0 - c));
}

/// Samples the parametric curve r(t), t in [t0, t1], about every step_mm of arc, with Frenet
/// geometry from central differences of r (step tiny against the curve's scale: exact to ~1e-7).
/// The radius tapers linearly in arc length from radius0 to radius1.
SkeletonPath sampleCurve(const CurveFunction& r,
  double t0,
  double t1,
  double radius0_mm,
  double radius1_mm,
  double step_mm)
{
  const double dt = (t1 - t0) * 1e-5;
  auto d1 = [&](double t) { return (r(t + dt) - r(t - dt)) * (0.5 / dt); };
  auto d2 = [&](double t) { return (r(t + dt) - r(t) * 2.0 + r(t - dt)) * (1.0 / (dt * dt)); };
  auto d3 = [&](double t)
  {
    return (r(t + 2 * dt) - r(t + dt) * 2.0 + r(t - dt) * 2.0 - r(t - 2 * dt)) *
           (0.5 / (dt * dt * dt));
  };

  // Arc length table on a fine parameter grid, then resample at equal arc steps.
  ArcLengthTable arc(r, t0, t1, 20000);
  const double length = arc.length_mm();
  const int count = std::max(2, static_cast<int>(std::ceil(length / step_mm)) + 1);

  SkeletonPath path;
  path.points.reserve(count);
  for (int k = 0; k < count; ++k)
  {
    const double s = length * k / (count - 1);
    const double t = arc.parameterAt(s);
    const Vec3 v1 = d1(t);
    const Vec3 v2 = d2(t);
    const Vec3 c12 = v1.cross(v2);
    const double speed = v1.norm();
    SkeletonPoint point;
    point.position_World_mm = r(t);
    point.tangent_World = normalized(v1);
    point.curvature_per_mm = speed > 0.0 ? c12.norm() / (speed * speed * speed) : 0.0;
    const double c12sq = c12.dot(c12);
    // Torsion is undefined where the curve is straight; report 0 there.
    point.torsion_per_mm = c12sq > 1e-12 * std::pow(speed, 6) ? c12.dot(d3(t)) / c12sq : 0.0;
    point.radius_mm = radius0_mm + (radius1_mm - radius0_mm) * (length > 0 ? s / length : 0.0);
    path.points.push_back(point);
  }
  path.points.front().label = PointLabel::EndPoint;
  path.points.back().label = PointLabel::EndPoint;
  return path;
}

class ShapeBuilder
{
public:
  ShapeBuilder(const PhantomSpec& spec, double step_mm)
    : Spec(spec)
    , Step(step_mm)
    , N(spec.referenceLength_mm())
  {
    for (int a = 0; a < 3; ++a)
    {
      const double extent = (spec.dimensions[a] - 1) * spec.spacing_mm[a];
      this->Center[a] = spec.origin_mm[a] + 0.5 * extent;
    }
  }

  QSkeleton build()
  {
    switch (this->Spec.shape)
    {
      case PhantomShape::Circle:
        this->circle();
        break;
      case PhantomShape::WindingLine:
        this->windingLine();
        break;
      case PhantomShape::Helix:
        this->helix();
        break;
      case PhantomShape::StraightTube:
        this->straightTube();
        break;
      case PhantomShape::YBifurcation:
        this->yBifurcation();
        break;
      case PhantomShape::Tree:
        this->tree();
        break;
      case PhantomShape::LoopNetwork:
        this->loopNetwork();
        break;
      case PhantomShape::Column:
        this->column();
        break;
      case PhantomShape::RawAngiogram:
        this->Skeleton = VascularTreeGenerator(this->Spec, this->Step).build();
        break;
    }
    return this->Skeleton;
  }

private:
  Vec3 center() const { return { this->Center[0], this->Center[1], this->Center[2] }; }
  double radius(double fraction) const { return fraction * this->N; }

  int addPath(const CurveFunction& r, double t0, double t1, double radiusStart_mm)
  {
    SkeletonPath path =
      sampleCurve(r, t0, t1, radiusStart_mm, radiusStart_mm * this->Spec.taperRatio, this->Step);
    path.id = static_cast<int>(this->Skeleton.paths.size());
    this->Skeleton.paths.push_back(std::move(path));
    return this->Skeleton.paths.back().id;
  }

  int addSegment(const Vec3& a, const Vec3& b, double radiusStart_mm)
  {
    return this->addPath([a, b](double t) { return a + (b - a) * t; }, 0.0, 1.0, radiusStart_mm);
  }

  /// The `end` of `child` attaches to point `parentPoint` of `parent`.
  void join(int child, Junction::End end, int parent, int parentPoint)
  {
    Junction j;
    j.childPath = child;
    j.childEnd = end;
    j.parentPath = parent;
    j.parentPoint = parentPoint;
    const int index = static_cast<int>(this->Skeleton.junctions.size());
    this->Skeleton.junctions.push_back(j);
    SkeletonPath& c = this->Skeleton.paths[child];
    if (end == Junction::End::Head)
    {
      c.head.junction = index;
      c.points.front().label = PointLabel::Bifurcation;
    }
    else
    {
      c.tail.junction = index;
      c.points.back().label = PointLabel::Bifurcation;
    }
    this->Skeleton.paths[parent].points[parentPoint].label = PointLabel::Bifurcation;
  }

  int nearestPoint(int path, const Vec3& p) const
  {
    const auto& pts = this->Skeleton.paths[path].points;
    int best = 0;
    double bestD = 1e300;
    for (int i = 0; i < static_cast<int>(pts.size()); ++i)
    {
      const double d = (pts[i].position_World_mm - p).norm();
      if (d < bestD)
      {
        bestD = d;
        best = i;
      }
    }
    return best;
  }

  /// A closed ring: one path whose tail joins its own head (a loop, not a tree).
  void closeLoop(int path)
  {
    auto& pts = this->Skeleton.paths[path].points;
    pts.pop_back(); // the last sample repeats the first
    pts.back().label = PointLabel::Ordinary;
    pts.front().label = PointLabel::Ordinary;
    this->join(path, Junction::End::Tail, path, 0);
    pts.back().label = PointLabel::Ordinary;
    pts.front().label = PointLabel::Ordinary;
  }

  void circle()
  {
    // Ring of radius 0.3 N in a plane tilted 60 deg about x: seen along z it is a narrow oval.
    const Vec3 c = this->center();
    const double R = 0.3 * this->N;
    const double tilt = 60.0 * kPi / 180.0;
    const Vec3 e1{ 1, 0, 0 };
    const Vec3 e2{ 0, std::cos(tilt), std::sin(tilt) };
    const int id =
      this->addPath([=](double t) { return c + e1 * (R * std::cos(t)) + e2 * (R * std::sin(t)); },
        0.0,
        2 * kPi,
        this->radius(this->Spec.radiusFraction));
    this->closeLoop(id);
  }

  void windingLine()
  {
    // Along x over 0.8 N, oscillating in the x-z plane (by default two periods of amplitude
    // 0.2 N).
    const Vec3 c = this->center();
    const double L = 0.8 * this->N;
    const double A = this->Spec.windingAmplitudeFraction * this->N;
    const double w = 2.0 * kPi * this->Spec.windingPeriods;
    this->addPath(
      [=](double t) {
        return Vec3{ c.x + L * (t - 0.5), c.y, c.z + A * std::sin(w * t) };
      },
      0.0,
      1.0,
      this->radius(this->Spec.radiusFraction));
  }

  void helix()
  {
    // Axis z through the center; x = a cos t, y = a sin t, z = c t; kappa = a/(a^2+c^2),
    // tau = c/(a^2+c^2).
    const Vec3 center = this->center();
    const double a = this->Spec.helixRadiusFraction * this->N;
    const double c = this->Spec.helixPitchFraction * this->N / (2 * kPi);
    const double tEnd = 2 * kPi * this->Spec.helixTurns;
    const double z0 = center.z - 0.5 * c * tEnd;
    this->addPath(
      [=](double t) {
        return Vec3{ center.x + a * std::cos(t), center.y + a * std::sin(t), z0 + c * t };
      },
      0.0,
      tEnd,
      this->radius(this->Spec.radiusFraction));
  }

  void straightTube()
  {
    const Vec3 c = this->center();
    const double extentX = (this->Spec.dimensions[0] - 1) * this->Spec.spacing_mm[0];
    this->addSegment({ c.x - 0.4 * extentX, c.y, c.z },
      { c.x + 0.4 * extentX, c.y, c.z },
      this->radius(this->Spec.radiusFraction));
  }

  void yBifurcation()
  {
    // Trunk up along y, then two branches leaving toward and away from the viewer (+/- z).
    const Vec3 c = this->center();
    const double n = this->N;
    const double r = this->radius(this->Spec.radiusFraction);
    const Vec3 split{ c.x, c.y + 0.0 * n, c.z };
    const int trunk = this->addSegment({ c.x, c.y - 0.4 * n, c.z }, split, r);
    const double rBranch = r * this->Spec.taperRatio * 0.8;
    const int left =
      this->addSegment(split, { c.x - 0.3 * n, c.y + 0.33 * n, c.z + 0.12 * n }, rBranch);
    const int right =
      this->addSegment(split, { c.x + 0.3 * n, c.y + 0.33 * n, c.z - 0.12 * n }, rBranch);
    const int last = static_cast<int>(this->Skeleton.paths[trunk].points.size()) - 1;
    this->join(left, Junction::End::Head, trunk, last);
    this->join(right, Junction::End::Head, trunk, last);
  }

  double treeRadius(int generation) const
  {
    const auto& explicitFractions = this->Spec.treeRadiusFractions;
    if (!explicitFractions.empty())
    {
      const int i = std::min<int>(generation, static_cast<int>(explicitFractions.size()) - 1);
      return this->radius(explicitFractions[i]);
    }
    return this->radius(this->Spec.radiusFraction) *
           std::pow(this->Spec.treeRadiusRatio, generation);
  }

  void treeBranch(int parent,
    const Vec3& start,
    const Vec3& direction,
    const Vec3& splitAxis,
    double length,
    int generation)
  {
    const Vec3 end = start + direction * length;
    const int id = this->addSegment(start, end, this->treeRadius(generation));
    if (parent >= 0)
    {
      const int last = static_cast<int>(this->Skeleton.paths[parent].points.size()) - 1;
      this->join(id, Junction::End::Head, parent, last);
    }
    if (generation + 1 >= this->Spec.treeDepth)
    {
      return;
    }
    // Children split +/- 35 deg about an axis that turns 60 deg about each child's direction per
    // generation: a 3D tree whose branches rise and fall in depth, yet all stay visible in a MIP
    // seen along z (a 90 deg turn would hide the third generation behind the second).
    const double angle = 35.0 * kPi / 180.0;
    for (double sign : { -1.0, 1.0 })
    {
      const Vec3 childDirection = normalized(rotate(direction, splitAxis, sign * angle));
      const Vec3 nextAxis =
        normalized(rotate(splitAxis, childDirection, sign * 60.0 * kPi / 180.0));
      this->treeBranch(id, end, childDirection, nextAxis, 0.7 * length, generation + 1);
    }
  }

  void tree()
  {
    const Vec3 c = this->center();
    const double n = this->N;
    // Root length 0.3 N so that even depth 6 stays inside (0.3 N * sum 0.7^g < 1 N).
    const double rootLength = this->Spec.treeDepth > 3 ? 0.22 * n : 0.3 * n;
    this->treeBranch(-1, { c.x, c.y - 0.42 * n, c.z }, { 0, 1, 0 }, { 0, 0, 1 }, rootLength, 0);
  }

  void loopNetwork()
  {
    // A ring (radius 0.22 N, tilted 30 deg about x) fed by two vessels from below and drained by
    // two vessels above, like the circle of Willis: one loop, four inflow/outflow ends.
    const Vec3 c = this->center();
    const double n = this->N;
    const double R = 0.22 * n;
    const double tilt = 30.0 * kPi / 180.0;
    const Vec3 e1{ 1, 0, 0 };
    const Vec3 e2{ 0, std::cos(tilt), std::sin(tilt) };
    const double r = this->radius(this->Spec.radiusFraction);
    const int ring =
      this->addPath([=](double t) { return c + e1 * (R * std::cos(t)) + e2 * (R * std::sin(t)); },
        0.0,
        2 * kPi,
        r);
    this->closeLoop(ring);
    for (double degrees : { 225.0, 315.0, 45.0, 135.0 })
    {
      const double t = degrees * kPi / 180.0;
      const Vec3 radial = e1 * std::cos(t) + e2 * std::sin(t);
      const Vec3 onRing = c + radial * R;
      const int spoke = this->addSegment(onRing, onRing + radial * (0.2 * n), r * 0.8);
      this->join(spoke, Junction::End::Head, ring, this->nearestPoint(ring, onRing));
    }
  }

  void column()
  {
    // A 4x4-voxel square column along z; its centerline runs between the middle voxels.
    const auto& d = this->Spec.dimensions;
    const auto& s = this->Spec.spacing_mm;
    const auto& o = this->Spec.origin_mm;
    const double cx = o[0] + (d[0] / 2 - 0.5) * s[0];
    const double cy = o[1] + (d[1] / 2 - 0.5) * s[1];
    const double zEnd = o[2] + (d[2] - 1) * s[2];
    this->addSegment({ cx, cy, o[2] }, { cx, cy, zEnd }, 2.0 * std::min(s[0], s[1]));
  }

  const PhantomSpec& Spec;
  double Step;
  double N;
  double Center[3] = { 0, 0, 0 };
  QSkeleton Skeleton;
};

} // namespace

QSkeleton buildPhantomCenterline(const PhantomSpec& spec, double step_mm)
{
  return ShapeBuilder(spec, step_mm).build();
}

} // namespace vtouch

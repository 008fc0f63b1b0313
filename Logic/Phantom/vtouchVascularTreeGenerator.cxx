#include "vtouchVascularTreeGenerator.h"

#include "vtouchArcLengthTable.h"
#include "vtouchPhantomRandom.h"

#include <algorithm>
#include <cmath>
#include <deque>

namespace vtouch
{
namespace
{
constexpr double kPi = 3.14159265358979323846;
constexpr double kGap_vox = 2.0;    ///< clearance between vessel walls, voxels
constexpr double kMargin_vox = 3.0; ///< clearance between a vessel wall and the volume's faces
constexpr int kAttempts = 24;       ///< tries to place the two children of a bifurcation

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

/// A unit vector perpendicular to the unit vector t.
Vec3 perpendicular(const Vec3& t)
{
  const Vec3 other = std::abs(t.x) < 0.9 ? Vec3{ 1, 0, 0 } : Vec3{ 0, 1, 0 };
  return normalized(t.cross(other));
}

/// Cubic Hermite curve and its first three derivatives at t in [0, 1].
struct Hermite
{
  Vec3 p0, m0, p1, m1;

  Vec3 at(double t) const
  {
    const double t2 = t * t;
    const double t3 = t2 * t;
    return p0 * (2 * t3 - 3 * t2 + 1) + m0 * (t3 - 2 * t2 + t) + p1 * (-2 * t3 + 3 * t2) +
           m1 * (t3 - t2);
  }
  Vec3 d1(double t) const
  {
    const double t2 = t * t;
    return p0 * (6 * t2 - 6 * t) + m0 * (3 * t2 - 4 * t + 1) + p1 * (-6 * t2 + 6 * t) +
           m1 * (3 * t2 - 2 * t);
  }
  Vec3 d2(double t) const
  {
    return p0 * (12 * t - 6) + m0 * (6 * t - 4) + p1 * (-12 * t + 6) + m1 * (6 * t - 2);
  }
  Vec3 d3() const { return p0 * 12.0 + m0 * 6.0 + p1 * -12.0 + m1 * 6.0; }
};

/// Samples a Hermite segment at equal arc steps of about step_mm, with analytic Frenet geometry.
SkeletonPath sampleHermite(const Hermite& h, double radius_mm, double step_mm)
{
  ArcLengthTable arc([&h](double t) { return h.at(t); }, 0.0, 1.0, 1024);
  const double length = arc.length_mm();
  const int count = std::max(2, static_cast<int>(std::ceil(length / step_mm)) + 1);
  SkeletonPath path;
  path.points.reserve(count);
  for (int k = 0; k < count; ++k)
  {
    const double s = length * k / (count - 1);
    const double t = arc.parameterAt(s);
    const Vec3 v1 = h.d1(t);
    const Vec3 v2 = h.d2(t);
    const Vec3 c12 = v1.cross(v2);
    const double speed = v1.norm();
    SkeletonPoint point;
    point.position_World_mm = h.at(t);
    point.tangent_World = normalized(v1);
    point.curvature_per_mm = speed > 0.0 ? c12.norm() / (speed * speed * speed) : 0.0;
    const double c12sq = c12.dot(c12);
    point.torsion_per_mm = c12sq > 1e-12 * std::pow(speed, 6) ? c12.dot(h.d3()) / c12sq : 0.0;
    point.radius_mm = radius_mm;
    path.points.push_back(point);
  }
  path.points.front().label = PointLabel::EndPoint;
  path.points.back().label = PointLabel::EndPoint;
  return path;
}

/// Murray's minimum-work branching angle of the child of radius r1 (sibling r2, parent r0).
double murrayAngle(double r0, double r1, double r2)
{
  const double c = (std::pow(r0, 4) + std::pow(r1, 4) - std::pow(r2, 4)) / (2 * r0 * r0 * r1 * r1);
  return std::acos(std::clamp(c, -1.0, 1.0));
}
} // namespace

VascularTreeGenerator::VascularTreeGenerator(const PhantomSpec& spec, double step_mm)
  : Spec(spec)
  , Step_mm(step_mm)
  , Voxel_mm(std::min({ spec.spacing_mm[0], spec.spacing_mm[1], spec.spacing_mm[2] }))
{
  const auto& o = spec.origin_mm;
  this->Lo = { o[0], o[1], o[2] };
  this->Hi = { o[0] + (spec.dimensions[0] - 1) * spec.spacing_mm[0],
    o[1] + (spec.dimensions[1] - 1) * spec.spacing_mm[1],
    o[2] + (spec.dimensions[2] - 1) * spec.spacing_mm[2] };
  const double rMax = spec.angiogramLargestRadius_vox * this->Voxel_mm;
  this->Cell_mm = 2.0 * rMax + kGap_vox * this->Voxel_mm;
  const Vec3 extent = this->Hi - this->Lo;
  const double* e = &extent.x;
  for (int a = 0; a < 3; ++a)
  {
    this->GridDims[a] = std::max(1, static_cast<int>(std::ceil(e[a] / this->Cell_mm)) + 1);
  }
  this->Grid.resize(
    static_cast<std::size_t>(this->GridDims[0]) * this->GridDims[1] * this->GridDims[2]);
}

VascularTreeGenerator::Segment VascularTreeGenerator::makeSegment(int parent,
  const Vec3& start,
  const Vec3& direction,
  double radius_mm,
  double lengthScale,
  PhantomRandom& random) const
{
  const double n =
    std::min({ this->Hi.x - this->Lo.x, this->Hi.y - this->Lo.y, this->Hi.z - this->Lo.z });
  double length =
    std::max(random.uniform(10.0, 20.0) * this->Voxel_mm, random.uniform(8.0, 16.0) * radius_mm);
  if (parent < 0)
  {
    length = random.uniform(16.0, 24.0) * radius_mm;
  }
  length = std::min(length * lengthScale, (parent < 0 ? 0.4 : 0.25) * n);
  const Vec3 bendAxis = rotate(perpendicular(direction), direction, random.uniform(0.0, 2 * kPi));
  Vec3 endTangent =
    normalized(rotate(direction, bendAxis, random.uniform(-35.0, 35.0) * kPi / 180.0));
  // Vessels heading for a face bend back toward the centre (the closer, the more), so that the
  // tree fills the volume instead of stopping at its faces.
  const Vec3 ahead = start + direction * length;
  double faceDistance = 1e300;
  for (int a = 0; a < 3; ++a)
  {
    faceDistance = std::min(
      { faceDistance, (&ahead.x)[a] - (&this->Lo.x)[a], (&this->Hi.x)[a] - (&ahead.x)[a] });
  }
  const double steer = 1.2 * std::clamp(1.0 - faceDistance / (0.3 * n), 0.0, 1.0);
  endTangent = normalized(endTangent + normalized((this->Lo + this->Hi) * 0.5 - ahead) * steer);
  Segment s;
  s.parent = parent;
  s.radius_mm = radius_mm;
  s.p0 = start;
  s.p1 = start + normalized(direction + endTangent) * length;
  s.m0 = direction * length;
  s.m1 = endTangent * length;
  const Hermite h{ s.p0, s.m0, s.p1, s.m1 };
  const int count = std::max(2, static_cast<int>(std::ceil(1.2 * length / this->Voxel_mm)) + 1);
  for (int i = 0; i < count; ++i)
  {
    s.samples.push_back(h.at(static_cast<double>(i) / (count - 1)));
  }
  return s;
}

bool VascularTreeGenerator::fits(const Segment& s, int parent, int sibling) const
{
  const double margin = s.radius_mm + kMargin_vox * this->Voxel_mm;
  const double gap = kGap_vox * this->Voxel_mm;
  // Near the bifurcation the parent and the sibling overlap the segment by construction.
  const double parentRadius = parent >= 0 ? this->Segments[parent].radius_mm : 0.0;
  const double zone = 3.0 * parentRadius + s.radius_mm + 3.0 * this->Voxel_mm;
  const Segment* siblingSegment = sibling >= 0 ? &this->Segments[sibling] : nullptr;
  for (const Vec3& q : s.samples)
  {
    const double* p = &q.x;
    const double* lo = &this->Lo.x;
    const double* hi = &this->Hi.x;
    for (int a = 0; a < 3; ++a)
    {
      if (p[a] < lo[a] + margin || p[a] > hi[a] - margin)
      {
        return false;
      }
    }
    const bool nearStart = (q - s.p0).norm() < zone;
    int cell[3];
    for (int a = 0; a < 3; ++a)
    {
      cell[a] =
        std::clamp(static_cast<int>((p[a] - lo[a]) / this->Cell_mm), 0, this->GridDims[a] - 1);
    }
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx)
        {
          const int c[3] = { cell[0] + dx, cell[1] + dy, cell[2] + dz };
          if (c[0] < 0 || c[1] < 0 || c[2] < 0 || c[0] >= this->GridDims[0] ||
              c[1] >= this->GridDims[1] || c[2] >= this->GridDims[2])
          {
            continue;
          }
          const auto& bucket =
            this->Grid[(static_cast<std::size_t>(c[2]) * this->GridDims[1] + c[1]) *
                         this->GridDims[0] +
                       c[0]];
          for (const auto& [index, sample] : bucket)
          {
            const Segment& other = this->Segments[index];
            const Vec3& o = other.samples[sample];
            // The parent's end, the siblings' starts (children of the same parent) and the
            // grandparent's end all meet at the bifurcation.
            const bool family = index == parent || other.parent == parent ||
                                (parent >= 0 && index == this->Segments[parent].parent);
            if (nearStart && family && (o - s.p0).norm() < zone)
            {
              continue;
            }
            if ((q - o).norm() < s.radius_mm + other.radius_mm + gap)
            {
              return false;
            }
          }
        }
    if (siblingSegment)
    {
      for (const Vec3& o : siblingSegment->samples)
      {
        if (nearStart && (o - s.p0).norm() < zone)
        {
          continue;
        }
        if ((q - o).norm() < s.radius_mm + siblingSegment->radius_mm + gap)
        {
          return false;
        }
      }
    }
  }
  return true;
}

void VascularTreeGenerator::addToGrid(int index)
{
  const Segment& s = this->Segments[index];
  for (int i = 0; i < static_cast<int>(s.samples.size()); ++i)
  {
    const double* p = &s.samples[i].x;
    const double* lo = &this->Lo.x;
    int cell[3];
    for (int a = 0; a < 3; ++a)
    {
      cell[a] =
        std::clamp(static_cast<int>((p[a] - lo[a]) / this->Cell_mm), 0, this->GridDims[a] - 1);
    }
    this
      ->Grid[(static_cast<std::size_t>(cell[2]) * this->GridDims[1] + cell[1]) * this->GridDims[0] +
             cell[0]]
      .emplace_back(index, i);
  }
}

QSkeleton VascularTreeGenerator::build()
{
  PhantomRandom random(0xA5E1u + 7919ull * this->Spec.seed);
  const double rMax = this->Spec.angiogramLargestRadius_vox * this->Voxel_mm;
  const double rMin = this->Spec.angiogramSmallestRadius_vox * this->Voxel_mm;

  // Root: near the centre of a random face, pointing inward within 20 deg of the face normal.
  for (int attempt = 0; attempt < 64 && this->Segments.empty(); ++attempt)
  {
    const int axis = random.index(3);
    const bool high = random.uniform() < 0.5;
    const Vec3 centre = (this->Lo + this->Hi) * 0.5;
    const Vec3 extent = this->Hi - this->Lo;
    Vec3 start = centre;
    double* st = &start.x;
    const double* ex = &extent.x;
    for (int a = 0; a < 3; ++a)
    {
      if (a != axis)
      {
        st[a] += random.uniform(-0.2, 0.2) * ex[a];
      }
    }
    const double inset = rMax + (kMargin_vox + 1.0) * this->Voxel_mm;
    st[axis] = high ? (&this->Hi.x)[axis] - inset : (&this->Lo.x)[axis] + inset;
    Vec3 inward{ 0, 0, 0 };
    (&inward.x)[axis] = high ? -1.0 : 1.0;
    const Vec3 tilt = rotate(perpendicular(inward), inward, random.uniform(0.0, 2 * kPi));
    const Vec3 direction =
      normalized(rotate(inward, tilt, random.uniform(0.0, 20.0) * kPi / 180.0));
    Segment root = this->makeSegment(-1, start, direction, rMax, 1.0, random);
    this->Segments.push_back(root);
    if (!this->fits(this->Segments.back(), -1, -1))
    {
      this->Segments.pop_back();
    }
  }
  if (this->Segments.empty())
  {
    return {};
  }
  this->addToGrid(0);

  std::deque<int> leaves{ 0 };
  const int target = this->Spec.angiogramSegments;
  while (!leaves.empty() && static_cast<int>(this->Segments.size()) + 2 <= target)
  {
    const int leaf = leaves.front();
    leaves.pop_front();
    const double r0 = this->Segments[leaf].radius_mm;
    if (r0 * r0 * r0 < 2.0 * rMin * rMin * rMin * (1.0 - 1e-12))
    {
      continue; // too thin to split into two vessels of at least the smallest radius
    }
    // Murray's law r0^3 = r1^3 + r2^3 with r2 = alpha r1.
    const double alpha = random.uniform(0.25, 1.0);
    double r1 = r0 / std::cbrt(1.0 + alpha * alpha * alpha);
    double r2 = alpha * r1;
    if (r2 < rMin)
    {
      r2 = rMin;
      r1 = std::cbrt(r0 * r0 * r0 - rMin * rMin * rMin);
    }
    const double theta1 = murrayAngle(r0, r1, r2);
    const double theta2 = murrayAngle(r0, r2, r1);
    // Copies: the children are pushed onto Segments below.
    const Vec3 end = this->Segments[leaf].p1;
    const Vec3 tangent = normalized(this->Segments[leaf].m1);
    for (int attempt = 0; attempt < kAttempts; ++attempt)
    {
      // Later attempts try shorter children (a crowded or small volume still branches).
      const double lengthScale = 1.0 - 0.6 * attempt / kAttempts;
      const Vec3 axis = rotate(perpendicular(tangent), tangent, random.uniform(0.0, 2 * kPi));
      Segment a = this->makeSegment(
        leaf, end, normalized(rotate(tangent, axis, theta1)), r1, lengthScale, random);
      Segment b = this->makeSegment(
        leaf, end, normalized(rotate(tangent, axis, -theta2)), r2, lengthScale, random);
      this->Segments.push_back(std::move(a));
      const int ia = static_cast<int>(this->Segments.size()) - 1;
      if (!this->fits(this->Segments[ia], leaf, -1))
      {
        this->Segments.pop_back();
        continue;
      }
      this->Segments.push_back(std::move(b));
      const int ib = ia + 1;
      if (!this->fits(this->Segments[ib], leaf, ia))
      {
        this->Segments.pop_back();
        this->Segments.pop_back();
        continue;
      }
      this->addToGrid(ia);
      this->addToGrid(ib);
      leaves.push_back(ia);
      leaves.push_back(ib);
      break;
    }
  }

  QSkeleton tree;
  for (int i = 0; i < static_cast<int>(this->Segments.size()); ++i)
  {
    const Segment& s = this->Segments[i];
    SkeletonPath path = sampleHermite({ s.p0, s.m0, s.p1, s.m1 }, s.radius_mm, this->Step_mm);
    path.id = i;
    tree.paths.push_back(std::move(path));
    if (s.parent >= 0)
    {
      Junction j;
      j.childPath = i;
      j.childEnd = Junction::End::Head;
      j.parentPath = s.parent;
      j.parentPoint = static_cast<int>(tree.paths[s.parent].points.size()) - 1;
      tree.paths[i].head.junction = static_cast<int>(tree.junctions.size());
      tree.paths[i].points.front().label = PointLabel::Bifurcation;
      tree.paths[s.parent].points.back().label = PointLabel::Bifurcation;
      tree.junctions.push_back(j);
    }
  }
  return tree;
}

} // namespace vtouch

#include "vtouchSkeletonTestSupport.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <sstream>

namespace vtouch
{
namespace test
{

FloatImage::Pointer blankImage(int nx, int ny, int nz, double spacing)
{
  auto image = FloatImage::New();
  FloatImage::RegionType region;
  region.SetSize({ { static_cast<itk::SizeValueType>(nx),
    static_cast<itk::SizeValueType>(ny),
    static_cast<itk::SizeValueType>(nz) } });
  image->SetRegions(region);
  FloatImage::SpacingType sp;
  sp.Fill(spacing);
  image->SetSpacing(sp);
  image->Allocate(true);
  return image;
}

FloatImage::Pointer phantomImage(const PhantomGenerator& generator)
{
  const PhantomSpec& spec = generator.spec();
  auto image = blankImage(spec.dimensions[0], spec.dimensions[1], spec.dimensions[2]);
  FloatImage::SpacingType sp;
  FloatImage::PointType origin;
  for (int a = 0; a < 3; ++a)
  {
    sp[a] = spec.spacing_mm[a];
    origin[a] = spec.origin_mm[a];
  }
  image->SetSpacing(sp);
  image->SetOrigin(origin);
  generator.fill(image->GetBufferPointer());
  return image;
}

double wallThreshold(const PhantomSpec& spec)
{
  return 0.5 * (spec.backgroundIntensity + spec.peakIntensity);
}

namespace
{
double segmentDistance(const Vec3& p, const Vec3& a, const Vec3& b)
{
  const Vec3 ab = b - a;
  const double len2 = ab.dot(ab);
  double t = len2 > 0.0 ? (p - a).dot(ab) / len2 : 0.0;
  t = std::clamp(t, 0.0, 1.0);
  return (p - (a + ab * t)).norm();
}

bool isFreeEnd(const QSkeleton& s, int path, bool tail)
{
  const SkeletonPath& p = s.paths[path];
  if ((tail ? p.tail.junction : p.head.junction) >= 0)
  {
    return false;
  }
  const int point = tail ? static_cast<int>(p.points.size()) - 1 : 0;
  for (const Junction& j : s.junctions)
  {
    if (j.parentPath == path && j.parentPoint == point)
    {
      return false;
    }
  }
  return true;
}
} // namespace

double distanceToSkeleton(const QSkeleton& s, const Vec3& p)
{
  double best = 1e300;
  for (const SkeletonPath& path : s.paths)
  {
    if (path.points.size() == 1)
    {
      best = std::min(best, (p - path.points[0].position_World_mm).norm());
    }
    for (std::size_t i = 1; i < path.points.size(); ++i)
    {
      best = std::min(best,
        segmentDistance(p, path.points[i - 1].position_World_mm, path.points[i].position_World_mm));
    }
  }
  return best;
}

Accuracy measure(const QSkeleton& output, const PhantomGenerator& generator, double coverRadius_mm)
{
  Accuracy acc;
  std::vector<double> d;
  double radiusError = 0.0;
  std::size_t radiusCount = 0;
  for (std::size_t p = 0; p < output.paths.size(); ++p)
  {
    const SkeletonPath& path = output.paths[p];
    for (std::size_t i = 0; i < path.points.size(); ++i)
    {
      const SkeletonPoint& q = path.points[i];
      double r = 0.0;
      d.push_back(generator.distanceToCenterline_mm(q.position_World_mm, &r));
      // Radius is compared away from free ends and junctions (where no single radius exists).
      const double margin = 2.0 * r;
      double fromHead = 0.0, fromTail = 0.0;
      for (std::size_t k = 1; k <= i; ++k)
      {
        fromHead +=
          (path.points[k].position_World_mm - path.points[k - 1].position_World_mm).norm();
      }
      for (std::size_t k = i + 1; k < path.points.size(); ++k)
      {
        fromTail +=
          (path.points[k].position_World_mm - path.points[k - 1].position_World_mm).norm();
      }
      if (fromHead > margin && fromTail > margin && q.label == PointLabel::Ordinary)
      {
        radiusError += std::abs(q.radius_mm - r);
        ++radiusCount;
      }
    }
  }
  acc.outputPoints = d.size();
  if (!d.empty())
  {
    acc.mean_mm = std::accumulate(d.begin(), d.end(), 0.0) / static_cast<double>(d.size());
    std::sort(d.begin(), d.end());
    acc.p95_mm = d[std::min(d.size() - 1, static_cast<std::size_t>(0.95 * d.size()))];
  }
  acc.radiusError_mm = radiusCount ? radiusError / static_cast<double>(radiusCount) : 0.0;
  std::size_t covered = 0, total = 0;
  for (const SkeletonPath& path : generator.centerline().paths)
  {
    for (const SkeletonPoint& q : path.points)
    {
      ++total;
      covered += distanceToSkeleton(output, q.position_World_mm) <= coverRadius_mm ? 1 : 0;
    }
  }
  acc.coverage = total ? static_cast<double>(covered) / static_cast<double>(total) : 0.0;
  return acc;
}

Topology topology(const QSkeleton& s, double mergeDistance_mm)
{
  Topology t;
  const int n = static_cast<int>(s.paths.size());
  std::vector<int> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  const auto find = [&](int a)
  {
    while (parent[a] != a)
    {
      a = parent[a] = parent[parent[a]];
    }
    return a;
  };
  for (const Junction& j : s.junctions)
  {
    parent[find(j.childPath)] = find(j.parentPath);
  }
  for (int p = 0; p < n; ++p)
  {
    t.components += find(p) == p ? 1 : 0;
    t.endPoints += isFreeEnd(s, p, false) ? 1 : 0;
    t.endPoints += isFreeEnd(s, p, true) ? 1 : 0;
  }
  t.loops = static_cast<int>(s.junctions.size()) - n + t.components;
  // Degree of each attachment place: branches leaving the parent point plus the child ends.
  struct Place
  {
    Vec3 position;
    int degree = 0;
    std::vector<std::pair<int, int>> parents;
  };
  std::vector<Place> places;
  for (const Junction& j : s.junctions)
  {
    const SkeletonPath& pp = s.paths[j.parentPath];
    const Vec3 pos = pp.points[j.parentPoint].position_World_mm;
    Place* place = nullptr;
    for (Place& pl : places)
    {
      if ((pl.position - pos).norm() <= mergeDistance_mm)
      {
        place = &pl;
      }
    }
    if (!place)
    {
      places.push_back({ pos, 0, {} });
      place = &places.back();
    }
    place->degree += 1;
    const bool known = std::any_of(place->parents.begin(),
      place->parents.end(),
      [&](const std::pair<int, int>& q) { return q.first == j.parentPath; });
    if (!known)
    {
      place->parents.push_back({ j.parentPath, j.parentPoint });
      const bool end =
        j.parentPoint == 0 || j.parentPoint + 1 == static_cast<int>(pp.points.size());
      place->degree += end ? 1 : 2;
    }
  }
  for (const Place& pl : places)
  {
    t.bifurcations += pl.degree >= 3 ? 1 : 0;
  }
  return t;
}

std::string check26Connected(const RawSkeleton& raw, const std::array<double, 3>&)
{
  std::ostringstream msg;
  for (std::size_t p = 0; p < raw.paths.size(); ++p)
  {
    const auto& v = raw.paths[p].voxels;
    if (v.size() < 2)
    {
      msg << "path " << p << " has " << v.size() << " voxel(s)";
      return msg.str();
    }
    for (std::size_t i = 1; i < v.size(); ++i)
    {
      std::int64_t m = 0;
      for (int a = 0; a < 3; ++a)
      {
        m = std::max<std::int64_t>(m, std::abs(v[i][a] - v[i - 1][a]));
      }
      if (m != 1)
      {
        msg << "path " << p << " points " << i - 1 << "," << i << " are " << m
            << " voxels apart (Chebyshev)";
        return msg.str();
      }
    }
  }
  return {};
}

} // namespace test
} // namespace vtouch

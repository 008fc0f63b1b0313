// Scenes drawn as masks for the tube-section tests (TubeLikenessPruner, TubeSectionTracker):
// a mask from an inside test, the distance to an axis segment, the points off the axes and the
// axis covered, and the raw path's coding of a mask from a seed voxel. Unit spacing, origin 0: voxel index = world mm.
#pragma once

#include "vtouchQSkeleton.h"
#include "vtouchSparseVesselMask.h"
#include "vtouchVoxelCodingSkeletonFilter.h"

#include <itkImage.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

namespace vtouch
{
namespace mask_scenes
{
using Dims = std::array<std::int64_t, 3>;

/// The mask of the voxels whose index `inside` accepts.
inline SparseVesselMask makeMask(const Dims& dims, const std::function<bool(const Vec3&)>& inside)
{
  SparseVesselMask mask(dims);
  for (std::int64_t k = 0; k < dims[2]; ++k)
  {
    for (std::int64_t j = 0; j < dims[1]; ++j)
    {
      for (std::int64_t i = 0; i < dims[0]; ++i)
      {
        if (inside(Vec3{ double(i), double(j), double(k) }))
        {
          mask.set(static_cast<std::uint64_t>(i + dims[0] * (j + dims[1] * k)));
        }
      }
    }
  }
  mask.finalize();
  return mask;
}

/// Distance from p to the segment a-b.
inline double segmentDistance(const Vec3& p, const Vec3& a, const Vec3& b)
{
  const Vec3 ab = b - a;
  const double t = std::clamp((p - a).dot(ab) / ab.dot(ab), 0.0, 1.0);
  return (p - (a + ab * t)).norm();
}


/// The skeleton's points farther than `d` from every segment of `axes`: how many, of how many.
struct PointsOff
{
  std::size_t off = 0;
  std::size_t all = 0;
  double share() const { return this->all ? double(this->off) / double(this->all) : 0.0; }
};
inline PointsOff pointsOffAxes(const QSkeleton& s,
  const std::vector<std::array<Vec3, 2>>& axes,
  double d)
{
  PointsOff counted;
  for (const SkeletonPath& path : s.paths)
  {
    for (const SkeletonPoint& q : path.points)
    {
      double best = 1e300;
      for (const auto& ab : axes)
      {
        best = std::min(best, segmentDistance(q.position_World_mm, ab[0], ab[1]));
      }
      counted.off += best > d ? 1 : 0;
      ++counted.all;
    }
  }
  return counted;
}

/// Share of the axis a-b (sampled every voxel, `margin` voxels in from its ends) within `d` of
/// some skeleton point.
inline double coverage(const QSkeleton& s, const Vec3& a, const Vec3& b, double margin, double d)
{
  const double length = (b - a).norm();
  int covered = 0, all = 0;
  for (double t = margin; t <= length - margin; t += 1.0)
  {
    const Vec3 p = a + (b - a) * (t / length);
    bool hit = false;
    for (const SkeletonPath& path : s.paths)
    {
      for (const SkeletonPoint& q : path.points)
      {
        hit = hit || (q.position_World_mm - p).norm() <= d;
      }
    }
    covered += hit ? 1 : 0;
    ++all;
  }
  return all ? double(covered) / double(all) : 0.0;
}
/// Codes `mask` from the seed voxel (unit spacing, origin 0) as the raw path does.
inline QSkeleton codeFromSeed(const Dims& dims, const SparseVesselMask& mask, const Vec3& seed)
{
  using Image = itk::Image<float, 3>;
  using Filter = VoxelCodingSkeletonFilter<Image>;
  auto image = Image::New();
  Image::RegionType region;
  region.SetSize({ { static_cast<itk::SizeValueType>(dims[0]),
    static_cast<itk::SizeValueType>(dims[1]),
    static_cast<itk::SizeValueType>(dims[2]) } });
  image->SetRegions(region);
  image->Allocate(true);
  auto filter = Filter::New();
  filter->SetInput(image);
  filter->SetVesselMask(std::make_shared<const SparseVesselMask>(mask));
  typename Filter::PointType p;
  p[0] = seed.x;
  p[1] = seed.y;
  p[2] = seed.z;
  filter->SetSeedPoint(p);
  filter->Update();
  return filter->GetSkeleton();
}

} // namespace mask_scenes
} // namespace vtouch

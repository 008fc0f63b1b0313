// TubeLikenessPruner on tiny masks made in code, coded by the real voxel coder from a seed: a tube,
// a thin diagonal tube and a Y stay whole; a plate touching a tube loses its paths, the tube stays.
#include "vtouchTubeLikenessPruner.h"
#include "vtouchVoxelCodingSkeletonFilter.h"

#include <gtest/gtest.h>

#include <itkImage.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <iostream>
#include <memory>
#include <vector>

using namespace vtouch;

namespace
{
using Image = itk::Image<float, 3>;
using Filter = VoxelCodingSkeletonFilter<Image>;
using Dims = std::array<std::int64_t, 3>;

SparseVesselMask makeMask(const Dims& dims, const std::function<bool(const Vec3&)>& inside)
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
double segmentDistance(const Vec3& p, const Vec3& a, const Vec3& b)
{
  const Vec3 ab = b - a;
  const double t = std::clamp((p - a).dot(ab) / ab.dot(ab), 0.0, 1.0);
  return (p - (a + ab * t)).norm();
}

/// Codes `mask` from the seed voxel (unit spacing, origin 0) as the raw path does.
QSkeleton code(const Dims& dims, const SparseVesselMask& mask, const Vec3& seed)
{
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
  Filter::PointType p;
  p[0] = seed.x;
  p[1] = seed.y;
  p[2] = seed.z;
  filter->SetSeedPoint(p);
  filter->Update();
  return filter->GetSkeleton();
}

/// Share of the skeleton's points farther than `d` from every segment of `axes`.
double shareOff(const QSkeleton& s, const std::vector<std::array<Vec3, 2>>& axes, double d)
{
  std::size_t off = 0, all = 0;
  for (const SkeletonPath& path : s.paths)
  {
    for (const SkeletonPoint& q : path.points)
    {
      double best = 1e300;
      for (const auto& ab : axes)
      {
        best = std::min(best, segmentDistance(q.position_World_mm, ab[0], ab[1]));
      }
      off += best > d ? 1 : 0;
      ++all;
    }
  }
  return all ? double(off) / double(all) : 0.0;
}

/// Share of the axis a-b (sampled every voxel, `margin` voxels in from its ends) within `d` of
/// some skeleton point.
double coverage(const QSkeleton& s, const Vec3& a, const Vec3& b, double margin, double d)
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

const TubeLikenessPruner::Geometry kUnit{};
} // namespace

TEST(TubeLikenessPruner, SectionOfATubeIsTubeLikeAndOfAPlateIsNot)
{
  const Dims dims{ 48, 48, 48 };
  const Vec3 a{ 4, 24, 24 }, b{ 44, 24, 24 };
  const SparseVesselMask tube =
    makeMask(dims, [&](const Vec3& p) { return segmentDistance(p, a, b) <= 2.5; });
  EXPECT_TRUE(TubeLikenessPruner::isTubeLikeSection(
    TubeLikenessPruner::foreground(tube), kUnit, Vec3{ 24, 24, 24 }, Vec3{ 1, 0, 0 }, 2.5, {}));
  // A plate 4 voxels thick (z 22..25), 36 x 36 wide: its mid-sheet and its rim.
  const SparseVesselMask plate = makeMask(dims,
    [](const Vec3& p)
    { return p.z >= 22 && p.z <= 25 && p.x >= 6 && p.x <= 41 && p.y >= 6 && p.y <= 41; });
  EXPECT_FALSE(TubeLikenessPruner::isTubeLikeSection(
    TubeLikenessPruner::foreground(plate), kUnit, Vec3{ 24, 24, 23.5 }, Vec3{ 1, 0, 0 }, 2.0, {}));
  EXPECT_FALSE(TubeLikenessPruner::isTubeLikeSection(
    TubeLikenessPruner::foreground(plate), kUnit, Vec3{ 24, 7.5, 23.5 }, Vec3{ 1, 0, 0 }, 2.0, {}));
  // A tube lying on that plate's face: its section reaches the plate across its thickness.
  const SparseVesselMask touching = makeMask(dims,
    [&](const Vec3& p)
    {
      return segmentDistance(p, Vec3{ 4, 24, 19.5 }, Vec3{ 44, 24, 19.5 }) <= 2.5 ||
             (p.z >= 22 && p.z <= 25 && p.x >= 6 && p.x <= 41 && p.y >= 6 && p.y <= 41);
    });
  EXPECT_TRUE(TubeLikenessPruner::isTubeLikeSection(TubeLikenessPruner::foreground(touching),
    kUnit,
    Vec3{ 24, 24, 19.5 },
    Vec3{ 1, 0, 0 },
    2.5,
    {}));
}

TEST(TubeLikenessPruner, KeepsAStraightTubeAndAThinDiagonalTube)
{
  const Dims dims{ 64, 48, 48 };
  const Vec3 a{ 4, 24, 24 }, b{ 60, 24, 24 };
  const SparseVesselMask tube =
    makeMask(dims, [&](const Vec3& p) { return segmentDistance(p, a, b) <= 3.0; });
  QSkeleton s = code(dims, tube, a + Vec3{ 2, 0, 0 });
  const std::size_t before = s.pointCount();
  const auto r = TubeLikenessPruner::prune(s, TubeLikenessPruner::foreground(tube), kUnit);
  EXPECT_EQ(r.pathsRemoved, 0);
  EXPECT_EQ(s.pointCount(), before);
  EXPECT_EQ(s.validate(), "");

  // Radius 0.9, diagonal: a 26-connected line of single voxels with a few neighbours.
  const Vec3 c{ 4, 4, 4 }, d{ 42, 40, 38 };
  const SparseVesselMask thin =
    makeMask(dims, [&](const Vec3& p) { return segmentDistance(p, c, d) <= 0.9; });
  QSkeleton t = code(dims, thin, c + Vec3{ 1, 1, 1 });
  ASSERT_FALSE(t.empty());
  const std::size_t thinBefore = t.pointCount();
  const auto rt = TubeLikenessPruner::prune(t, TubeLikenessPruner::foreground(thin), kUnit);
  EXPECT_EQ(rt.pathsRemoved, 0);
  EXPECT_EQ(t.pointCount(), thinBefore);
}

TEST(TubeLikenessPruner, KeepsAYBifurcation)
{
  const Dims dims{ 80, 64, 40 };
  const Vec3 root{ 4, 32, 20 }, fork{ 40, 32, 20 }, left{ 76, 12, 20 }, right{ 76, 52, 20 };
  const SparseVesselMask y = makeMask(dims,
    [&](const Vec3& p)
    {
      return segmentDistance(p, root, fork) <= 3.5 || segmentDistance(p, fork, left) <= 2.5 ||
             segmentDistance(p, fork, right) <= 2.5;
    });
  QSkeleton s = code(dims, y, root + Vec3{ 2, 0, 0 });
  const std::size_t before = s.pointCount();
  const std::size_t paths = s.paths.size();
  ASSERT_GE(paths, 2u);
  const auto r = TubeLikenessPruner::prune(s, TubeLikenessPruner::foreground(y), kUnit);
  EXPECT_EQ(r.pathsRemoved, 0);
  EXPECT_EQ(r.endsTrimmed, 0);
  EXPECT_EQ(s.pointCount(), before);
  EXPECT_EQ(s.paths.size(), paths);
}

TEST(TubeLikenessPruner, RemovesThePathsOfAPlateTouchingATubeAndKeepsTheTube)
{
  // A tube of radius 2.5 along x; a plate 4 voxels thick lies on its face (0.5 voxel overlap, as
  // VesselPhantom's clutter), 36 x 36 voxels wide: its rims are tube-like at their own scale.
  const Dims dims{ 72, 56, 40 };
  const Vec3 a{ 3, 28, 14 }, b{ 68, 28, 14 };
  const auto onPlate = [](const Vec3& p)
  { return p.z >= 16 && p.z <= 19 && p.x >= 18 && p.x <= 53 && p.y >= 10 && p.y <= 45; };
  const SparseVesselMask mask =
    makeMask(dims, [&](const Vec3& p) { return segmentDistance(p, a, b) <= 2.5 || onPlate(p); });
  QSkeleton s = code(dims, mask, a + Vec3{ 2, 0, 0 });
  const std::vector<std::array<Vec3, 2>> axis{ { a, b } };
  const double offBefore = shareOff(s, axis, 2.5);
  const auto r = TubeLikenessPruner::prune(s, TubeLikenessPruner::foreground(mask), kUnit);
  const double offAfter = shareOff(s, axis, 2.5);
  std::cout << "plate on a tube: paths removed " << r.pathsRemoved << ", ends trimmed "
            << r.endsTrimmed << ", points off the tube " << offBefore << " -> " << offAfter
            << ", tube covered " << coverage(s, a, b, 4.0, 2.5) << "\n";
  EXPECT_EQ(s.validate(), "");
  EXPECT_GT(offBefore, 0.2); // the coder did code the plate
  EXPECT_GE(r.pathsRemoved, 1);
  EXPECT_LE(offAfter, 0.05);
  // Within the tube's radius (the recall: max(1.5 voxels, radius)): where the plate
  // overlaps it, the coded axis of the union leans ~2 voxels toward the plate.
  EXPECT_GE(coverage(s, a, b, 4.0, 2.5), 0.99);
}

// Helpers of the stitcher's tests (issue 19, item 2): skeletons in index = world coordinates
// (1 mm voxels), clipped per piece by SkeletonClipper with the overlap band, stitched, and the
// topology counts the tests compare.
#pragma once

#include "vtouchPieceOwnership.h"
#include "vtouchSkeletonClipper.h"
#include "vtouchSkeletonOverlapResolver.h"
#include "vtouchSkeletonStitcher.h"

#include <cmath>
#include <numeric>
#include <vector>

namespace vtouch_test
{
using namespace vtouch;

/// The tests' whole extent: 21 x 21 x 11 voxels.
inline const VoxelExtent6 kWhole{ 0, 20, 0, 20, 0, 10 };
/// Two pieces split at x = 10 (the executive's split: the layer x = 10 is shared).
inline PieceOwnership twoPieces()
{
  return PieceOwnership({ { 0, 10, 0, 20, 0, 10 }, { 10, 20, 0, 20, 0, 10 } }, kWhole);
}

inline SkeletonPoint point(double x, double y, double z, double radius_mm = 1.0)
{
  SkeletonPoint p;
  p.position_World_mm = { x, y, z };
  p.radius_mm = radius_mm;
  return p;
}

inline SkeletonPath path(int id, std::vector<SkeletonPoint> points)
{
  SkeletonPath p;
  p.id = id;
  p.points = std::move(points);
  p.points.front().label = PointLabel::EndPoint;
  p.points.back().label = PointLabel::EndPoint;
  return p;
}

/// Attaches `child`'s `end` to `parent`'s point.
inline void attach(QSkeleton& s, int child, Junction::End end, int parent, int parentPoint)
{
  Junction j;
  j.childPath = child;
  j.childEnd = end;
  j.parentPath = parent;
  j.parentPoint = parentPoint;
  SkeletonPath& c = s.paths[static_cast<std::size_t>(child)];
  (end == Junction::End::Head ? c.head : c.tail).junction = static_cast<int>(s.junctions.size());
  SkeletonPoint& q = end == Junction::End::Head ? c.points.front() : c.points.back();
  q.label = PointLabel::Bifurcation;
  q.position_World_mm = s.paths[static_cast<std::size_t>(parent)]
                          .points[static_cast<std::size_t>(parentPoint)]
                          .position_World_mm;
  s.junctions.push_back(j);
}

/// Clips `perPiece[r]` (piece r's own skeleton) with piece r's ownership and stitches them all.
inline QSkeleton clipAndStitch(const std::vector<QSkeleton>& perPiece,
  const PieceOwnership& ownership,
  StitchReport& report)
{
  std::vector<SkeletonFragment> all;
  for (std::size_t r = 0; r < perPiece.size(); ++r)
  {
    const SkeletonClipper clipper(ownership, IndexFrame{}, static_cast<int>(r), kOverlapBandVoxels);
    for (SkeletonFragment& f : clipper.clip(perPiece[r]))
    {
      all.push_back(std::move(f));
    }
  }
  SkeletonStitcher stitcher;
  stitcher.joinTolerance_mm = 1.5;
  stitcher.ownership = ownership;
  return stitcher.stitch(all, report);
}

/// Every piece of `pieces` sends the part of one coded skeleton it owns plus its overlap band
/// (SkeletonClipper in `frame`), and the first rank stitches them with the filter's settings
/// (DistributedCenterline::gatherAndStitch, reaches in voxels of `voxel_mm`): the pieces coded
/// the same centres, so this is the stitch of a distributed run whose coders agree.
/// `fragmentPoints`, if given, receives each sent fragment's point count.
inline QSkeleton clipAndStitchAsTheFilter(const QSkeleton& coded,
  const PieceOwnership& ownership,
  const IndexFrame& frame,
  int pieces,
  double voxel_mm,
  StitchReport& report,
  std::vector<std::size_t>* fragmentPoints = nullptr)
{
  std::vector<SkeletonFragment> all;
  for (int r = 0; r < pieces; ++r)
  {
    for (SkeletonFragment& f : SkeletonClipper(ownership, frame, r, kOverlapBandVoxels).clip(coded))
    {
      all.push_back(std::move(f));
    }
  }
  if (fragmentPoints)
  {
    fragmentPoints->clear();
    for (const SkeletonFragment& f : all)
    {
      fragmentPoints->push_back(f.points.size());
    }
  }
  SkeletonStitcher stitcher;
  stitcher.joinTolerance_mm = 2.0 * voxel_mm;
  stitcher.ownership = ownership;
  stitcher.frame = frame;
  stitcher.copyReach_mm = kCopyReachVoxels * voxel_mm;
  stitcher.coverageReach_mm = kCopyReachVoxels * voxel_mm;
  stitcher.coincidentPoint_mm = kCoincidentPointVoxels * voxel_mm;
  return stitcher.stitch(all, report);
}

/// Independent cycles of the network: junctions - paths + connected parts (each path is a
/// chain, each junction one more edge between two paths' points).
inline int cycleRank(const QSkeleton& s)
{
  std::vector<int> parent(s.paths.size());
  std::iota(parent.begin(), parent.end(), 0);
  const auto find = [&](int a)
  {
    while (parent[static_cast<std::size_t>(a)] != a)
    {
      a = parent[static_cast<std::size_t>(a)];
    }
    return a;
  };
  for (const Junction& j : s.junctions)
  {
    parent[static_cast<std::size_t>(find(j.childPath))] = find(j.parentPath);
  }
  int parts = 0;
  for (std::size_t i = 0; i < s.paths.size(); ++i)
  {
    parts += find(static_cast<int>(i)) == static_cast<int>(i) ? 1 : 0;
  }
  return static_cast<int>(s.junctions.size()) - static_cast<int>(s.paths.size()) + parts;
}

/// Vessel ends: path ends neither attached nor the parent point of a junction (a ring's point 0).
inline int freeEnds(const QSkeleton& s)
{
  const auto isParent = [&s](int path, int point)
  {
    for (const Junction& j : s.junctions)
    {
      if (j.parentPath == path && j.parentPoint == point)
      {
        return true;
      }
    }
    return false;
  };
  int n = 0;
  for (const SkeletonPath& p : s.paths)
  {
    const int last = static_cast<int>(p.points.size()) - 1;
    n += (p.head.junction < 0 && !isParent(p.id, 0)) ? 1 : 0;
    n += (p.tail.junction < 0 && !isParent(p.id, last)) ? 1 : 0;
  }
  return n;
}

/// Every point of `a` has a point of `b` within `tolerance_mm`.
inline bool allPointsNear(const QSkeleton& a, const QSkeleton& b, double tolerance_mm)
{
  for (const SkeletonPath& pa : a.paths)
  {
    for (const SkeletonPoint& p : pa.points)
    {
      double best = 1e300;
      for (const SkeletonPath& pb : b.paths)
      {
        for (const SkeletonPoint& q : pb.points)
        {
          best = std::min(best, (p.position_World_mm - q.position_World_mm).norm());
        }
      }
      if (best > tolerance_mm)
      {
        return false;
      }
    }
  }
  return true;
}
} // namespace vtouch_test

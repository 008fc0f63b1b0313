// Tiny synthetic masks and the voxel-coding stages wired in order, for the stage tests.
#pragma once

#include "vtouchSkeletonBoundaryCodeStage.h"
#include "vtouchSkeletonClusterStage.h"
#include "vtouchSkeletonDraft.h"
#include "vtouchSkeletonEndStage.h"
#include "vtouchSkeletonLoopStage.h"
#include "vtouchSkeletonRunMeter.h"
#include "vtouchSkeletonSeedCodeStage.h"
#include "vtouchSkeletonTraceStage.h"
#include "vtouchSkeletonTracer.h"
#include "vtouchSkeletonVoxelCodes.h"
#include "vtouchSkeletonVoxelGrid.h"
#include "vtouchSparseVesselMask.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <vector>

namespace vtouch
{
namespace skeleton
{
namespace test
{

using Dims = std::array<std::int64_t, 3>;

/// The mask of the voxels (i, j, k) (1 mm voxels: index = position in mm) where `inside` holds.
inline SparseVesselMask makeMask(const Dims& d, const std::function<bool(const Point_mm&)>& inside)
{
  SparseVesselMask mask(d);
  for (std::int64_t k = 0; k < d[2]; ++k)
    for (std::int64_t j = 0; j < d[1]; ++j)
      for (std::int64_t i = 0; i < d[0]; ++i)
      {
        if (inside({ static_cast<double>(i), static_cast<double>(j), static_cast<double>(k) }))
        {
          mask.set(static_cast<std::uint64_t>(i + d[0] * (j + d[1] * k)));
        }
      }
  mask.finalize();
  return mask;
}

/// Distance (mm) from `p` to the segment a-b.
inline double distanceToSegment(const Point_mm& p, const Point_mm& a, const Point_mm& b)
{
  const Point_mm ab{ b[0] - a[0], b[1] - a[1], b[2] - a[2] };
  const Point_mm ap{ p[0] - a[0], p[1] - a[1], p[2] - a[2] };
  const double t = std::clamp((ab[0] * ap[0] + ab[1] * ap[1] + ab[2] * ap[2]) /
                                (ab[0] * ab[0] + ab[1] * ab[1] + ab[2] * ab[2]),
    0.0,
    1.0);
  return distance(p, { a[0] + t * ab[0], a[1] + t * ab[1], a[2] + t * ab[2] });
}

/// A flat-ended tube along x: voxels x0..x1, radius `radius_mm` around (j, k) = (cy, cz).
inline SparseVesselMask flatTube(const Dims& d,
  double x0,
  double x1,
  double cy,
  double cz,
  double radius_mm)
{
  return makeMask(d,
    [&](const Point_mm& p)
    {
      return p[0] >= x0 && p[0] <= x1 &&
             (p[1] - cy) * (p[1] - cy) + (p[2] - cz) * (p[2] - cz) <= radius_mm * radius_mm;
    });
}

/// The Y of the tests: capsules of radius 3 mm in a 40 x 40 x 20 volume, a trunk along y from
/// kYTrunkEnd to kYFork and two branches from the fork to kYLeftEnd and kYRightEnd.
const Point_mm kYFork{ 20, 22, 10 };
const Point_mm kYTrunkEnd{ 20, 4, 10 };
const Point_mm kYLeftEnd{ 9, 34, 10 };
const Point_mm kYRightEnd{ 31, 34, 10 };

/// Distance (mm) from `p` to the Y's axes.
inline double distanceToY(const Point_mm& p)
{
  return std::min({ distanceToSegment(p, kYTrunkEnd, kYFork),
    distanceToSegment(p, kYFork, kYLeftEnd),
    distanceToSegment(p, kYFork, kYRightEnd) });
}

inline SparseVesselMask yShape()
{
  return makeMask({ 40, 40, 20 }, [](const Point_mm& p) { return distanceToY(p) <= 3.0; });
}

/// The stages of one component run by hand, in VoxelCoder's order, on 1 mm voxels.
struct Pipeline
{
  explicit Pipeline(const SparseVesselMask& m, double minimumBranchLength = 2.5)
    : mask(m)
    , meter(noProgress)
    , grid(m, { 1.0, 1.0, 1.0 }, 0.0)
    , minimumBranchLength_radii(minimumBranchLength)
  {
    const std::uint64_t n = m.vesselCount();
    codes.bs.assign(n, VoxelCodes::kInf);
    codes.ss.assign(n, VoxelCodes::kInf);
    codes.flags.assign(n, 0);
    graph.label.assign(n, 0);
  }

  std::uint32_t lin(std::int64_t i, std::int64_t j, std::int64_t k) const
  {
    return static_cast<std::uint32_t>(grid.linOf(i, j, k));
  }
  std::uint32_t rank(std::int64_t i, std::int64_t j, std::int64_t k) const
  {
    return mask.rank(grid.linOf(i, j, k));
  }

  /// Stages 1-2: the BS code, and the SS code from `source`.
  void code(std::uint32_t source)
  {
    BoundaryCodeStage boundary(grid, meter, codes.bs);
    boundary.start();
    boundary.await();
    seed.propagate({ source });
  }
  /// Stage 3.
  void cluster() { clusters.build(); }
  /// Stage 4; the number of paths.
  std::size_t trace() { return TraceStage(tracer, minimumBranchLength_radii).run(); }
  /// Stage 5.
  void loops() { LoopStage(tracer, minimumBranchLength_radii, 0).run(); }
  /// Stage 6.
  void ends() { EndStage(grid, minimumBranchLength_radii, draft, 0).run(); }

  const SparseVesselMask& mask;
  std::function<bool(double)> noProgress;
  RunMeter meter;
  VoxelGrid grid;
  double minimumBranchLength_radii;
  VoxelCodes codes;
  ClusterGraph graph;
  SkeletonDraft draft;
  SeedCodeStage seed{ grid, meter, codes, 0.0 };
  ClusterStage clusters{ grid, meter, codes, graph };
  SkeletonTracer tracer{ grid, meter, codes, graph, draft };
};

} // namespace test
} // namespace skeleton
} // namespace vtouch

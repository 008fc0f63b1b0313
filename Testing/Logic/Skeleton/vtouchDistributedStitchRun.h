// The filter's distributed run without MPI (issue 19 item 2, h19q): each rank, a thread, codes
// its grown piece of a phantom volume with VoxelCodingSkeletonFilter and the single run's SS
// field (DistributedSeedCode from the single run's root, as the filter's global-field hook), the
// face tips' order across the pieces (DistributedFaceTips, as the filter's second hook),
// clips it to its owned box and the overlap band (SkeletonClipper, kOverlapBandVoxels) and the
// pieces are stitched (SkeletonStitcher, configured as DistributedCenterline::gatherAndStitch).
// As the filter, the ranks keep their centres (positions unsmoothed) and the stitched whole
// paths are smoothed (smoothSkeletonPaths).
// What the geometry tests compare with the single run: the stitched skeleton and, to tell a
// coding cause from a stitching one, each rank's own unclipped skeleton.
#pragma once

#include "vtouchPhantomSpec.h"
#include "vtouchPieceOwnership.h"
#include "vtouchQSkeleton.h"
#include "vtouchRoundsOutcome.h"
#include "vtouchSkeletonStitcher.h"
#include "vtouchVoxelCoding.h"

#include <array>
#include <cstdint>
#include <map>
#include <utility>
#include <vector>

namespace vtouch::test
{

struct DistributedStitchRun
{
  QSkeleton single;                   ///< the single run (the whole volume, unseeded or seeded)
  std::vector<QSkeleton> pieces;      ///< each rank's own skeleton, world frame, unclipped
  QSkeleton stitchedCentres;          ///< the pieces clipped and stitched: the ranks' centres
  QSkeleton stitched;                 ///< the same, its whole paths smoothed (the output)
  RawSkeleton rawSingle;              ///< the single run's coder output (whole voxel indices)
  std::vector<RawSkeleton> rawPieces; ///< each rank's coder output (voxels: whole indices)
  StitchReport report;                ///< what the stitch did
  PieceOwnership ownership;           ///< the executive's split
  std::array<std::int64_t, 3> root{}; ///< the single run's (first) root voxel
  std::array<std::int64_t, 3> dims{}; ///< the volume's voxels per axis
};

/// `spec`'s volume thresholded at `lower` (VesselCenterline: AutomaticIntensityRange off), split
/// as the executive splits it into `counts` pieces, each grown by `ghost_voxels`. `seeded`: the
/// single run and the field from `seed` (whole voxel index, a vessel voxel); else the single
/// run's automatic root.
DistributedStitchRun runDistributedStitch(const PhantomSpec& spec,
  double lower,
  const std::array<int, 3>& counts,
  int ghost_voxels,
  bool seeded = false,
  const std::array<std::int64_t, 3>& seed = {});

/// The same on any volume: `voxels` (x fastest) of `dims` voxels of 1 mm at 0. `clearOuterLayer`:
/// each rank's mask loses its outermost layer on shared faces before coding and the face tips
/// are at the evaluable box's faces, as the filter's raw seeded mode codes its region
/// (SeededDistributedCoding::Settings::clearOuterLayer). `frame`: the volume's origin and
/// spacing (axis-aligned; default 1 mm voxels at 0); each rank's piece is an image whose origin
/// is its first voxel's world position and is told where it lies in the whole volume
/// (VoxelCodingSkeletonFilter::SetPieceInWhole), as the filter's ranks are
/// (DistributedCenterline::pieceFromIndexZero, pieceInWhole).
DistributedStitchRun runDistributedStitch(const std::vector<float>& voxels,
  const std::array<std::int64_t, 3>& dims,
  double lower,
  const std::array<int, 3>& counts,
  int ghost_voxels,
  bool seeded = false,
  const std::array<std::int64_t, 3>& seed = {},
  bool clearOuterLayer = false,
  const IndexFrame& frame = IndexFrame{});

/// The largest distance from a point of `a` to the nearest point of `b`, mm; only points of `a`
/// farther than `awayFrom_mm` from `avoid` count (a root's neighbourhood; `awayFrom_mm` 0: all).
double farthestPoint_mm(const QSkeleton& a,
  const QSkeleton& b,
  const Vec3& avoid = {},
  double awayFrom_mm = 0.0);

/// Free vessel ends (neither attached nor a parent point) and junction parent points.
int freeEnds(const QSkeleton& s);

} // namespace vtouch::test

#include "vtouchDistributedStitchRun.h"

#include "vtouchDistributedFaceTips.h"
#include "vtouchDistributedSeedCode.h"
#include "vtouchEveryRank.h"
#include "vtouchPhantomGenerator.h"
#include "vtouchPieceGrid.h"
#include "vtouchSeededDistributedCoding.h"
#include "vtouchSkeletonClipper.h"
#include "vtouchSkeletonOverlapResolver.h"
#include "vtouchSkeletonPathSmoothing.h"
#include "vtouchVoxelCodingSkeletonFilter.h"

#include <itkImage.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <stdexcept>
#include <string>

namespace vtouch::test
{
namespace
{
using FloatImage = itk::Image<float, 3>;
using Filter = VoxelCodingSkeletonFilter<FloatImage>;
using Index = std::array<std::int64_t, 3>;

/// The voxels of `box` of the whole volume `voxels` (x fastest), as an image whose first voxel
/// lies at the box's world position in `frame` (axis-aligned), computed as
/// DistributedCenterline::pieceFromIndexZero does (vtkImageData::TransformIndexToPhysicalPoint:
/// origin + index * spacing): the piece coded from its first voxel.
FloatImage::Pointer imageOf(const std::vector<float>& voxels,
  const Index& dims,
  const VoxelBox& box,
  const IndexFrame& frame)
{
  auto image = FloatImage::New();
  FloatImage::SizeType size;
  FloatImage::PointType origin;
  FloatImage::SpacingType spacing;
  for (unsigned a = 0; a < 3; ++a)
  {
    size[a] = static_cast<itk::SizeValueType>(box.hi[a] - box.lo[a] + 1);
    origin[a] = frame.origin_mm[a] + static_cast<double>(box.lo[a]) * frame.spacing_mm[a];
    spacing[a] = frame.spacing_mm[a];
  }
  image->SetRegions(FloatImage::RegionType(size));
  image->SetOrigin(origin);
  image->SetSpacing(spacing);
  image->Allocate();
  float* out = image->GetBufferPointer();
  for (std::int64_t k = box.lo[2]; k <= box.hi[2]; ++k)
    for (std::int64_t j = box.lo[1]; j <= box.hi[1]; ++j)
      for (std::int64_t i = box.lo[0]; i <= box.hi[0]; ++i)
      {
        *out++ = voxels[static_cast<std::size_t>(i + dims[0] * (j + dims[1] * k))];
      }
  return image;
}

/// VesselCenterline's SmoothingWindow: its automatic windows (0); a diagnostic may fix them for
/// every path (VESSELTOUCH_STITCH_SMOOTHING, mm: the windows then do not depend on a path's
/// median radius).
double smoothingWindow_mm()
{
  const char* smoothing = std::getenv("VESSELTOUCH_STITCH_SMOOTHING");
  return smoothing ? std::atof(smoothing) : 0.0;
}

/// VesselCenterline's coder settings (its defaults, thresholded from `lower`).
Filter::Pointer coder(FloatImage* image, double lower)
{
  auto filter = Filter::New();
  filter->SetInput(image);
  filter->SetLowerThreshold(lower);
  filter->SetMinimumComponentSize(100);
  filter->SetMinimumBranchLength(2.5);
  filter->SetSmoothingWindow(smoothingWindow_mm());
  filter->SetDownsampleFactor(0);
  return filter;
}

/// The executive's split by cells (neighbouring pieces share a face layer), as extents.
std::vector<VoxelExtent6> executiveSplit(const Index& dims, const std::array<int, 3>& counts)
{
  std::vector<VoxelExtent6> out;
  const std::vector<PieceLayout> l = layouts(dims, counts, 0);
  for (const VoxelBox& owned : l.front().owned)
  {
    VoxelExtent6 e{};
    for (int a = 0; a < 3; ++a)
    {
      e[2 * a] = static_cast<int>(owned.lo[a]);
      e[2 * a + 1] = static_cast<int>(owned.hi[a] < dims[a] - 1 ? owned.hi[a] + 1 : owned.hi[a]);
    }
    out.push_back(e);
  }
  return out;
}
} // namespace

DistributedStitchRun runDistributedStitch(const PhantomSpec& spec,
  double lower,
  const std::array<int, 3>& counts,
  int ghost_voxels,
  bool seeded,
  const Index& seed)
{
  const PhantomGenerator phantom(spec);
  if (!phantom.ok())
  {
    throw std::invalid_argument("phantom: " + phantom.error());
  }
  const Index dims{ spec.dimensions[0], spec.dimensions[1], spec.dimensions[2] };
  std::vector<float> voxels(static_cast<std::size_t>(dims[0] * dims[1] * dims[2]));
  phantom.fill(voxels.data());
  return runDistributedStitch(voxels, dims, lower, counts, ghost_voxels, seeded, seed, false);
}

DistributedStitchRun runDistributedStitch(const std::vector<float>& voxels,
  const Index& dims,
  double lower,
  const std::array<int, 3>& counts,
  int ghost_voxels,
  bool seeded,
  const Index& seed,
  bool clearOuterLayer,
  const IndexFrame& frame)
{
  DistributedStitchRun run;
  run.dims = dims;
  // The single run: the whole volume.
  const VoxelBox whole{ { 0, 0, 0 }, { dims[0] - 1, dims[1] - 1, dims[2] - 1 } };
  FloatImage::Pointer wholeImage = imageOf(voxels, dims, whole, frame);
  Filter::Pointer single = coder(wholeImage, lower);
  if (seeded)
  {
    Filter::PointType p;
    for (unsigned a = 0; a < 3; ++a)
    {
      p[a] = frame.origin_mm[a] + static_cast<double>(seed[a]) * frame.spacing_mm[a];
    }
    single->SetSeedPoint(p);
  }
  single->Update();
  run.single = single->GetSkeleton();
  run.rawSingle = single->GetRawSkeleton();
  const RawSkeleton& raw = run.rawSingle;
  std::vector<Index> roots;
  if (seeded)
  {
    roots.push_back(seed);
  }
  for (const RawComponentRoot& r : seeded ? std::vector<RawComponentRoot>() : raw.roots)
  {
    // The root each component is coded from: the thickest end when moved, else the end cap's
    // voxel(s) it was first propagated from.
    if (r.moved)
    {
      roots.push_back(r.thickest);
    }
    else
    {
      roots.insert(roots.end(), r.extremity.begin(), r.extremity.end());
    }
  }
  if (roots.empty())
  {
    throw std::invalid_argument("the volume has no vessel component");
  }
  run.root = roots.front();
  // Every rank: its grown piece coded with the single run's field (the filter's hook).
  const std::vector<PieceLayout> layout = layouts(dims, counts, ghost_voxels);
  run.rawPieces.resize(layout.size());
  run.pieces = onEveryRank<QSkeleton>(layout,
    [&](const PieceLayout& l, RankCollectives& c, QSkeleton& out)
    {
      FloatImage::Pointer piece = imageOf(voxels, dims, l.mine(), frame);
      Filter::Pointer filter = coder(piece, lower);
      // Where the piece lies in the whole volume (DistributedCenterline::pieceInWhole).
      filter->SetPieceInWhole({ l.mine().lo, frame.origin_mm });
      // The centres kept: the whole paths are smoothed after the stitch, as the filter's first
      // rank does (smoothSkeletonPaths).
      filter->SetSmoothingWindow(kPositionsKeptWindow_mm);
      // The face tips' order across the pieces, as the filter's DistributedGlobalField gives it.
      DistributedFaceTips faceTips(c, l);
      faceTips.setOuterLayerCleared(clearOuterLayer);
      filter->SetGlobalFaceTips(
        [&faceTips](const skeleton::SkeletonTracer& t) { return faceTips.answer(t); });
      filter->SetGlobalSeedCode(
        [&](SparseVesselMask& mask)
        {
          if (clearOuterLayer)
          {
            vtouch::clearOuterLayer(mask, l); // as SeededDistributedCoding (the raw seeded mode)
          }
          DistributedSeedCode code(l, mask, frame.spacing_mm);
          code.run(c, roots);
          return code.ss();
        });
      filter->Update();
      out = filter->GetSkeleton();
      RawSkeleton& raw = run.rawPieces[static_cast<std::size_t>(l.rank)];
      raw = filter->GetRawSkeleton();
      for (RawSkeletonPath& path : raw.paths)
      {
        for (std::array<std::int64_t, 3>& v : path.voxels)
        {
          v = l.toWhole(v);
        }
      }
    });
  // Clip and stitch as DistributedCenterline::gatherAndStitch (DistributedRequest: the join
  // tolerance is two of the largest spacing, the reaches in the largest spacing).
  const VoxelExtent6 wholeExtent{ 0, int(dims[0] - 1), 0, int(dims[1] - 1), 0, int(dims[2] - 1) };
  run.ownership = PieceOwnership(executiveSplit(dims, counts), wholeExtent);
  const double voxel_mm = *std::max_element(frame.spacing_mm.begin(), frame.spacing_mm.end());
  std::vector<SkeletonFragment> all;
  for (std::size_t r = 0; r < run.pieces.size(); ++r)
  {
    const std::vector<SkeletonFragment> f =
      SkeletonClipper(run.ownership, frame, static_cast<int>(r), kOverlapBandVoxels)
        .clip(run.pieces[r]);
    all.insert(all.end(), f.begin(), f.end());
  }
  SkeletonStitcher stitcher;
  stitcher.joinTolerance_mm = 2.0 * voxel_mm;
  stitcher.ownership = run.ownership;
  stitcher.frame = frame;
  stitcher.copyReach_mm = kCopyReachVoxels * voxel_mm;
  stitcher.coverageReach_mm = kCopyReachVoxels * voxel_mm;
  stitcher.coincidentPoint_mm = kCoincidentPointVoxels * voxel_mm;
  run.stitchedCentres = stitcher.stitch(all, run.report);
  run.stitched = run.stitchedCentres;
  smoothSkeletonPaths(run.stitched, voxel_mm, smoothingWindow_mm()); // the coder's (coder())
  return run;
}

double farthestPoint_mm(const QSkeleton& a,
  const QSkeleton& b,
  const Vec3& avoid,
  double awayFrom_mm)
{
  double worst = 0.0;
  for (const SkeletonPath& pa : a.paths)
  {
    for (const SkeletonPoint& p : pa.points)
    {
      if (awayFrom_mm > 0.0 && (p.position_World_mm - avoid).norm() <= awayFrom_mm)
      {
        continue;
      }
      double best = std::numeric_limits<double>::infinity();
      for (const SkeletonPath& pb : b.paths)
      {
        for (const SkeletonPoint& q : pb.points)
        {
          best = std::min(best, (p.position_World_mm - q.position_World_mm).norm());
        }
      }
      worst = std::max(worst, best);
    }
  }
  return worst;
}

int freeEnds(const QSkeleton& s)
{
  std::vector<std::pair<int, int>> parents;
  for (const Junction& j : s.junctions)
  {
    parents.emplace_back(j.parentPath, j.parentPoint);
  }
  const auto isParent = [&](int path, int point) {
    return std::find(parents.begin(), parents.end(), std::make_pair(path, point)) != parents.end();
  };
  int ends = 0;
  for (std::size_t p = 0; p < s.paths.size(); ++p)
  {
    const SkeletonPath& path = s.paths[p];
    const int last = static_cast<int>(path.points.size()) - 1;
    ends += path.head.junction < 0 && !isParent(static_cast<int>(p), 0) ? 1 : 0;
    ends += path.tail.junction < 0 && !isParent(static_cast<int>(p), last) ? 1 : 0;
  }
  return ends;
}

} // namespace vtouch::test

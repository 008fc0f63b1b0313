#include "vtouchDistributedRawRefinement.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <utility>

namespace vtouch
{

std::vector<std::int64_t> DistributedRawRefinement::prefetchPages(const QSkeleton& skeleton,
  const SectionGeometry& geometry,
  const DistributedVolumePages& pages,
  const std::array<std::int64_t, 3>& wholeDims,
  const Settings& settings)
{
  const SectionForeground grid{ wholeDims, {} }; // nearestVoxel reads only the dims
  const SectionSampler sampler(grid, geometry);
  const std::array<std::int64_t, 3>& per = pages.pagesPerAxis();
  std::vector<char> wanted(static_cast<std::size_t>(per[0] * per[1] * per[2]), 0);
  const std::int64_t edge = DistributedVolumePages::kPageEdge_voxels;
  for (const SkeletonPath& path : skeleton.paths)
  {
    for (const SkeletonPoint& p : path.points)
    {
      std::array<std::int64_t, 3> c{ 0, 0, 0 };
      if (!sampler.nearestVoxel(p.position_World_mm, c))
      {
        continue;
      }
      const double r = std::max(0.5, p.radius_mm / sampler.voxel_mm());
      const double bound_mm =
        (settings.prefetchRadii * r + settings.prefetchMargin_voxels) * sampler.voxel_mm();
      std::array<std::int64_t, 3> lo{ 0, 0, 0 }, hi{ 0, 0, 0 };
      for (std::size_t a = 0; a < 3; ++a)
      {
        // The direction is a rotation: a ball of bound_mm spans bound_mm / spacing on each axis.
        const auto b = static_cast<std::int64_t>(std::ceil(bound_mm / geometry.spacing_mm[a]));
        lo[a] = std::max<std::int64_t>(0, c[a] - b) / edge;
        hi[a] = std::min<std::int64_t>(wholeDims[a] - 1, c[a] + b) / edge;
      }
      for (std::int64_t k = lo[2]; k <= hi[2]; ++k)
        for (std::int64_t j = lo[1]; j <= hi[1]; ++j)
          for (std::int64_t i = lo[0]; i <= hi[0]; ++i)
          {
            wanted[static_cast<std::size_t>(i + per[0] * (j + per[1] * k))] = 1;
          }
    }
  }
  std::vector<std::int64_t> out;
  for (std::size_t p = 0; p < wanted.size(); ++p)
  {
    if (wanted[p])
    {
      out.push_back(static_cast<std::int64_t>(p));
    }
  }
  return out;
}

DistributedRawRefinement::Result DistributedRawRefinement::run(RankCollectives& collectives,
  const PieceLayout& layout,
  DistributedVolumePages::OwnedIntensity mine,
  QSkeleton* skeleton,
  const SectionGeometry& geometry,
  const Settings& settings)
{
  const auto start = std::chrono::steady_clock::now();
  Result result;
  DistributedVolumePages pages(collectives, layout, std::move(mine));
  const bool first = collectives.rank() == 0;
  std::vector<std::int64_t> prefetch;
  std::function<void()> reader;
  QSkeleton work;
  if (first && skeleton && !skeleton->empty())
  {
    prefetch = prefetchPages(*skeleton, geometry, pages, layout.wholeDims, settings);
    result.pagesPrefetched = static_cast<std::int64_t>(prefetch.size());
    const SectionForeground inRange = pages.inRange(settings.lower, settings.upper);
    const TurnedDimTipTrimmer::Evidence tips{
      pages.intensity(), settings.lower, settings.background, settings.backgroundNoise
    };
    // Every run from the untouched stitched skeleton: a miss leaves `work` half refined.
    reader = [&, inRange, tips]
    {
      work = *skeleton;
      result.refinement =
        RawSkeletonRefinement::apply(work, inRange, geometry, settings.smoothingWindow_mm, &tips);
    };
  }
  result.pages = pages.run(prefetch, reader);
  if (first && reader && result.pages.completed)
  {
    *skeleton = std::move(work);
    result.refined = true;
  }
  result.message = result.pages.message;
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

} // namespace vtouch

#include "vtouchAutomaticDownsampling.h"

#include <algorithm>
#include <cmath>

namespace vtouch
{

double AutomaticDownsampling::typicalRadius_vox(const SparseVesselMask& mask)
{
  const auto& d = mask.dims();
  const auto nx = static_cast<std::uint64_t>(d[0]);
  const auto nxy = static_cast<std::uint64_t>(d[0] * d[1]);
  const std::uint64_t n = mask.voxelCount();
  std::uint64_t surface = 0;
  mask.forEach(
    [&](std::uint64_t lin)
    {
      const std::uint64_t i = lin % nx;
      const std::uint64_t j = (lin / nx) % static_cast<std::uint64_t>(d[1]);
      // Out of the volume counts as outside: a vessel cut by the border has a surface there.
      const bool inside = i > 0 && i + 1 < nx && j > 0 &&
                          j + 1 < static_cast<std::uint64_t>(d[1]) && lin >= nxy && lin + nxy < n &&
                          mask.test(lin - 1) && mask.test(lin + 1) && mask.test(lin - nx) &&
                          mask.test(lin + nx) && mask.test(lin - nxy) && mask.test(lin + nxy);
      surface += inside ? 0 : 1;
    });
  return surface == 0
           ? 0.0
           : 2.0 * static_cast<double>(mask.vesselCount()) / static_cast<double>(surface);
}

unsigned int AutomaticDownsampling::factorFor(const SparseVesselMask& mask,
  const std::array<double, 3>& spacing_mm)
{
  if (mask.vesselCount() < kMinimumVesselVoxels)
  {
    return 1;
  }
  const double meanSpacing_mm = std::cbrt(spacing_mm[0] * spacing_mm[1] * spacing_mm[2]);
  const double maxSpacing_mm = std::max({ spacing_mm[0], spacing_mm[1], spacing_mm[2] });
  const double radius_mm = typicalRadius_vox(mask) * meanSpacing_mm;
  const double f = std::floor(radius_mm / (kCoarseRadius_vox * maxSpacing_mm));
  return static_cast<unsigned int>(std::clamp(f, 1.0, static_cast<double>(kMaximumFactor)));
}

bool AutomaticDownsampling::resolvesEveryBranch(const RawSkeleton& coarse, double coarseVoxel_mm)
{
  for (const RawSkeletonPath& path : coarse.paths)
  {
    if (path.radius_mm.empty())
    {
      continue;
    }
    std::vector<double> r = path.radius_mm;
    std::nth_element(r.begin(), r.begin() + r.size() / 2, r.end());
    const double median_mm = r[r.size() / 2];
    const double length_mm = coarseVoxel_mm * static_cast<double>(path.voxels.size());
    if (length_mm > 2.0 * median_mm && median_mm < kBranchRadius_vox * coarseVoxel_mm)
    {
      return false;
    }
  }
  return true;
}

} // namespace vtouch

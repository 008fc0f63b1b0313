#include "vtouchSeedCodeRun.h"

namespace vtouch::test
{

SeedCodeRun::SeedCodeRun(const SparseVesselMask& mask, const std::array<double, 3>& spacing_mm)
  : grid(mask, spacing_mm, 0.0)
  , meter(noProgress)
  , stage(grid, meter, codes, 0.0)
{
  codes.ss.assign(mask.vesselCount(), skeleton::VoxelCodes::kInf);
  codes.flags.assign(mask.vesselCount(), 0);
}

const std::vector<float>& SeedCodeRun::propagateFrom(
  const std::vector<std::array<std::int64_t, 3>>& roots)
{
  std::vector<std::uint32_t> sources;
  for (const std::array<std::int64_t, 3>& v : roots)
  {
    sources.push_back(linOf(v));
  }
  stage.propagate(sources);
  return codes.ss;
}

float SeedCodeRun::ssAt(const std::array<std::int64_t, 3>& v) const
{
  return codes.ss[grid.mask.rank(grid.linOf(v[0], v[1], v[2]))];
}

std::uint32_t SeedCodeRun::linOf(const std::array<std::int64_t, 3>& v) const
{
  return static_cast<std::uint32_t>(grid.linOf(v[0], v[1], v[2]));
}

std::vector<float> singleRunField(const SparseVesselMask& mask,
  const std::array<double, 3>& spacing_mm,
  const std::vector<std::array<std::int64_t, 3>>& roots)
{
  SeedCodeRun run(mask, spacing_mm);
  return run.propagateFrom(roots);
}

RawSkeleton seededSkeleton(const SparseVesselMask& mask,
  const std::array<double, 3>& spacing_mm,
  const std::array<std::int64_t, 3>& root)
{
  VoxelCodingParameters seeded;
  seeded.spacing_mm = spacing_mm;
  seeded.hasSeed = true;
  seeded.seedIndex = root;
  return VoxelCoder(mask, seeded).run();
}

} // namespace vtouch::test

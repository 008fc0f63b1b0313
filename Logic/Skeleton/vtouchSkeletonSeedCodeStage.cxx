// Voxel coding stage 2: the SS code and the root at an extremity (double propagation).
#include "vtouchSkeletonSeedCodeStage.h"

#include "vtouchBucketQueue.h"
#include "vtouchSkeletonEndCapRule.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace vtouch
{
namespace skeleton
{
namespace
{
constexpr float kInf = VoxelCodes::kInf;
constexpr std::uint8_t kDone = VoxelCodes::kDone;
constexpr std::uint8_t kComponent = VoxelCodes::kComponent;
constexpr std::uint8_t kRegion = VoxelCodes::kRegion;
} // namespace

/// The exploratory propagation's own mask, grid, codes and stage (no progress of its own).
struct SeedCodeStage::Explorer
{
  Explorer(const SparseVesselMask& fine, const VoxelGrid& fineGrid, double clusterWidth_mm)
    : mask(fine.downsampled(2))
    , grid(mask,
        { 2.0 * fineGrid.sp[0], 2.0 * fineGrid.sp[1], 2.0 * fineGrid.sp[2] },
        clusterWidth_mm)
    , meter(noProgress)
    , stage(grid, meter, codes, clusterWidth_mm)
  {
    codes.ss.assign(mask.vesselCount(), VoxelCodes::kInf);
    codes.flags.assign(mask.vesselCount(), 0);
  }
  SparseVesselMask mask;
  VoxelGrid grid;
  VoxelCodes codes;
  std::function<bool(double)> noProgress;
  RunMeter meter;
  SeedCodeStage stage;
};

SeedCodeStage::SeedCodeStage(const VoxelGrid& g, RunMeter& m, VoxelCodes& c, double clusterWidth)
  : grid(g)
  , meter(m)
  , codes(c)
  , clusterWidth_mm(clusterWidth)
{
}

SeedCodeStage::~SeedCodeStage() = default;

std::size_t SeedCodeStage::explorerBytes() const
{
  if (!explorer)
  {
    return 0;
  }
  return explorer->mask.memoryBytes() + explorer->codes.ss.capacity() * (sizeof(float) + 1) +
         explorer->codes.order.capacity() * sizeof(std::uint32_t) +
         explorer->stage.peakQueue() * sizeof(std::uint32_t);
}

void SeedCodeStage::propagate(const std::vector<std::uint32_t>& sources)
{
  const StageTimer timer{ meter, "ss" };
  BucketQueue queue(grid.minSpacing, grid.maxSpacing * std::sqrt(3.0));
  codes.order.clear();
  // The inner loop's arrays, held here (their size does not change while it runs).
  float* const ss = codes.ss.data();
  std::uint8_t* const flags = codes.flags.data();
  for (std::uint32_t s : sources)
  {
    ss[grid.mask.rank(s)] = 0.0F;
    queue.push(s, 0.0);
  }
  std::uint32_t lin = 0;
  std::uint32_t pops = 0;
  while (queue.pop(lin))
  {
    if ((++pops & 0xFFFF) == 0)
    {
      meter.checkpoint(); // stale entries are not work, but they take time
    }
    const std::uint32_t r = grid.mask.rank(lin);
    if (flags[r] & kDone)
    {
      continue; // a stale entry of a voxel improved while queued
    }
    flags[r] |= kDone;
    codes.order.push_back(lin);
    const float d = ss[r];
    // No test of the neighbours' kDone flags (a cache miss each): a finalized neighbour u left a
    // bucket at or below the current one, so ss[u] < d + bucket width <= d + any edge, and the
    // comparison below already rejects it.
    grid.forNeighbours(lin,
      [&](std::uint64_t u, int n, std::uint32_t ru)
      {
        const float nd = d + grid.offLenF[n];
        if (nd < ss[ru])
        {
          ss[ru] = nd;
          queue.push(static_cast<std::uint32_t>(u), nd);
        }
      });
    meter.tick();
  }
  peakQueueEntries = std::max(peakQueueEntries, queue.peak());
}

std::size_t SeedCodeStage::relax(std::vector<Source> sources, std::vector<std::uint32_t>& lowered)
{
  const StageTimer timer{ meter, "ss" };
  BucketQueue queue(grid.minSpacing, grid.maxSpacing * std::sqrt(3.0));
  // Ascending distance (ties in the callers' order): each enters the queue at its own bucket.
  std::stable_sort(sources.begin(),
    sources.end(),
    [](const Source& a, const Source& b) { return a.ss_mm < b.ss_mm; });
  float* const ss = codes.ss.data();
  std::uint8_t* const flags = codes.flags.data();
  const auto lower = [&](std::uint32_t lin, std::uint32_t r, float d)
  {
    ss[r] = d;
    flags[r] &= static_cast<std::uint8_t>(~kDone);
    lowered.push_back(lin);
    queue.push(lin, d);
  };
  std::size_t next = 0;
  std::size_t settled = 0;
  std::uint32_t lin = 0;
  std::uint32_t pops = 0;
  while (true)
  {
    const std::uint64_t last = next < sources.size() ? queue.bucketOf(sources[next].ss_mm)
                                                     : std::numeric_limits<std::uint64_t>::max();
    if (!queue.popUpTo(lin, last))
    {
      if (next == sources.size())
      {
        break;
      }
      // Every entry below the next source's bucket is final: that bucket's sources join it.
      queue.skipTo(last);
      for (; next < sources.size() && queue.bucketOf(sources[next].ss_mm) == last; ++next)
      {
        const Source& s = sources[next];
        const std::uint32_t r = grid.mask.rank(s.lin);
        if (s.ss_mm < ss[r])
        {
          lower(s.lin, r, s.ss_mm);
        }
      }
      continue;
    }
    if ((++pops & 0xFFFF) == 0)
    {
      meter.checkpoint();
    }
    const std::uint32_t r = grid.mask.rank(lin);
    if (flags[r] & kDone)
    {
      continue; // a stale entry of a voxel lowered while queued
    }
    flags[r] |= kDone;
    ++settled;
    const float d = ss[r];
    grid.forNeighbours(lin,
      [&](std::uint64_t u, int n, std::uint32_t ru)
      {
        const float nd = d + grid.offLenF[n];
        if (nd < ss[ru])
        {
          lower(static_cast<std::uint32_t>(u), ru, nd);
        }
      });
    meter.tick();
  }
  peakQueueEntries = std::max(peakQueueEntries, queue.peak());
  return settled;
}

void SeedCodeStage::reset()
{
  for (std::uint32_t lin : codes.order)
  {
    const std::uint32_t r = grid.mask.rank(lin);
    codes.flags[r] &= static_cast<std::uint8_t>(~kDone);
    codes.ss[r] = kInf;
  }
}

std::uint32_t SeedCodeStage::farVoxel() const
{
  std::uint32_t far = codes.order.front();
  std::uint64_t farB = farBucket(codes.ss[grid.mask.rank(far)], grid.minSpacing);
  for (const std::uint32_t lin : codes.order)
  {
    const std::uint64_t b = farBucket(codes.ss[grid.mask.rank(lin)], grid.minSpacing);
    if (fartherVoxel(b, lin, farB, far))
    {
      far = lin;
      farB = b;
    }
  }
  return far;
}

std::vector<std::uint32_t> SeedCodeStage::extremityRegion()
{
  const std::uint32_t far = farVoxel();
  const float threshold = codes.ss[grid.mask.rank(far)] - static_cast<float>(grid.bandWidth);
  std::vector<std::uint32_t> region{ far };
  codes.flags[grid.mask.rank(far)] |= kRegion;
  for (std::size_t q = 0; q < region.size(); ++q)
  {
    grid.forNeighbours(region[q],
      [&](std::uint64_t u, int, std::uint32_t ru)
      {
        if (!(codes.flags[ru] & kRegion) && codes.ss[ru] >= threshold)
        {
          codes.flags[ru] |= kRegion;
          region.push_back(static_cast<std::uint32_t>(u));
        }
      });
  }
  std::array<std::int64_t, 3> sum{ 0, 0, 0 };
  for (std::uint32_t lin : region)
  {
    codes.flags[grid.mask.rank(lin)] &= static_cast<std::uint8_t>(~kRegion);
    std::int64_t c[3];
    grid.coords(lin, c);
    for (int a = 0; a < 3; ++a)
    {
      sum[a] += c[a];
    }
  }
  // One root voxel at the centre of the end cap when it is vessel: every trace converges there.
  // Integer sums (project rule, issue 19 item 2): the distributed run adds the pieces' sums.
  const std::array<std::int64_t, 3> v =
    nearestIndex(indexCentroid(sum, region.size()), { grid.nx, grid.ny, grid.nz });
  const std::uint64_t centre = grid.linOf(v[0], v[1], v[2]);
  if (grid.mask.test(centre))
  {
    return { static_cast<std::uint32_t>(centre) };
  }
  return region;
}

std::uint32_t SeedCodeStage::coarseExtremity(std::uint32_t lin)
{
  if (grid.mask.vesselCount() < kCoarseFromVoxels || grid.nx < 2 || grid.ny < 2 || grid.nz < 2)
  {
    return kNoVoxel;
  }
  const StageTimer timer{ meter, "explore" };
  if (!explorer)
  {
    explorer = std::make_unique<Explorer>(grid.mask, grid, clusterWidth_mm);
  }
  VoxelCodes& coarse = explorer->codes;
  const VoxelGrid& coarseGrid = explorer->grid;
  std::int64_t c[3];
  grid.coords(lin, c);
  const auto blockOf = [&](const std::int64_t* v)
  {
    return static_cast<std::uint32_t>(
      v[0] / 2 + coarseGrid.nx * (v[1] / 2 + coarseGrid.ny * (v[2] / 2)));
  };
  const std::uint32_t start = blockOf(c);
  if (coarse.flags[coarseGrid.mask.rank(start)] & kComponent)
  {
    // Its blocks touch a component already explored (small blobs beside a vessel): the exact
    // search costs the blob's size, another block propagation would cost the vessel's.
    return kNoVoxel;
  }
  explorer->stage.propagate({ start });
  const std::vector<std::uint32_t> region = explorer->stage.extremityRegion();
  for (const std::uint32_t b : coarse.order)
  {
    coarse.flags[coarseGrid.mask.rank(b)] |= kComponent;
  }
  std::array<std::int64_t, 3> blockSum{ 0, 0, 0 };
  for (const std::uint32_t b : region)
  {
    std::int64_t bc[3];
    coarseGrid.coords(b, bc);
    for (int a = 0; a < 3; ++a)
    {
      blockSum[a] += bc[a];
    }
  }
  const std::array<double, 3> centre = blockCentre(blockSum, region.size()); // fine indices
  explorer->stage.reset();
  // The vessel voxel nearest the end cap's centre, within the blocks around it.
  std::uint32_t best = kNoVoxel;
  double bestDistance = std::numeric_limits<double>::infinity();
  const CentreWindow window(centre, { grid.nx, grid.ny, grid.nz });
  for (std::int64_t k = window.lo[2]; k <= window.hi[2]; ++k)
    for (std::int64_t j = window.lo[1]; j <= window.hi[1]; ++j)
      for (std::int64_t i = window.lo[0]; i <= window.hi[0]; ++i)
      {
        const auto v = static_cast<std::uint64_t>(i + grid.nx * (j + grid.ny * k));
        const double d = CentreWindow::distance2_mm2(centre, grid.sp, i, j, k);
        if (d < bestDistance && grid.mask.test(v))
        {
          bestDistance = d;
          best = static_cast<std::uint32_t>(v);
        }
      }
  return best;
}

} // namespace skeleton
} // namespace vtouch

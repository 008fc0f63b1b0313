// vesseltouch-distributed-seedcode: the SS code across pieces in rounds
// (vtouch::DistributedSeedCode, issue 19 item 2) on the raw-angiogram phantom's vessel tree,
// thresholded, split in 2, 4 and 8 pieces as the executive splits (ranks as threads of one
// process): rounds, voxels each rank reported, and the voxels whose SS differs from the single
// run's (must be 0). Then the free ends and junctions each rank's voxel coder places inside its
// owned box (3 voxels from its shared faces), coded from roots of its own (today's distributed
// coding) and with the global SS field (VoxelCodingParameters::globalSs_mm), against the single
// run's in the same boxes.
//
//   vesseltouch-distributed-seedcode [N=112] [ghost margin voxels=8] [segments=60]
#include "vtouchDistributedSeedCode.h"
#include "vtouchInProcessCollectives.h"
#include "vtouchPhantomGenerator.h"
#include "vtouchPieceGrid.h"
#include "vtouchSkeletonRunMeter.h"
#include "vtouchSkeletonSeedCodeStage.h"
#include "vtouchSkeletonVoxelCodes.h"
#include "vtouchSkeletonVoxelGrid.h"
#include "vtouchVoxelCoding.h"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace
{
using namespace vtouch;

double secondsSince(std::chrono::steady_clock::time_point t)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}
} // namespace

int main(int argc, char** argv)
{
  const int n = argc > 1 ? std::atoi(argv[1]) : 112;
  const int margin = argc > 2 ? std::atoi(argv[2]) : 8;
  const int segments = argc > 3 ? std::atoi(argv[3]) : 60;
  PhantomSpec spec;
  spec.shape = PhantomShape::RawAngiogram;
  spec.dimensions = { n, n, n };
  spec.angiogramSegments = segments;
  spec.clutterCount = 0;
  spec.noiseStdDev = 0.0;
  spec.biasAmplitude = 0.0;
  const PhantomGenerator generator(spec);
  if (!generator.ok() || n < 8 || margin < 1)
  {
    std::fprintf(stderr, "unusable setup: %s\n", generator.error().c_str());
    return 1;
  }
  const std::array<std::int64_t, 3> dims{ n, n, n };
  std::vector<float> voxels(static_cast<std::size_t>(n) * n * n);
  generator.fill(voxels.data());
  // Half way from the tissue to the vessels' peak: the vessels (partial volume included).
  const float threshold = static_cast<float>(0.5 * (spec.tissueIntensity + spec.peakIntensity));
  SparseVesselMask whole(dims);
  for (std::size_t v = 0; v < voxels.size(); ++v)
  {
    if (voxels[v] >= threshold)
    {
      whole.set(v);
    }
  }
  whole.finalize();
  // The root: the tree's seed (its first centerline point) snapped to the nearest vessel voxel.
  const Vec3 p0 = generator.centerline().paths.at(0).points.at(0).position_World_mm;
  const double seed[3] = { p0.x, p0.y, p0.z };
  std::array<std::int64_t, 3> root{ 0, 0, 0 };
  double best = 1e300;
  whole.forEach(
    [&](std::uint64_t lin)
    {
      const auto l = static_cast<std::int64_t>(lin);
      const std::array<std::int64_t, 3> c{
        l % n, (l / n) % n, l / (static_cast<std::int64_t>(n) * n)
      };
      double d2 = 0.0;
      for (int a = 0; a < 3; ++a)
      {
        const double p = spec.origin_mm[a] + c[a] * spec.spacing_mm[a];
        d2 += (p - seed[a]) * (p - seed[a]);
      }
      if (d2 < best)
      {
        best = d2;
        root = c;
      }
    });
  // The single run.
  auto t0 = std::chrono::steady_clock::now();
  skeleton::VoxelGrid grid(whole, spec.spacing_mm, 0.0);
  skeleton::VoxelCodes codes;
  codes.ss.assign(whole.vesselCount(), skeleton::VoxelCodes::kInf);
  codes.flags.assign(whole.vesselCount(), 0);
  const std::function<bool(double)> none;
  skeleton::RunMeter meter(none);
  skeleton::SeedCodeStage stage(grid, meter, codes, 0.0);
  stage.propagate({ static_cast<std::uint32_t>(grid.linOf(root[0], root[1], root[2])) });
  const double singleSeconds = secondsSince(t0);
  std::printf("raw angiogram phantom %d^3, %d segments, threshold %.1f: %llu vessel voxels, "
              "%zu reached from the root (%lld, %lld, %lld); single run %.3f s\n",
    n,
    segments,
    threshold,
    static_cast<unsigned long long>(whole.vesselCount()),
    codes.order.size(),
    static_cast<long long>(root[0]),
    static_cast<long long>(root[1]),
    static_cast<long long>(root[2]),
    singleSeconds);
  VoxelCodingParameters seeded;
  seeded.spacing_mm = spec.spacing_mm;
  seeded.hasSeed = true;
  seeded.seedIndex = root;
  const RawSkeleton singleSkeleton = VoxelCoder(whole, seeded).run();
  constexpr int kInset = 3;
  std::vector<std::string> topologyRows;
  std::printf(
    "| pieces | margin | rounds | voxels reported (all ranks) | per rank, max | differing "
    "| wall s (threads) |\n|---|---|---|---|---|---|---|\n");
  for (const std::array<int, 3>& counts :
    { std::array<int, 3>{ 1, 1, 2 }, std::array<int, 3>{ 1, 2, 2 }, std::array<int, 3>{ 2, 2, 2 } })
  {
    const std::vector<PieceLayout> pieces = test::layouts(dims, counts, margin);
    const int ranks = static_cast<int>(pieces.size());
    std::vector<DistributedSeedCode::Outcome> outcomes(static_cast<std::size_t>(ranks));
    std::vector<std::uint64_t> differing(static_cast<std::size_t>(ranks), 0);
    std::vector<std::array<std::pair<int, int>, 3>> topology(static_cast<std::size_t>(ranks));
    test::InProcessWorld world(ranks);
    t0 = std::chrono::steady_clock::now();
    world.run(
      [&](int r, RankCollectives& c)
      {
        const PieceLayout& l = pieces[static_cast<std::size_t>(r)];
        const SparseVesselMask mask = test::pieceMask(whole, l);
        DistributedSeedCode code(l, mask, spec.spacing_mm);
        outcomes[static_cast<std::size_t>(r)] = code.run(c, { root });
        VoxelCodingParameters own;
        own.spacing_mm = spec.spacing_mm;
        const RawSkeleton ownRoots = VoxelCoder(mask, own).run();
        VoxelCodingParameters global = own;
        global.globalSs_mm = &code.ss();
        const RawSkeleton globalField = VoxelCoder(mask, global).run();
        const VoxelBox& owned = l.owned[static_cast<std::size_t>(r)];
        topology[static_cast<std::size_t>(r)] = {
          test::endsAndJunctionsIn(singleSkeleton, { 0, 0, 0 }, owned, dims, kInset),
          test::endsAndJunctionsIn(ownRoots, l.mine().lo, owned, dims, kInset),
          test::endsAndJunctionsIn(globalField, l.mine().lo, owned, dims, kInset)
        };
        const std::array<std::int64_t, 3> d = l.pieceDims();
        mask.forEach(
          [&](std::uint64_t lin)
          {
            const auto li = static_cast<std::int64_t>(lin);
            const auto w = l.toWhole({ li % d[0], (li / d[0]) % d[1], li / (d[0] * d[1]) });
            const float expected =
              codes.ss[whole.rank(static_cast<std::uint64_t>(l.wholeLinear(w)))];
            differing[static_cast<std::size_t>(r)] += code.ssAt(lin) != expected;
          });
      });
    const double seconds = secondsSince(t0);
    std::uint64_t reported = 0, most = 0, differ = 0;
    for (int r = 0; r < ranks; ++r)
    {
      reported += outcomes[static_cast<std::size_t>(r)].reportedVoxels;
      most = std::max<std::uint64_t>(most, outcomes[static_cast<std::size_t>(r)].reportedVoxels);
      differ += differing[static_cast<std::size_t>(r)];
    }
    std::array<std::pair<int, int>, 3> sum{};
    for (const auto& t : topology)
    {
      for (std::size_t k = 0; k < 3; ++k)
      {
        sum[k].first += t[k].first;
        sum[k].second += t[k].second;
      }
    }
    char row[200];
    std::snprintf(row,
      sizeof row,
      "| %d | %d | %d / %d | %d / %d | %d / %d |",
      ranks,
      margin,
      sum[0].first,
      sum[0].second,
      sum[1].first,
      sum[1].second,
      sum[2].first,
      sum[2].second);
    topologyRows.emplace_back(row);
    std::printf("| %d | %d | %d%s | %llu | %llu | %llu | %.3f |\n",
      ranks,
      margin,
      outcomes.front().rounds,
      outcomes.front().settled ? "" : " (cap)",
      static_cast<unsigned long long>(reported),
      static_cast<unsigned long long>(most),
      static_cast<unsigned long long>(differ),
      seconds);
  }
  std::printf("\nFree ends / junctions inside the owned boxes (%d voxels from shared faces), "
              "summed over the ranks:\n| pieces | margin | single run | own roots | global SS "
              "|\n|---|---|---|---|---|\n",
    kInset);
  for (const std::string& row : topologyRows)
  {
    std::printf("%s\n", row.c_str());
  }
  return 0;
}

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
#include "vtouchDistributedBenchPhantom.h"
#include "vtouchDistributedSeedCode.h"
#include "vtouchEveryRank.h"
#include "vtouchHeldFieldDifference.h"
#include "vtouchPieceGrid.h"
#include "vtouchSeedCodeRun.h"
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

/// One rank's run: the rounds' outcome, the free ends / junctions in its owned box (single
/// run, own roots, global field) and its held voxels whose SS differs from the single run's.
struct RankRun
{
  DistributedSeedCode::Outcome outcome;
  std::array<std::pair<int, int>, 3> topology{};
  int differing = 0;
};
} // namespace

int main(int argc, char** argv)
{
  const DistributedBenchPhantom phantom(argc, argv);
  if (!phantom.ok())
  {
    std::fprintf(stderr, "unusable setup: %s\n", phantom.error().c_str());
    return 1;
  }
  const int n = phantom.n();
  const int margin = phantom.margin();
  const PhantomSpec& spec = phantom.spec();
  const std::array<std::int64_t, 3> dims = phantom.dims();
  const float threshold = phantom.threshold();
  const SparseVesselMask& whole = phantom.whole();
  // The root: the tree's seed (its first centerline point) snapped to the nearest vessel voxel.
  const Vec3 p0 = phantom.generator().centerline().paths.at(0).points.at(0).position_World_mm;
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
  test::SeedCodeRun single(whole, spec.spacing_mm);
  single.propagateFrom({ root });
  const skeleton::VoxelCodes& codes = single.codes;
  const double singleSeconds = secondsSince(t0);
  std::printf("raw angiogram phantom %d^3, %d segments, threshold %.1f: %llu vessel voxels, "
              "%zu reached from the root (%lld, %lld, %lld); single run %.3f s\n",
    n,
    phantom.segments(),
    threshold,
    static_cast<unsigned long long>(whole.vesselCount()),
    codes.order.size(),
    static_cast<long long>(root[0]),
    static_cast<long long>(root[1]),
    static_cast<long long>(root[2]),
    singleSeconds);
  const RawSkeleton singleSkeleton = test::seededSkeleton(whole, spec.spacing_mm, root);
  constexpr int kInset = 3;
  std::vector<std::string> topologyRows;
  std::printf(
    "| pieces | margin | rounds | voxels reported (all ranks) | per rank, max | differing "
    "| wall s (threads) |\n|---|---|---|---|---|---|---|\n");
  for (const std::array<int, 3>& counts : test::kSplitsIn2And4And8)
  {
    const std::vector<PieceLayout> pieces = test::layouts(dims, counts, margin);
    const int ranks = static_cast<int>(pieces.size());
    t0 = std::chrono::steady_clock::now();
    const std::vector<RankRun> runs = test::onEveryRank<RankRun>(pieces,
      [&](const PieceLayout& l, RankCollectives& c, RankRun& out)
      {
        const SparseVesselMask mask = test::pieceMask(whole, l);
        DistributedSeedCode code(l, mask, spec.spacing_mm);
        out.outcome = code.run(c, { root });
        out.topology =
          test::ownedBoxTopology(singleSkeleton, l, mask, code.ss(), spec.spacing_mm, kInset);
        out.differing =
          test::compareWithSingleRun(whole, codes.ss, l, mask, code.ss(), l.mine()).differing;
      });
    const double seconds = secondsSince(t0);
    std::uint64_t reported = 0, most = 0, differ = 0;
    std::array<std::pair<int, int>, 3> sum{};
    for (const RankRun& run : runs)
    {
      reported += run.outcome.reportedVoxels;
      most = std::max<std::uint64_t>(most, run.outcome.reportedVoxels);
      differ += static_cast<std::uint64_t>(run.differing);
      for (std::size_t k = 0; k < 3; ++k)
      {
        sum[k].first += run.topology[k].first;
        sum[k].second += run.topology[k].second;
      }
    }
    const DistributedSeedCode::Outcome& first = runs.front().outcome;
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
      first.rounds,
      first.settled ? "" : " (cap)",
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

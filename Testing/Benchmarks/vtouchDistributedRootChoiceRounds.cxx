// vesseltouch-distributed-root: the automatic root across pieces (vtouch::DistributedRootChoice,
// issue 19 item 2) on the raw-angiogram phantom's vessel tree, thresholded as
// vesseltouch-distributed-seedcode thresholds it, split in 2, 4 and 8 pieces as the executive
// splits (ranks as threads of one process): the components and final roots every rank got
// against the single run's (VoxelCoder without a seed: RawSkeleton::roots, the thickest end when
// moved, else the extremity; and the extremity and the move), the propagations and exchanges it
// took, the move's exchanges (BS code and cluster graphs) and their 64-bit values, and the held
// voxels whose SS differs from the single run's final field (must be 0).
//
//   vesseltouch-distributed-root [N=112] [ghost margin voxels=8] [segments=60]
#include "vtouchDistributedRootChoice.h"
#include "vtouchInProcessCollectives.h"
#include "vtouchPhantomGenerator.h"
#include "vtouchPieceGrid.h"
#include "vtouchSkeletonRunMeter.h"
#include "vtouchSkeletonSeedCodeStage.h"
#include "vtouchSkeletonVoxelCodes.h"
#include "vtouchSkeletonVoxelGrid.h"
#include "vtouchVoxelCoding.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <tuple>
#include <vector>

namespace
{
using namespace vtouch;
using Index = std::array<std::int64_t, 3>;

std::vector<Index> sorted(std::vector<Index> v)
{
  std::sort(v.begin(),
    v.end(),
    [](const Index& a, const Index& b)
    { return std::make_tuple(a[2], a[1], a[0]) < std::make_tuple(b[2], b[1], b[0]); });
  return v;
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
  const Index dims{ n, n, n };
  std::vector<float> voxels(static_cast<std::size_t>(n) * n * n);
  generator.fill(voxels.data());
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
  voxels = {};
  // The single run: its roots, and its SS field from them.
  VoxelCodingParameters parameters;
  parameters.spacing_mm = spec.spacing_mm;
  const RawSkeleton skeleton = VoxelCoder(whole, parameters).run();
  skeleton::VoxelGrid grid(whole, spec.spacing_mm, 0.0);
  std::vector<std::uint32_t> sources;
  int moved = 0;
  for (const RawComponentRoot& c : skeleton.roots)
  {
    moved += c.moved;
    for (const Index& v : c.moved ? std::vector<Index>{ c.thickest } : c.extremity)
    {
      sources.push_back(static_cast<std::uint32_t>(grid.linOf(v[0], v[1], v[2])));
    }
  }
  skeleton::VoxelCodes codes;
  codes.ss.assign(whole.vesselCount(), skeleton::VoxelCodes::kInf);
  codes.flags.assign(whole.vesselCount(), 0);
  const std::function<bool(double)> none;
  skeleton::RunMeter meter(none);
  skeleton::SeedCodeStage(grid, meter, codes, 0.0).propagate(sources);
  std::printf("raw angiogram phantom %d^3, %d segments, threshold %.1f: %llu vessel voxels; "
              "single run: %zu components coded, %d re-rooted at the thickest end\n",
    n,
    segments,
    threshold,
    static_cast<unsigned long long>(whole.vesselCount()),
    skeleton.roots.size(),
    moved);
  std::printf("| pieces | G | components | roots as the single run's (ranks) | on blocks | moved | "
              "propagations | exchanges | move: exchanges | move: values | BS bound mm | "
              "SS differing |\n");
  for (const std::array<int, 3>& counts :
    { std::array<int, 3>{ 1, 1, 2 }, std::array<int, 3>{ 1, 2, 2 }, std::array<int, 3>{ 2, 2, 2 } })
  {
    const std::vector<PieceLayout> pieces = test::layouts(dims, counts, margin);
    std::vector<DistributedRootChoice::Result> results(pieces.size());
    std::vector<long> differing(pieces.size(), 0);
    test::InProcessWorld world(static_cast<int>(pieces.size()));
    world.run(
      [&](int r, RankCollectives& c)
      {
        const PieceLayout& l = pieces[static_cast<std::size_t>(r)];
        const SparseVesselMask mask = test::pieceMask(whole, l);
        DistributedRootChoice::Result& out = results[static_cast<std::size_t>(r)];
        out = DistributedRootChoice::choose(l, mask, spec.spacing_mm, c, {});
        const Index d = l.pieceDims();
        mask.forEach(
          [&](std::uint64_t lin)
          {
            const auto li = static_cast<std::int64_t>(lin);
            const Index w = l.toWhole({ li % d[0], (li / d[0]) % d[1], li / (d[0] * d[1]) });
            const float expected =
              codes.ss[whole.rank(static_cast<std::uint64_t>(l.wholeLinear(w)))];
            differing[static_cast<std::size_t>(r)] +=
              !out.ok || out.ss_mm[mask.rank(lin)] != expected;
          });
      });
    int same = 0, onBlocks = 0, movedHere = 0;
    long differ = 0;
    for (std::size_t r = 0; r < results.size(); ++r)
    {
      bool equal = results[r].ok && results[r].components.size() == skeleton.roots.size();
      for (std::size_t k = 0; equal && k < skeleton.roots.size(); ++k)
      {
        const DistributedRootChoice::ComponentRoot& got = results[r].components[k];
        const RawComponentRoot& want = skeleton.roots[k];
        equal = got.extremity_Whole == sorted(want.extremity) && got.moved == want.moved &&
                got.roots_Whole ==
                  (want.moved ? std::vector<Index>{ want.thickest } : sorted(want.extremity));
        onBlocks += r == 0 && got.fromBlocks;
        movedHere += r == 0 && got.moved;
      }
      same += equal;
      differ += differing[r];
    }
    const DistributedRootChoice::Result& first = results.front();
    std::printf("| %zu | %d | %zu | %d of %zu | %d | %d | %d | %d | %d | %llu | %.2f | %ld |%s%s\n",
      pieces.size(),
      margin,
      first.components.size(),
      same,
      results.size(),
      onBlocks,
      movedHere,
      first.propagations,
      first.rounds,
      first.moveExchanges,
      static_cast<unsigned long long>(first.moveValues),
      first.boundBs_mm,
      differ,
      first.ok ? "" : " ",
      first.message.c_str());
  }
  return 0;
}

// The move of the automatic root to the thickest end across pieces (issue 19 item 2), ranks as
// threads: the BS code exact on every owned voxel of a vessel thicker than the ghost margin
// (vtouch::DistributedBoundaryCode), the cluster graph the single run's in the key order
// (vtouch::DistributedClusterGraph), and the single run's final root and field when the root moves
// to a thick trunk that crosses a piece face (vtouch::DistributedRootChoice).
#include "vtouchDistributedBoundaryCode.h"
#include "vtouchDistributedClusterGraph.h"
#include "vtouchDistributedRootChoice.h"
#include "vtouchInProcessCollectives.h"
#include "vtouchPieceGrid.h"
#include "vtouchSkeletonBoundaryCodeStage.h"
#include "vtouchSkeletonClusterStage.h"
#include "vtouchSkeletonSeedCodeStage.h"
#include "vtouchSkeletonStageTestSupport.h"
#include "vtouchSkeletonThickerEnd.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <tuple>

namespace vtouch
{
namespace
{
using skeleton::Point_mm;
using skeleton::test::Dims;
using test::InProcessWorld;
using test::layouts;
using test::pieceMask;
using Index = std::array<std::int64_t, 3>;

const std::array<std::array<int, 3>, 3> kSplits{ { { 2, 1, 1 }, { 2, 2, 1 }, { 2, 2, 2 } } };
const std::array<std::array<double, 3>, 2> kSpacings{ { { 1, 1, 1 }, { 0.9, 0.75, 1.2 } } };

/// A trunk of radius 6 voxels along x (the faces between the pieces cut across it and along its
/// axis), two long thin branches from its right end: the single run's extremity is a thin end
/// (the far end from the first voxel in scan order, the other branch's), its root moves to the
/// trunk's end.
SparseVesselMask trunkAndBranches(const Dims& d)
{
  using skeleton::test::distanceToSegment;
  return skeleton::test::makeMask(d,
    [](const Point_mm& p)
    {
      return distanceToSegment(p, { 6, 20, 22 }, { 30, 20, 22 }) <= 6.0 ||
             distanceToSegment(p, { 30, 20, 22 }, { 60, 36, 4 }) <= 1.5 ||
             distanceToSegment(p, { 26, 20, 22 }, { 60, 4, 40 }) <= 1.5;
    });
}

Index wholeOfLocal(const PieceLayout& l, std::uint64_t lin)
{
  const Dims d = l.pieceDims();
  const auto li = static_cast<std::int64_t>(lin);
  return l.toWhole({ li % d[0], (li / d[0]) % d[1], li / (d[0] * d[1]) });
}

/// The single run's stages on the whole mask: BS, SS from `root`, the clusters.
struct SingleStages
{
  SingleStages(const SparseVesselMask& m,
    const std::array<double, 3>& spacing_mm,
    const Index& root)
    : grid(m, spacing_mm, 0.0)
    , meter(none)
  {
    const std::size_t n = m.vesselCount();
    codes.bs.assign(n, skeleton::VoxelCodes::kInf);
    codes.ss.assign(n, skeleton::VoxelCodes::kInf);
    codes.flags.assign(n, 0);
    graph.label.assign(n, 0);
    skeleton::BoundaryCodeStage boundary(grid, meter, codes.bs);
    boundary.start();
    boundary.await();
    skeleton::SeedCodeStage(grid, meter, codes, 0.0)
      .propagate({ static_cast<std::uint32_t>(grid.linOf(root[0], root[1], root[2])) });
    skeleton::ClusterStage(grid, meter, codes, graph).build();
  }
  skeleton::VoxelGrid grid;
  std::function<bool(double)> none;
  skeleton::RunMeter meter;
  skeleton::VoxelCodes codes;
  skeleton::ClusterGraph graph;
};

TEST(DistributedBoundaryCode, IsTheSingleRunsOnEveryOwnedVoxelOfAVesselThickerThanTheMargin)
{
  const Dims dims{ 64, 40, 44 };
  const SparseVesselMask whole = trunkAndBranches(dims);
  for (const std::array<double, 3>& spacing_mm : kSpacings)
  {
    const SingleStages single(whole, spacing_mm, { 6, 20, 22 });
    // Owned voxels whose code on the held box alone (the bound) is not the single run's: the
    // faces along the trunk cut off its far wall; without them the test would prove nothing.
    int wrong = 0;
    for (const std::array<int, 3>& counts : kSplits)
    {
      for (int margin = 1; margin <= 3; ++margin)
      {
        SCOPED_TRACE("split " + std::to_string(counts[0]) + std::to_string(counts[1]) +
                     std::to_string(counts[2]) + ", margin " + std::to_string(margin) +
                     ", spacing x " + std::to_string(spacing_mm[0]));
        const std::vector<PieceLayout> pieces = layouts(dims, counts, margin);
        std::vector<int> differing(pieces.size(), 0), wrongOnHeldBox(pieces.size(), 0);
        std::vector<DistributedBoundaryCode::Result> results(pieces.size());
        InProcessWorld world(static_cast<int>(pieces.size()));
        world.run(
          [&](int r, RankCollectives& c)
          {
            const PieceLayout& l = pieces[static_cast<std::size_t>(r)];
            const SparseVesselMask mask = pieceMask(whole, l);
            results[static_cast<std::size_t>(r)] =
              DistributedBoundaryCode::compute(l, mask, spacing_mm, c);
            // The held box alone (the bound): wrong somewhere, or the test would prove nothing.
            const skeleton::VoxelGrid grid(mask, spacing_mm, 0.0);
            const std::function<bool(double)> none;
            skeleton::RunMeter meter(none);
            std::vector<float> held(mask.vesselCount(), skeleton::VoxelCodes::kInf);
            skeleton::BoundaryCodeStage stage(grid, meter, held);
            stage.setOrigin(l.mine().lo);
            stage.start();
            stage.await();
            mask.forEach(
              [&](std::uint64_t lin)
              {
                const Index w = wholeOfLocal(l, lin);
                if (!l.owned[static_cast<std::size_t>(r)].contains(w))
                {
                  return;
                }
                const float expected =
                  single.codes.bs[whole.rank(static_cast<std::uint64_t>(l.wholeLinear(w)))];
                differing[static_cast<std::size_t>(r)] +=
                  results[static_cast<std::size_t>(r)].bs_mm[mask.rank(lin)] != expected;
                wrongOnHeldBox[static_cast<std::size_t>(r)] += held[mask.rank(lin)] != expected;
              });
          });
        for (std::size_t r = 0; r < pieces.size(); ++r)
        {
          EXPECT_TRUE(results[r].ok) << results[r].message;
          EXPECT_EQ(differing[r], 0) << "rank " << r;
          EXPECT_GT(results[r].sentVoxels, 0U);
          wrong += wrongOnHeldBox[r];
        }
      }
    }
    EXPECT_GT(wrong, 100);
  }
}

TEST(DistributedClusterGraph, IsTheSingleRunsGraphInTheKeyOrder)
{
  const Dims dims{ 64, 40, 44 };
  const SparseVesselMask whole = trunkAndBranches(dims);
  for (const std::array<double, 3>& spacing_mm : kSpacings)
  {
    ASSERT_TRUE(whole.test(static_cast<std::uint64_t>(60 + 64 * (36 + 40 * 4))));
    const SingleStages single(whole, spacing_mm, { 60, 36, 4 });
    const std::vector<skeleton::Cluster>& expected = single.graph.clusters;
    const std::vector<std::uint32_t> position =
      skeleton::clusterKeyOrder(expected, single.codes.ss, whole);
    ASSERT_GT(expected.size(), 20U);
    for (std::size_t split = 0; split < kSplits.size(); ++split)
    {
      const std::array<int, 3>& counts = kSplits[split];
      const int margin = 1 + static_cast<int>(split); // 1, 2, 3
      SCOPED_TRACE("split " + std::to_string(counts[0]) + std::to_string(counts[1]) +
                   std::to_string(counts[2]) + ", margin " + std::to_string(margin) +
                   ", spacing x " + std::to_string(spacing_mm[0]));
      const std::vector<PieceLayout> pieces = layouts(dims, counts, margin);
      std::vector<DistributedClusterGraph::Graph> graphs(pieces.size());
      InProcessWorld world(static_cast<int>(pieces.size()));
      world.run(
        [&](int r, RankCollectives& c)
        {
          const PieceLayout& l = pieces[static_cast<std::size_t>(r)];
          const SparseVesselMask mask = pieceMask(whole, l);
          std::vector<float> ss(mask.vesselCount()), bs(mask.vesselCount());
          mask.forEach(
            [&](std::uint64_t lin)
            {
              const auto w = static_cast<std::uint64_t>(l.wholeLinear(wholeOfLocal(l, lin)));
              ss[mask.rank(lin)] = single.codes.ss[whole.rank(w)];
              bs[mask.rank(lin)] = single.codes.bs[whole.rank(w)];
            });
          graphs[static_cast<std::size_t>(r)] = DistributedClusterGraph::build(
            l, mask, spacing_mm, single.grid.inverseBandWidth, ss, bs, c);
        });
      for (std::size_t r = 0; r < graphs.size(); ++r)
      {
        SCOPED_TRACE("rank " + std::to_string(r));
        const DistributedClusterGraph::Graph& got = graphs[r];
        ASSERT_EQ(got.clusters.size(), expected.size());
        int differing = 0;
        std::string firstDiffer;
        for (std::uint32_t c = 0; c < expected.size(); ++c)
        {
          const skeleton::Cluster& e = expected[c];
          const skeleton::Cluster& g = got.clusters[position[c]];
          std::vector<std::uint32_t> lower, higher;
          for (const std::uint32_t n : e.lower)
          {
            lower.push_back(position[n]);
          }
          for (const std::uint32_t n : e.higher)
          {
            higher.push_back(position[n]);
          }
          std::sort(lower.begin(), lower.end());
          std::sort(higher.begin(), higher.end());
          const Index best = single.grid.voxelArray(e.bestVoxel);
          const Index first = single.grid.voxelArray(e.firstVoxel);
          const bool differs = g.band != e.band || g.count != e.count || g.maxBs != e.maxBs ||
                               g.indexSum[0] != e.indexSum[0] || g.indexSum[1] != e.indexSum[1] ||
                               g.indexSum[2] != e.indexSum[2] || g.lower != lower ||
                               g.higher != higher ||
                               got.bestVoxel_Whole[position[c]] != pieces[0].wholeLinear(best) ||
                               got.firstVoxel_Whole[position[c]] != pieces[0].wholeLinear(first);
          differing += differs;
          if (differs && firstDiffer.empty())
          {
            firstDiffer = "cluster " + std::to_string(c) + ": band " + std::to_string(g.band) +
                          "/" + std::to_string(e.band) + " count " + std::to_string(g.count) + "/" +
                          std::to_string(e.count) + " maxBs " + std::to_string(g.maxBs) + "/" +
                          std::to_string(e.maxBs) + " best " +
                          std::to_string(got.bestVoxel_Whole[position[c]]) + "/" +
                          std::to_string(pieces[0].wholeLinear(best)) + " lists " +
                          std::to_string(g.lower != lower) + std::to_string(g.higher != higher);
          }
        }
        EXPECT_EQ(differing, 0) << firstDiffer;
        EXPECT_EQ(skeleton::thickerEnd(got.clusters,
                    [&]
                    {
                      std::vector<std::uint32_t> identity(got.clusters.size());
                      for (std::uint32_t c = 0; c < identity.size(); ++c)
                      {
                        identity[c] = c;
                      }
                      return identity;
                    }())
                    .has_value(),
          skeleton::thickerEnd(expected, position).has_value());
      }
    }
  }
}

TEST(DistributedRootChoice, TheRootMovesToAThickTrunkAcrossAPieceFaceAsInTheSingleRun)
{
  const Dims dims{ 64, 40, 44 };
  const SparseVesselMask whole = trunkAndBranches(dims);
  for (const std::array<double, 3>& spacing_mm : kSpacings)
  {
    VoxelCodingParameters p;
    p.spacing_mm = spacing_mm;
    const RawSkeleton skeleton = VoxelCoder(whole, p).run();
    ASSERT_EQ(skeleton.roots.size(), 1U);
    ASSERT_FALSE(skeleton.roots[0].extremity.empty());
    ASSERT_TRUE(skeleton.roots[0].moved) // the test is about the move
      << skeleton.roots[0].extremity[0][0] << " " << skeleton.roots[0].extremity[0][1] << " "
      << skeleton.roots[0].extremity[0][2];
    std::vector<Index> extremity = skeleton.roots[0].extremity;
    std::sort(extremity.begin(),
      extremity.end(),
      [](const Index& a, const Index& b)
      { return std::make_tuple(a[2], a[1], a[0]) < std::make_tuple(b[2], b[1], b[0]); });
    // The single run's field from the trunk's end.
    const SingleStages single(whole, spacing_mm, skeleton.roots[0].thickest);
    for (const std::array<int, 3>& counts : kSplits)
    {
      for (int margin = 1; margin <= 3; ++margin)
      {
        SCOPED_TRACE("split " + std::to_string(counts[0]) + std::to_string(counts[1]) +
                     std::to_string(counts[2]) + ", margin " + std::to_string(margin) +
                     ", spacing x " + std::to_string(spacing_mm[0]));
        const std::vector<PieceLayout> pieces = layouts(dims, counts, margin);
        std::vector<DistributedRootChoice::Result> results(pieces.size());
        std::vector<int> differing(pieces.size(), 0);
        InProcessWorld world(static_cast<int>(pieces.size()));
        world.run(
          [&](int r, RankCollectives& c)
          {
            const PieceLayout& l = pieces[static_cast<std::size_t>(r)];
            const SparseVesselMask mask = pieceMask(whole, l);
            DistributedRootChoice::Result& out = results[static_cast<std::size_t>(r)];
            out = DistributedRootChoice::choose(l, mask, spacing_mm, c, {});
            if (!out.ok)
            {
              return;
            }
            mask.forEach(
              [&](std::uint64_t lin)
              {
                const auto w = static_cast<std::uint64_t>(l.wholeLinear(wholeOfLocal(l, lin)));
                differing[static_cast<std::size_t>(r)] +=
                  out.ss_mm[mask.rank(lin)] != single.codes.ss[whole.rank(w)];
              });
          });
        for (std::size_t r = 0; r < pieces.size(); ++r)
        {
          SCOPED_TRACE("rank " + std::to_string(r));
          ASSERT_TRUE(results[r].ok) << results[r].message;
          ASSERT_EQ(results[r].components.size(), 1U);
          const DistributedRootChoice::ComponentRoot& got = results[r].components[0];
          EXPECT_TRUE(got.moved);
          EXPECT_EQ(got.roots_Whole, std::vector<Index>{ skeleton.roots[0].thickest });
          EXPECT_EQ(got.extremity_Whole, extremity);
          EXPECT_EQ(differing[r], 0);
          EXPECT_GT(results[r].moveExchanges, 0);
        }
      }
    }
  }
}

TEST(DistributedRootChoice, APieceWithoutBackgroundGivesEveryRankTheSameMessage)
{
  // A block of vessel filling the volume's lower half: the lower piece's held box has no
  // background voxel, so no bound of its BS code (DistributedBoundaryCode); every rank stops.
  const Dims dims{ 12, 10, 24 };
  const SparseVesselMask half =
    skeleton::test::makeMask(dims, [](const Point_mm& p) { return p[2] <= 13.0; });
  const std::vector<PieceLayout> pieces = layouts(dims, { 1, 1, 2 }, 1);
  std::vector<DistributedRootChoice::Result> results(pieces.size());
  InProcessWorld world(static_cast<int>(pieces.size()));
  world.run(
    [&](int r, RankCollectives& c)
    {
      const PieceLayout& l = pieces[static_cast<std::size_t>(r)];
      results[static_cast<std::size_t>(r)] =
        DistributedRootChoice::choose(l, pieceMask(half, l), { 1, 1, 1 }, c, {});
    });
  for (const DistributedRootChoice::Result& r : results)
  {
    EXPECT_FALSE(r.ok);
    EXPECT_NE(r.message.find("rank 0's held box has no background voxel"), std::string::npos)
      << r.message;
    EXPECT_EQ(r.message, results.front().message);
    EXPECT_TRUE(r.components.empty());
  }
}

} // namespace
} // namespace vtouch

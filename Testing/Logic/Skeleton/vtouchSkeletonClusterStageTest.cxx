// Stage 3 of the voxel coder alone: clusters and their graph on a tube and a Y, the root choice.
#include "vtouchSkeletonStageTestSupport.h"

#include <gtest/gtest.h>

namespace
{
using namespace vtouch;
using namespace vtouch::skeleton;
using namespace vtouch::skeleton::test;

TEST(SkeletonClusterStage, TubeClustersPartitionTheVesselIntoBands)
{
  const SparseVesselMask mask = flatTube({ 30, 13, 13 }, 2, 27, 6, 6, 3.0);
  Pipeline run(mask);
  run.code(run.lin(2, 6, 6));
  run.cluster();
  const std::vector<Cluster>& clusters = run.graph.clusters;
  ASSERT_GE(clusters.size(), 25U);
  EXPECT_EQ(clusters[0].band, 0U);
  EXPECT_EQ(clusters[0].count, 1U); // the source voxel alone
  EXPECT_EQ(clusters[0].bestVoxel, run.lin(2, 6, 6));
  std::size_t voxels = 0;
  for (std::size_t c = 0; c < clusters.size(); ++c)
  {
    voxels += clusters[c].count;
    EXPECT_TRUE(c == 0 || !clusters[c].lower.empty()) << c; // every cluster leads to the root
    for (std::uint32_t l : clusters[c].lower)
    {
      EXPECT_LT(clusters[l].band, clusters[c].band);
    }
    EXPECT_TRUE(std::is_sorted(clusters[c].higher.begin(), clusters[c].higher.end()));
    EXPECT_FALSE(clusters[c].onBorder);
    if (clusters[c].higher.empty() && c > 0)
    {
      EXPECT_GE(clusters[c].centroid()[0], 24.0) << c; // the tips are at the far end
    }
  }
  EXPECT_EQ(voxels, mask.vesselCount());
  // Every voxel's label is a cluster of its band.
  mask.forEach(
    [&](std::uint64_t lin)
    {
      const std::uint32_t r = mask.rank(lin);
      ASSERT_TRUE(run.graph.label[r] & ClusterGraph::kLabelled);
      EXPECT_EQ(clusters[run.graph.clusterOfRank(r)].band,
        static_cast<std::uint32_t>(run.codes.ss[r] * run.grid.inverseBandWidth));
    });
}

TEST(SkeletonClusterStage, YHasTipsAtBothBranchEndsOnly)
{
  const SparseVesselMask mask = yShape();
  Pipeline run(mask);
  run.code(run.lin(20, 2, 10)); // the cap's apex of the trunk
  run.cluster();
  int left = 0, right = 0;
  for (std::size_t c = 1; c < run.graph.clusters.size(); ++c)
  {
    const Cluster& cluster = run.graph.clusters[c];
    if (!cluster.higher.empty())
    {
      continue;
    }
    const Point_mm m = cluster.centroid();
    const bool atLeft = distance(m, kYLeftEnd) <= 4.5;
    const bool atRight = distance(m, kYRightEnd) <= 4.5;
    EXPECT_TRUE(atLeft || atRight) << m[0] << ", " << m[1] << ", " << m[2];
    left += atLeft ? 1 : 0;
    right += atRight ? 1 : 0;
  }
  EXPECT_GE(left, 1);
  EXPECT_GE(right, 1);
}

TEST(SkeletonClusterStage, ThickerRootMovesTheRootToTheThickEnd)
{
  // A thin tube (radius 2) that widens into a thick one (radius 5); rooted at the thin end.
  const SparseVesselMask mask = makeMask({ 60, 15, 15 },
    [](const Point_mm& p)
    {
      const double r2 = (p[1] - 7) * (p[1] - 7) + (p[2] - 7) * (p[2] - 7);
      return (p[0] >= 2 && p[0] < 30 && r2 <= 4.0) || (p[0] >= 30 && p[0] <= 57 && r2 <= 25.0);
    });
  Pipeline run(mask);
  run.code(run.lin(2, 7, 7));
  run.cluster();
  const std::optional<std::uint32_t> root = run.clusters.thickerRoot();
  ASSERT_TRUE(root.has_value());
  std::int64_t c[3];
  run.grid.coords(*root, c);
  EXPECT_GE(c[0], 55); // at the thick end's face
  EXPECT_TRUE(mask.test(*root));

  // Rooted there already: no better root.
  run.seed.reset();
  run.seed.propagate({ *root });
  run.cluster();
  EXPECT_FALSE(run.clusters.thickerRoot().has_value());
}

TEST(SkeletonClusterStage, TipStartIsTheCentroidVoxelWhenItIsVessel)
{
  const SparseVesselMask mask = makeMask({ 9, 9, 9 }, [](const Point_mm& p) { return p[2] == 4; });
  Pipeline run(mask);
  Cluster ring;
  ring.count = 2;
  ring.sum[0] = 2.0 + 6.0;
  ring.sum[1] = 8.0;
  ring.sum[2] = 8.0;
  ring.bestVoxel = run.lin(2, 4, 4);
  EXPECT_EQ(ClusterStage::tipStart(run.grid, ring), run.lin(4, 4, 4));
  ring.sum[2] = 2.0 * 6.0; // centroid at z = 6: background
  EXPECT_EQ(ClusterStage::tipStart(run.grid, ring), run.lin(2, 4, 4));
}

} // namespace

// Stages 1-2 of the voxel coder alone: the BS and SS codes on a straight tube; the run's meter.
#include "vtouchSkeletonStageTestSupport.h"

#include <gtest/gtest.h>

#include <functional>
#include <limits>
#include <string>
#include <vector>

namespace
{
using namespace vtouch;
using namespace vtouch::skeleton;
using namespace vtouch::skeleton::test;

/// A flat-ended tube along x, voxels 2..37, radius 4.2 mm around (j, k) = (8, 8).
SparseVesselMask straightTube()
{
  return flatTube({ 40, 17, 17 }, 2, 37, 8, 8, 4.2);
}

TEST(SkeletonBoundaryCodeStage, EqualsTheBruteForceDistanceToTheBackgroundOnATube)
{
  const SparseVesselMask mask = straightTube();
  Pipeline run(mask);
  BoundaryCodeStage stage(run.grid, run.meter, run.codes.bs);
  stage.start();
  stage.await();
  // Every vessel voxel against every background voxel centre of the volume (outside the volume
  // is not background).
  std::vector<Point_mm> background;
  for (std::int64_t k = 0; k < 17; ++k)
    for (std::int64_t j = 0; j < 17; ++j)
      for (std::int64_t i = 0; i < 40; ++i)
      {
        if (!mask.test(run.grid.linOf(i, j, k)))
        {
          background.push_back({ double(i), double(j), double(k) });
        }
      }
  std::size_t checked = 0;
  mask.forEach(
    [&](std::uint64_t lin)
    {
      const Point_mm p = run.grid.centerOf(static_cast<std::uint32_t>(lin));
      double best = std::numeric_limits<double>::infinity();
      for (const Point_mm& b : background)
      {
        best = std::min(best, distance(p, b));
      }
      EXPECT_NEAR(run.codes.bs[mask.rank(lin)], best, 1e-5);
      ++checked;
    });
  EXPECT_EQ(checked, mask.vesselCount());
  // On the axis the nearest background is the voxel (3, 3) off it: 18 > 4.2^2.
  EXPECT_FLOAT_EQ(run.codes.bs[run.rank(20, 8, 8)], static_cast<float>(std::sqrt(18.0)));
  // At the flat end, the background voxel just beyond it.
  EXPECT_FLOAT_EQ(run.codes.bs[run.rank(2, 8, 8)], 1.0F);
  EXPECT_GT(stage.scratchBytes(), 0U);
}

TEST(SkeletonSeedCodeStage, IsTheGeodesicDistanceAlongTheTube)
{
  const SparseVesselMask mask = straightTube();
  Pipeline run(mask);
  run.seed.propagate({ run.lin(2, 8, 8) });
  EXPECT_EQ(run.codes.order.size(), mask.vesselCount());
  EXPECT_EQ(run.codes.order.front(), run.lin(2, 8, 8));
  EXPECT_FLOAT_EQ(run.codes.ss[run.rank(2, 8, 8)], 0.0F);
  EXPECT_FLOAT_EQ(run.codes.ss[run.rank(37, 8, 8)], 35.0F);
  // One diagonal step (1, 1, 1): sqrt(3); then straight on along x.
  EXPECT_FLOAT_EQ(run.codes.ss[run.rank(12, 9, 9)], static_cast<float>(9.0 + std::sqrt(3.0)));
  EXPECT_FLOAT_EQ(run.codes.ss[run.rank(12, 9, 8)], static_cast<float>(9.0 + std::sqrt(2.0)));
  EXPECT_GT(run.seed.peakQueue(), 0U);

  run.seed.reset();
  EXPECT_EQ(run.codes.ss[run.rank(37, 8, 8)], VoxelCodes::kInf);
  EXPECT_FALSE(run.codes.flags[run.rank(37, 8, 8)] & VoxelCodes::kDone);
}

TEST(SkeletonSeedCodeStage, ExtremityRegionIsTheCentreOfAnEndCap)
{
  const SparseVesselMask mask = straightTube();
  Pipeline run(mask);
  run.seed.propagate({ run.lin(12, 8, 8) }); // nearer the head: the tail end is the farthest
  const std::vector<std::uint32_t> root = run.seed.extremityRegion();
  ASSERT_EQ(root.size(), 1U);
  EXPECT_EQ(root.front(), run.lin(37, 8, 8));
  // Small masks: no exploration on blocks.
  EXPECT_EQ(run.seed.coarseExtremity(run.lin(12, 8, 8)), SeedCodeStage::kNoVoxel);
  EXPECT_EQ(run.seed.explorerBytes(), 0U);
}

TEST(SkeletonRunMeter, AStopFromTheCallbackThrowsAndRaisesTheStopFlag)
{
  std::vector<double> seen;
  const std::function<bool(double)> progress = [&](double f)
  {
    seen.push_back(f);
    return seen.size() < 2;
  };
  RunMeter meter(progress);
  meter.setTotalWork(4 * 0x10000);
  meter.tick(0x10000); // a check point: 1/4, go on
  EXPECT_FALSE(meter.stopRequested);
  EXPECT_THROW(meter.tick(0x10000), VoxelCodingAborted);
  EXPECT_TRUE(meter.stopRequested);
  ASSERT_EQ(seen.size(), 2U);
  EXPECT_DOUBLE_EQ(seen[0], 0.25);
  EXPECT_DOUBLE_EQ(seen[1], 0.5);
}

TEST(SkeletonRunMeter, StageTimesKeepTheirNamesThroughTheCoder)
{
  const SparseVesselMask mask = straightTube();
  VoxelCodingParameters parameters;
  parameters.minimumComponentSize = 10;
  const RawSkeleton s = VoxelCoder(mask, parameters).run();
  ASSERT_EQ(s.paths.size(), 1U);
  std::vector<std::string> names;
  for (const auto& stage : s.stageSeconds)
  {
    names.push_back(stage.first);
    EXPECT_GE(stage.second, 0.0);
  }
  // A small mask: the BS code on the caller's thread, no exploration on blocks.
  EXPECT_EQ(names,
    (std::vector<std::string>{
      "bs", "ss", "clusters", "center", "loops", "trace(all)", "coder(all)" }));
}

} // namespace

// The ray-maximum search behind the panel's "Pick seed": tiny synthetic volumes built in code.
#include "vtouchRayMaximum.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

namespace
{

/// A dims[0] x dims[1] x dims[2] volume of seeded noise in [0, 10) with one bright voxel.
struct TestVolume
{
  std::array<int, 3> dims;
  std::vector<double> values;
  TestVolume(std::array<int, 3> d, unsigned seed)
    : dims(d)
    , values(static_cast<size_t>(d[0]) * d[1] * d[2])
  {
    std::mt19937 random(seed);
    std::uniform_real_distribution<double> noise(0.0, 10.0);
    for (double& v : this->values)
    {
      v = noise(random);
    }
  }
  double& at(int i, int j, int k)
  {
    return this->values[(static_cast<size_t>(k) * this->dims[1] + j) * this->dims[0] + i];
  }
  vtouch::RayMaximum::Sampler sampler()
  {
    return [this](int i, int j, int k) { return this->at(i, j, k); };
  }
};

} // namespace

TEST(RayMaximum, FindsTheBrightVoxelOnAnAxisAlignedRay)
{
  TestVolume volume({ 20, 16, 12 }, 7);
  volume.at(5, 9, 7) = 100.0;
  const auto r = vtouch::RayMaximum::find(
    volume.dims, { 5.0, 9.0, -30.0 }, { 5.0, 9.0, 40.0 }, volume.sampler());
  ASSERT_TRUE(r.found);
  EXPECT_EQ(r.index, (std::array<int, 3>{ 5, 9, 7 }));
  EXPECT_DOUBLE_EQ(r.value, 100.0);
  EXPECT_EQ(r.visited, 12); // every voxel of the column, once
}

TEST(RayMaximum, FindsTheBrightVoxelOnAnObliqueRay)
{
  TestVolume volume({ 32, 32, 32 }, 11);
  // The ray passes through (10, 12, 14) with direction (1, 2, 3) / |.|.
  volume.at(10, 12, 14) = 50.0;
  const std::array<double, 3> start{ 10.0 - 10.0, 12.0 - 20.0, 14.0 - 30.0 };
  const std::array<double, 3> end{ 10.0 + 10.0, 12.0 + 20.0, 14.0 + 30.0 };
  const auto r = vtouch::RayMaximum::find(volume.dims, start, end, volume.sampler());
  ASSERT_TRUE(r.found);
  EXPECT_EQ(r.index, (std::array<int, 3>{ 10, 12, 14 }));
}

TEST(RayMaximum, FrontMostVoxelWinsTies)
{
  TestVolume volume({ 8, 8, 8 }, 3);
  volume.at(4, 4, 2) = 20.0;
  volume.at(4, 4, 6) = 20.0;
  const auto fromFront =
    vtouch::RayMaximum::find(volume.dims, { 4, 4, -1 }, { 4, 4, 9 }, volume.sampler());
  EXPECT_EQ(fromFront.index[2], 2);
  const auto fromBack =
    vtouch::RayMaximum::find(volume.dims, { 4, 4, 9 }, { 4, 4, -1 }, volume.sampler());
  EXPECT_EQ(fromBack.index[2], 6);
}

TEST(RayMaximum, MissesWhenTheRayPassesBesideTheVolume)
{
  TestVolume volume({ 8, 8, 8 }, 5);
  const auto r =
    vtouch::RayMaximum::find(volume.dims, { 20, 4, -5 }, { 20, 4, 15 }, volume.sampler());
  EXPECT_FALSE(r.found);
  EXPECT_EQ(r.visited, 0);
}

TEST(RayMaximum, RejectsNonFiniteEndsAndEmptyVolumes)
{
  TestVolume volume({ 8, 8, 8 }, 5);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(
    vtouch::RayMaximum::find(volume.dims, { nan, 4, 0 }, { 4, 4, 8 }, volume.sampler()).found);
  EXPECT_FALSE(
    vtouch::RayMaximum::find({ 0, 8, 8 }, { 4, 4, 0 }, { 4, 4, 8 }, volume.sampler()).found);
  EXPECT_FALSE(vtouch::RayMaximum::find(volume.dims, { 4, 4, 0 }, { 4, 4, 8 }, nullptr).found);
}

TEST(RayMaximum, ClipsTheSegmentToTheVoxelBox)
{
  double t0 = 0.0;
  double t1 = 0.0;
  ASSERT_TRUE(
    vtouch::RayMaximum::clipToVolume({ 10, 10, 10 }, { 5, 5, -10.5 }, { 5, 5, 19.5 }, t0, t1));
  EXPECT_NEAR(t0, 10.0 / 30.0, 1e-12);
  EXPECT_NEAR(t1, 20.0 / 30.0, 1e-12);
}

TEST(RayMaximum, ClipsASegmentToAWorldBoxAndRefusesMissesAndNonFiniteEnds)
{
  // The world-frame use (a click's ray against a remote volume's bounds): an oblique segment.
  double t0 = 0.0;
  double t1 = 0.0;
  ASSERT_TRUE(vtouch::RayMaximum::clipSegmentToBox(
    { 10, 20, 30 }, { 12, 22, 34 }, { 0, 11, 32 }, { 20, 31, 32 }, t0, t1));
  EXPECT_NEAR(t0, 10.0 / 20.0, 1e-12); // x enters at 10 (y = 21 inside)
  EXPECT_NEAR(t1, 11.0 / 20.0, 1e-12); // y leaves at 22
  // Parallel to an axis outside the box, a miss beside it, a NaN end, an inverted box.
  EXPECT_FALSE(vtouch::RayMaximum::clipSegmentToBox(
    { 0, 0, 0 }, { 1, 1, 1 }, { 2, 0.5, -1 }, { 2, 0.5, 5 }, t0, t1));
  EXPECT_FALSE(vtouch::RayMaximum::clipSegmentToBox(
    { 0, 0, 0 }, { 1, 1, 1 }, { -1, 3, 0.5 }, { 3, 2, 0.5 }, t0, t1));
  EXPECT_FALSE(vtouch::RayMaximum::clipSegmentToBox(
    { 0, 0, 0 }, { 1, 1, 1 }, { 0.5, 0.5, std::nan("") }, { 0.5, 0.5, 1 }, t0, t1));
  EXPECT_FALSE(vtouch::RayMaximum::clipSegmentToBox(
    { 0, 0, 0 }, { -1, 1, 1 }, { 0.5, 0.5, 0 }, { 0.5, 0.5, 1 }, t0, t1));
}

TEST(RayMaximum, ASegmentInsideOneVoxelSamplesIt)
{
  TestVolume volume({ 4, 4, 4 }, 9);
  const auto r = vtouch::RayMaximum::find(
    volume.dims, { 1.1, 2.0, 3.0 }, { 1.2, 2.0, 3.0 }, volume.sampler(), 0.0);
  ASSERT_TRUE(r.found);
  EXPECT_EQ(r.index, (std::array<int, 3>{ 1, 2, 3 }));
  EXPECT_EQ(r.visited, 1);
}

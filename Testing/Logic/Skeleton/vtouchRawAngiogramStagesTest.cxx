// The raw-angiogram stages before the voxel coder, on tiny synthetic angiograms: range
// estimation, seeded growing, depth, restricted tubularity, neck cutting, and the whole candidate
// region with its messages for bad seeds.
#include "vtouchIntensityRangeEstimator.h"
#include "vtouchRawAngiogramTestImages.h"
#include "vtouchRegionDepth.h"
#include "vtouchRestrictedTubularity.h"
#include "vtouchSeededRegionGrower.h"
#include "vtouchTubeNeckCutter.h"
#include "vtouchVesselCandidateRegion.h"

#include <gtest/gtest.h>

namespace vtouch
{
namespace
{
using test::SyntheticAngiogram;

constexpr double kContrast = 900.0; // background 100, vessel 1000: half maximum at 550

/// A tube of radius 3 along x through the middle of a 48^3 volume, noise sigma 20.
SyntheticAngiogram tubeVolume(double noise = 20.0)
{
  SyntheticAngiogram g({ 48, 48, 48 });
  g.addTube({ 4, 24, 24 }, { 43, 24, 24 }, 3.0, kContrast);
  if (noise > 0.0)
  {
    g.addNoise(noise, 7);
  }
  return g;
}

bool has(const SparseVesselMask& m, std::int64_t i, std::int64_t j, std::int64_t k)
{
  const auto& d = m.dims();
  return m.test(static_cast<std::uint64_t>(i + d[0] * (j + d[1] * k)));
}

TEST(IntensityRangeEstimator, SeedOnATubeGivesTheHalfMaximumRange)
{
  const SyntheticAngiogram g = tubeVolume();
  const IntensityRange r = IntensityRangeEstimator::fromSeed(g.view(), { 24, 25, 24 });
  ASSERT_TRUE(r.ok) << r.message;
  EXPECT_NEAR(r.background, 100.0, 10.0);
  EXPECT_NEAR(r.backgroundNoise, 20.0, 5.0);
  EXPECT_NEAR(r.vessel, 1000.0, 40.0);
  EXPECT_NEAR(r.lower, 550.0, 30.0);
  EXPECT_GE(r.upper, 1000.0); // the volume's maximum: brighter vessel is still vessel
  EXPECT_LT(r.weakLower, r.lower);
  EXPECT_GT(r.weakLower, r.background + 3.0 * r.backgroundNoise);
  EXPECT_TRUE(r.message.empty());
}

TEST(IntensityRangeEstimator, SeedBesideAThinVesselFindsItsPeak)
{
  SyntheticAngiogram g({ 40, 40, 40 });
  g.addTube({ 3, 20, 20 }, { 36, 20, 20 }, 0.8, kContrast);
  g.addNoise(10.0, 3);
  const IntensityRange r = IntensityRangeEstimator::fromSeed(g.view(), { 20, 22, 21 });
  ASSERT_TRUE(r.ok) << r.message;
  EXPECT_EQ(r.seedIndex[1], 20);
  EXPECT_EQ(r.seedIndex[2], 20);
}

TEST(IntensityRangeEstimator, SeedOnBackgroundSaysToPickAVessel)
{
  const SyntheticAngiogram g = tubeVolume();
  const IntensityRange r = IntensityRangeEstimator::fromSeed(g.view(), { 24, 8, 8 });
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.message.find("background"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("pick a point on a vessel"), std::string::npos) << r.message;
}

TEST(IntensityRangeEstimator, SeedOutsideTheVolumeSaysToPickAVessel)
{
  const SyntheticAngiogram g = tubeVolume();
  const IntensityRange r = IntensityRangeEstimator::fromSeed(g.view(), { 24, 24, 48 });
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.message.find("outside the volume"), std::string::npos) << r.message;
}

TEST(IntensityRangeEstimator, BinaryMaskKeepsItsMidpoint)
{
  SyntheticAngiogram g({ 16, 16, 16 }, 0.0);
  for (std::int64_t i = 2; i < 14; ++i)
  {
    g.at(i, 8, 8) = 1.0F;
  }
  const IntensityRange seeded = IntensityRangeEstimator::fromSeed(g.view(), { 5, 8, 8 });
  ASSERT_TRUE(seeded.ok);
  EXPECT_TRUE(seeded.binary);
  EXPECT_DOUBLE_EQ(seeded.lower, 0.5);
  EXPECT_DOUBLE_EQ(seeded.upper, 1.0);
  const IntensityRange whole = IntensityRangeEstimator::fromVolume(g.view());
  ASSERT_TRUE(whole.ok);
  EXPECT_TRUE(whole.binary);
  EXPECT_DOUBLE_EQ(whole.lower, 0.5);
  EXPECT_FALSE(IntensityRangeEstimator::fromSeed(g.view(), { 5, 2, 2 }).ok);
}

TEST(IntensityRangeEstimator, WholeVolumeWithoutSeedSplitsVesselFromBackground)
{
  const SyntheticAngiogram g = tubeVolume();
  const IntensityRange r = IntensityRangeEstimator::fromVolume(g.view());
  ASSERT_TRUE(r.ok) << r.message;
  EXPECT_GT(r.lower, 100.0 + 3.0 * 20.0);
  EXPECT_LT(r.lower, 900.0);
}

TEST(IntensityRangeEstimator, FlatOrNoiseOnlyVolumeHasNoVessel)
{
  SyntheticAngiogram flat({ 16, 16, 16 });
  const IntensityRange r = IntensityRangeEstimator::fromVolume(flat.view());
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.message.find("no vessel-like structure"), std::string::npos) << r.message;
  SyntheticAngiogram noise({ 32, 32, 32 });
  noise.addNoise(20.0, 1);
  EXPECT_FALSE(IntensityRangeEstimator::fromSeed(noise.view(), { 16, 16, 16 }).ok);
}

TEST(SeededRegionGrower, ThinVesselCrossesADimVoxelAndThickVesselIsNotThickened)
{
  SyntheticAngiogram g({ 40, 40, 40 });
  // A one-voxel line with one dim voxel (partial volume) in the middle.
  for (std::int64_t i = 3; i < 37; ++i)
  {
    g.at(i, 20, 20) = 1000.0F;
  }
  g.at(20, 20, 20) = 400.0F;
  g.addTube({ 3, 8, 8 }, { 36, 8, 8 }, 3.0, kContrast);
  IntensityRange r;
  r.ok = true;
  r.lower = 550.0;
  r.upper = 2000.0;
  r.weakLower = 300.0;
  const SparseVesselMask line = SeededRegionGrower::grow(g.view(), r, { 5, 20, 20 });
  EXPECT_TRUE(has(line, 36, 20, 20)) << "the line continues past its dim voxel";
  EXPECT_EQ(line.vesselCount(), 34u);
  // The thick tube: its partial-volume shell between weakLower and lower stays out.
  const SparseVesselMask tube = SeededRegionGrower::grow(g.view(), r, { 20, 8, 8 });
  SparseVesselMask strongOnly = SeededRegionGrower::threshold(g.view(), r);
  const SparseVesselMask tubeStrong = TubeNeckCutter::component(strongOnly, { 20, 8, 8 });
  EXPECT_LE(tube.vesselCount(), tubeStrong.vesselCount() + tubeStrong.vesselCount() / 50);
}

TEST(DimStrandPruner, NoiseVoxelPastAnEndGoesDimVesselAndGapStay)
{
  // Background 100, noise sigma 20: Rose's criterion asks a dead end for a summed contrast of
  // 5 x 20 x sqrt(n). Each line is strong (1000) from i = 3 to 20, then what follows.
  SyntheticAngiogram g({ 40, 40, 40 });
  const auto line = [&g](std::int64_t j, std::int64_t k, std::int64_t to)
  {
    for (std::int64_t i = 3; i <= to; ++i)
    {
      g.at(i, j, k) = 1000.0F;
    }
  };
  line(10, 10, 20);
  g.at(21, 10, 10) = 170.0F; // one dim ridge voxel past the end, 3.5 sigma: noise
  line(20, 10, 20);
  g.at(21, 20, 10) = 250.0F; // 7.5 sigma: detectable alone
  line(30, 10, 20);
  for (std::int64_t i = 21; i <= 24; ++i)
  {
    g.at(i, 30, 10) = 170.0F; // a dim thin vessel 4 voxels long: 4 x 70 >= 5 x 20 x 2
  }
  line(10, 30, 36);
  g.at(20, 10, 30) = 170.0F; // a dim gap: vessel on both sides
  IntensityRange r;
  r.ok = true;
  r.lower = 550.0;
  r.upper = 2000.0;
  r.weakLower = 160.0; // B + 3 S
  r.background = 100.0;
  r.backgroundNoise = 20.0;
  const SparseVesselMask noisyEnd = SeededRegionGrower::grow(g.view(), r, { 5, 10, 10 });
  EXPECT_FALSE(has(noisyEnd, 21, 10, 10));
  EXPECT_EQ(noisyEnd.vesselCount(), 18u);
  EXPECT_TRUE(has(SeededRegionGrower::grow(g.view(), r, { 5, 20, 10 }), 21, 20, 10));
  const SparseVesselMask dimVessel = SeededRegionGrower::grow(g.view(), r, { 5, 30, 10 });
  EXPECT_TRUE(has(dimVessel, 24, 30, 10));
  EXPECT_EQ(dimVessel.vesselCount(), 22u);
  const SparseVesselMask gap = SeededRegionGrower::grow(g.view(), r, { 5, 10, 30 });
  EXPECT_TRUE(has(gap, 36, 10, 30)) << "the line continues past its dim voxel";
  EXPECT_TRUE(has(gap, 20, 10, 30));
  // With no noise figure (sigma 0) every dim ridge voxel passes: nothing is cleared.
  r.backgroundNoise = 0.0;
  EXPECT_TRUE(has(SeededRegionGrower::grow(g.view(), r, { 5, 10, 10 }), 21, 10, 10));
}

TEST(RegionDepth, DepthCountsLayersToTheBorder)
{
  SparseVesselMask m({ 12, 12, 12 });
  for (std::int64_t k = 1; k < 10; ++k)
    for (std::int64_t j = 1; j < 10; ++j)
      for (std::int64_t i = 1; i < 10; ++i)
      {
        m.set(static_cast<std::uint64_t>(i + 12 * (j + 12 * k)));
      }
  m.finalize();
  const auto depth = RegionDepth::layers(m);
  EXPECT_EQ(depth[m.rank(1 + 12 * (1 + 12 * 1))], 1);
  EXPECT_EQ(depth[m.rank(5 + 12 * (5 + 12 * 5))], 5); // centre of a 9^3 cube
  EXPECT_EQ(depth[m.rank(3 + 12 * (5 + 12 * 5))], 3);
}

TEST(RestrictedTubularity, TubeScoresAbovePlateAndBlob)
{
  // Each shape alone (more than three largest scales apart).
  SyntheticAngiogram g({ 64, 64, 48 });
  g.addTube({ 4, 8, 24 }, { 60, 8, 24 }, 2.0, kContrast);
  g.addBox({ 4, 26, 4 }, { 60, 30, 44 }, kContrast); // a plate 5 voxels thick
  g.addBall({ 32, 52, 24 }, 5.0, kContrast);
  g.addNoise(20.0, 11);
  IntensityRange r;
  r.lower = 550.0;
  r.upper = 1e9;
  const SparseVesselMask region = SeededRegionGrower::threshold(g.view(), r);
  RestrictedTubularity::Parameters p;
  p.structureness = VesselCandidateRegion::Settings{}.structurenessFraction * kContrast;
  p.sigmaMaximum_mm = 5.0;
  const auto t = RestrictedTubularity::compute(g.view(), region, RegionDepth::layers(region), p);
  const auto score = [&](std::int64_t i, std::int64_t j, std::int64_t k)
  { return t.tubularity[region.rank(static_cast<std::uint64_t>(i + 64 * (j + 64 * k)))]; };
  const float core = VesselCandidateRegion::Settings{}.coreTubularity;
  EXPECT_GT(score(32, 8, 24), core) << "tube axis";
  EXPECT_LT(score(32, 28, 24), 0.1F) << "plate centre";
  EXPECT_LT(score(32, 52, 24), core) << "blob centre";
  EXPECT_GT(t.hessianVoxels, 0u);
}

TEST(RestrictedTubularity, OnlyTilesNearTheRegionAreComputed)
{
  SyntheticAngiogram g({ 128, 128, 64 });
  g.addTube({ 4, 10, 10 }, { 30, 10, 10 }, 1.5, kContrast);
  IntensityRange r;
  r.lower = 550.0;
  r.upper = 1e9;
  const SparseVesselMask region = SeededRegionGrower::threshold(g.view(), r);
  RestrictedTubularity::Parameters p;
  p.structureness = VesselCandidateRegion::Settings{}.structurenessFraction * kContrast;
  p.sigmaMaximum_mm = 1.5;
  const auto t = RestrictedTubularity::compute(g.view(), region, RegionDepth::layers(region), p);
  const std::uint64_t perScaleVolume = 128u * 128u * 64u;
  EXPECT_LT(t.hessianVoxels, perScaleVolume * t.scales_mm.size() / 10);
}

TEST(TubeNeckCutter, PlateTouchingAVesselIsCutAtItsNeck)
{
  SyntheticAngiogram g({ 64, 48, 48 });
  g.addTube({ 4, 20, 24 }, { 60, 20, 24 }, 2.5, kContrast);
  g.addBox({ 10, 23, 4 }, { 40, 27, 44 }, kContrast); // touches the tube along its side
  g.addNoise(20.0, 5);
  VesselCandidateRegion::Settings s;
  s.useSeed = true;
  s.seed = { 50, 20, 24 };
  const auto result = VesselCandidateRegion::extract(g.view(), s);
  ASSERT_TRUE(result.ok) << result.message;
  EXPECT_TRUE(has(result.mask, 6, 20, 24)) << "both ends of the vessel kept";
  EXPECT_TRUE(has(result.mask, 58, 20, 24));
  for (std::int64_t z : { 12, 16, 32, 36 })
  {
    EXPECT_FALSE(has(result.mask, 25, 25, z)) << "the plate is cut off at z = " << z;
  }
  EXPECT_TRUE(has(result.mask, 25, 20, 24)) << "the vessel runs on along the plate";
  // The plate's rims are tube-like at their own scale and may stay (Docs/CENTERLINES.md).
  EXPECT_LT(result.mask.vesselCount(), result.grownVoxels * 7 / 10);
}

TEST(VesselCandidateRegion, SeedOnAPlateSaysItIsNotAVessel)
{
  SyntheticAngiogram g({ 64, 48, 48 });
  g.addTube({ 4, 12, 24 }, { 60, 12, 24 }, 2.0, kContrast);
  g.addBox({ 10, 26, 4 }, { 50, 31, 44 }, kContrast);
  g.addNoise(20.0, 5);
  VesselCandidateRegion::Settings s;
  s.useSeed = true;
  s.seed = { 30, 28, 24 };
  const auto result = VesselCandidateRegion::extract(g.view(), s);
  EXPECT_FALSE(result.ok);
  EXPECT_EQ(result.mask.vesselCount(), 0u);
  EXPECT_NE(result.message.find("pick a point on a vessel"), std::string::npos) << result.message;
}

TEST(VesselCandidateRegion, BinaryMaskIsCodedAsDrawnAndOverrideIsUsed)
{
  SyntheticAngiogram g({ 24, 24, 24 }, 0.0);
  g.addBox({ 4, 4, 4 }, { 12, 12, 12 }, 0.0);
  for (std::int64_t i = 2; i < 22; ++i)
  {
    g.at(i, 12, 12) = 1.0F;
  }
  VesselCandidateRegion::Settings s;
  s.useSeed = true;
  s.seed = { 10, 12, 12 };
  const auto binary = VesselCandidateRegion::extract(g.view(), s);
  ASSERT_TRUE(binary.ok) << binary.message;
  EXPECT_EQ(binary.mask.vesselCount(), 20u);
  EXPECT_TRUE(binary.range.binary);
  s.automatic = false;
  s.lower = 2.0;
  s.upper = 3.0;
  const auto none = VesselCandidateRegion::extract(g.view(), s);
  EXPECT_FALSE(none.ok);
  EXPECT_FALSE(none.message.empty());
}

} // namespace
} // namespace vtouch

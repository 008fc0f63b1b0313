// vtouch::ShadingField (issue 16 item 1; Docs/CENTERLINES.md "Shading"): a raw angiogram's
// smooth multiplicative shading, fitted to the background of blocks and divided out, on volumes
// made here with a known gain.
#include "vtouchShadingField.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

namespace
{

using vtouch::ShadingField;
using vtouch::VolumeView;

constexpr std::int64_t kNx = 96, kNy = 96, kNz = 48;

/// Tissue at `tissue` with Gaussian noise, tubes of radius 2 at 1000 running along x (every 20
/// voxels in y and z, a fifth of no block's voxels), all times gain(j).
template<typename Gain>
std::vector<float> shadedVolume(Gain gain, double tissue = 300.0, std::uint32_t seed = 7)
{
  std::mt19937 random(seed);
  std::normal_distribution<double> noise(0.0, 15.0);
  std::vector<float> v(static_cast<std::size_t>(kNx * kNy * kNz));
  for (std::int64_t k = 0; k < kNz; ++k)
    for (std::int64_t j = 0; j < kNy; ++j)
      for (std::int64_t i = 0; i < kNx; ++i)
      {
        const double dj = static_cast<double>((j + 10) % 20) - 10.0;
        const double dk = static_cast<double>((k + 10) % 20) - 10.0;
        const double base = dj * dj + dk * dk <= 4.0 ? 1000.0 : tissue;
        v[static_cast<std::size_t>(i + kNx * (j + kNy * k))] =
          static_cast<float>(gain(i, j, k) * base + noise(random));
      }
  return v;
}

VolumeView<float> viewOf(const std::vector<float>& v)
{
  VolumeView<float> view;
  view.voxels = v.data();
  view.dims = { kNx, kNy, kNz };
  return view;
}

ShadingField fitted(const std::vector<float>& v)
{
  const VolumeView<float> view = viewOf(v);
  return ShadingField::fit(view.dims, 1, ShadingField::sampleOf(view, 1));
}

double median(std::vector<double> x)
{
  std::nth_element(x.begin(), x.begin() + static_cast<std::ptrdiff_t>(x.size() / 2), x.end());
  return x[x.size() / 2];
}

/// The median of the tissue voxels (off the tubes) of slab j0 <= j < j1.
double slabTissueMedian(const std::vector<float>& v, std::int64_t j0, std::int64_t j1)
{
  std::vector<double> x;
  for (std::int64_t k = 0; k < kNz; ++k)
    for (std::int64_t j = j0; j < j1; ++j)
      for (std::int64_t i = 0; i < kNx; ++i)
      {
        const double dj = static_cast<double>((j + 10) % 20) - 10.0;
        const double dk = static_cast<double>((k + 10) % 20) - 10.0;
        if (dj * dj + dk * dk > 16.0)
        {
          x.push_back(v[static_cast<std::size_t>(i + kNx * (j + kNy * k))]);
        }
      }
  return median(x);
}

} // namespace

TEST(ShadingField, RecoversAGainFallingFourfoldAlongTheVolumeAndFlattensItsBackground)
{
  // The raw CTA's kind of shading: the whole image 4 times darker at one end (j = 95).
  const auto gain = [](std::int64_t, std::int64_t j, std::int64_t)
  { return 1.6 - 1.2 * static_cast<double>(j) / static_cast<double>(kNy - 1); };
  const std::vector<float> v = shadedVolume(gain);
  ShadingField f = fitted(v);
  ASSERT_TRUE(f.active()) << f.summary();
  EXPECT_GT(f.gainRatio(), 2.5);
  f.setReference({ 48, 48, 24 });
  // The fitted gain against the true one, both relative to the reference voxel.
  double worst = 0.0;
  for (std::int64_t j = 8; j < kNy; j += 16)
  {
    for (std::int64_t i = 8; i < kNx; i += 16)
    {
      const double truth = gain(i, j, 24) / gain(48, 48, 24);
      const double got = f.gain(static_cast<double>(i), static_cast<double>(j), 24.0);
      worst = std::max(worst, std::abs(got / truth - 1.0));
    }
  }
  EXPECT_LT(worst, 0.08) << "the fitted gain's largest relative error at the blocks' centres";
  std::vector<float> corrected(v.size());
  f.correct(viewOf(v), { 0, 0, 0 }, corrected.data());
  const double reference = slabTissueMedian(corrected, 40, 56);
  EXPECT_NEAR(slabTissueMedian(corrected, 0, 16) / reference, 1.0, 0.06);
  EXPECT_NEAR(slabTissueMedian(corrected, 80, 96) / reference, 1.0, 0.06);
  // Before: the darker end at a third of the bright one's level.
  EXPECT_LT(slabTissueMedian(v, 80, 96) / slabTissueMedian(v, 0, 16), 0.4);
}

TEST(ShadingField, LeavesAVolumeWithoutShadingAsItIs)
{
  // +/- 3 % of slow texture (what the fit finds of the phantom family's bias, 1.03-1.04 between
  // its blocks' 5th and 95th percentiles): under the gate of 1.1.
  const auto gain = [](std::int64_t i, std::int64_t j, std::int64_t k)
  {
    return 1.0 + 0.03 * std::sin(0.05 * static_cast<double>(i)) *
                   std::cos(0.04 * static_cast<double>(j + k));
  };
  const std::vector<float> v = shadedVolume(gain);
  const ShadingField f = fitted(v);
  EXPECT_FALSE(f.active()) << f.summary();
  EXPECT_LT(f.gainRatio(), 1.1);
  EXPECT_NE(f.summary().find("No shading correction"), std::string::npos);
  EXPECT_EQ(f.gain(3.0, 90.0, 40.0), 1.0);
}

TEST(ShadingField, TakesNoTissueBoundaryForShading)
{
  // Air (the volume's minimum plus noise) fills the first third of the volume along i, tissue
  // the rest, unshaded: the air's blocks are another tissue, not a darker gain.
  std::vector<float> v = shadedVolume([](std::int64_t, std::int64_t, std::int64_t) { return 1.0; });
  std::mt19937 random(3);
  std::uniform_real_distribution<float> air(0.0F, 20.0F);
  for (std::int64_t k = 0; k < kNz; ++k)
    for (std::int64_t j = 0; j < kNy; ++j)
      for (std::int64_t i = 0; i < kNx / 3; ++i)
      {
        v[static_cast<std::size_t>(i + kNx * (j + kNy * k))] = air(random);
      }
  const ShadingField f = fitted(v);
  EXPECT_FALSE(f.active()) << f.summary();
}

TEST(ShadingField, LeavesAVolumeWithNegativeValuesAsItIs)
{
  // A CT in Hounsfield units: the same fourfold shading of the tissue, the volume offset to
  // -1024 (air) at its first slab. A multiplicative gain is not its shading: no field.
  const auto gain = [](std::int64_t, std::int64_t j, std::int64_t)
  { return 1.6 - 1.2 * static_cast<double>(j) / static_cast<double>(kNy - 1); };
  std::vector<float> v = shadedVolume(gain);
  for (std::size_t n = 0; n < static_cast<std::size_t>(kNx * kNy); ++n)
  {
    v[n] = -1024.0F;
  }
  const ShadingField f = fitted(v);
  EXPECT_FALSE(f.active());
  EXPECT_NE(f.summary().find("negative intensities"), std::string::npos) << f.summary();
}

TEST(ShadingField, TheSameSampleInAnyOrderGivesTheSameField)
{
  // A distributed run gathers the ranks' samples rank by rank: fit() sorts them.
  const auto gain = [](std::int64_t i, std::int64_t j, std::int64_t k)
  {
    const double u = static_cast<double>(i + j + k) / static_cast<double>(kNx + kNy + kNz);
    return 0.5 + 1.5 * u * u;
  };
  const std::vector<float> v = shadedVolume(gain);
  const VolumeView<float> view = viewOf(v);
  std::vector<ShadingField::Sample> sample = ShadingField::sampleOf(view, 3);
  const ShadingField a = ShadingField::fit(view.dims, 3, sample);
  std::shuffle(sample.begin(), sample.end(), std::mt19937(11));
  const ShadingField b = ShadingField::fit(view.dims, 3, sample);
  ASSERT_TRUE(a.active());
  EXPECT_EQ(a.gainRatio(), b.gainRatio());
  for (double p : { 0.0, 17.5, 50.0, 95.0 })
  {
    EXPECT_EQ(a.gain(p, 95.0 - p, 0.5 * p), b.gain(p, 95.0 - p, 0.5 * p));
  }
}

TEST(ShadingField, UnusableSamplesGiveNoFieldAndNoChange)
{
  const std::array<std::int64_t, 3> dims{ kNx, kNy, kNz };
  EXPECT_FALSE(ShadingField::fit(dims, 1, {}).active());
  // Every value at the minimum (padding), or not a number.
  std::vector<ShadingField::Sample> flat, nan;
  for (std::uint64_t n = 0; n < static_cast<std::uint64_t>(kNx * kNy * kNz); n += 7)
  {
    flat.push_back({ n, 0.0 });
    nan.push_back({ n, std::numeric_limits<double>::quiet_NaN() });
  }
  EXPECT_FALSE(ShadingField::fit(dims, 7, flat).active());
  EXPECT_NE(
    ShadingField::fit(dims, 7, flat).summary().find("binary mask or a single"), std::string::npos);
  EXPECT_FALSE(ShadingField::fit(dims, 7, nan).active());
  // A two-valued mask (0 and 1000 in slabs along j: a "gain" of 1000 the fit would find).
  std::vector<ShadingField::Sample> mask;
  for (std::uint64_t n = 0; n < static_cast<std::uint64_t>(kNx * kNy * kNz); n += 7)
  {
    mask.push_back({ n, (n / static_cast<std::uint64_t>(kNx)) % kNy < kNy / 2 ? 0.0 : 1000.0 });
  }
  EXPECT_FALSE(ShadingField::fit(dims, 7, mask).active());
  // A volume smaller than a block, and an empty one.
  EXPECT_FALSE(ShadingField::fit({ 4, 4, 4 }, 1, { { 0, 5.0 }, { 1, 6.0 } }).active());
  EXPECT_FALSE(ShadingField::fit({ 0, 0, 0 }, 1, { { 0, 5.0 } }).active());
  // An inactive field's correction copies the voxels.
  const ShadingField none = ShadingField::fit(dims, 1, {});
  const std::vector<float> in{ 1.0F, 2.5F, 300.0F, -4.0F };
  VolumeView<float> view;
  view.voxels = in.data();
  view.dims = { 4, 1, 1 };
  std::vector<float> out(4);
  none.correct(view, { 0, 0, 0 }, out.data());
  EXPECT_EQ(in, out);
}

TEST(ShadingField, AnIntegerVolumeIsRoundedAndClampedToItsType)
{
  // Unsigned char, 4 times darker at one end (with a plate at 250 every 24 voxels along i): the
  // dark end is raised, values are rounded and stay within 0..255.
  std::vector<std::uint8_t> v(static_cast<std::size_t>(kNx * kNy * kNz));
  std::mt19937 random(5);
  std::normal_distribution<double> noise(0.0, 3.0);
  for (std::int64_t k = 0; k < kNz; ++k)
    for (std::int64_t j = 0; j < kNy; ++j)
      for (std::int64_t i = 0; i < kNx; ++i)
      {
        const double g = 1.0 - 0.75 * static_cast<double>(j) / static_cast<double>(kNy - 1);
        const double x = g * ((i % 24 == 0) ? 250.0 : 60.0) + noise(random);
        v[static_cast<std::size_t>(i + kNx * (j + kNy * k))] =
          static_cast<std::uint8_t>(std::clamp(std::round(x), 0.0, 255.0));
      }
  VolumeView<std::uint8_t> view;
  view.voxels = v.data();
  view.dims = { kNx, kNy, kNz };
  ShadingField f = ShadingField::fit(view.dims, 1, ShadingField::sampleOf(view, 1));
  ASSERT_TRUE(f.active()) << f.summary();
  f.setReference({ 48, 0, 24 }); // the bright end: the dark end is raised up to 4 times
  std::vector<std::uint8_t> out(v.size());
  f.correct(view, { 0, 0, 0 }, out.data());
  // Row j = 88, at the last blocks' centres (the gain is not extrapolated past them): 0.31 of
  // the reference's.
  constexpr std::int64_t kDark = 88;
  std::vector<double> darkEnd;
  for (std::int64_t k = 0; k < kNz; ++k)
    for (std::int64_t i = 1; i < kNx; ++i)
    {
      if (i % 24 != 0)
      {
        darkEnd.push_back(out[static_cast<std::size_t>(i + kNx * (kDark + kNy * k))]);
      }
    }
  EXPECT_NEAR(median(darkEnd), 60.0, 6.0);
  // The plates at the dark end (about 76 before) come out near 250; none wraps around past 255.
  int wrapped = 0;
  for (std::int64_t k = 0; k < kNz; ++k)
  {
    const std::uint8_t x = out[static_cast<std::size_t>(24 + kNx * (kDark + kNy * k))];
    wrapped += x < 200 ? 1 : 0;
  }
  EXPECT_EQ(wrapped, 0);
  // At the reference end the plates stay as they were (250 +/- noise, clamped at 255).
  EXPECT_NEAR(
    static_cast<double>(out[static_cast<std::size_t>(24 + kNx * (0 + kNy * 24))]), 250.0, 12.0);
}

// The extent arithmetic behind a reader's re-read of a grown piece (issue 19): the boxes still
// to read plus the overlap tile the new extent exactly once, and voxels copied between two
// layouts land on the same (i, j, k).
#include "vtouchExtentReuse.h"

#include "vtouchTestExtents.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <vector>

using vtouch::VoxelExtent;
using vtouch::test::box;

namespace
{
/// A voxel's value: its index in a 32^3 volume, so every copy can be checked by position.
std::uint32_t code(std::size_t i, std::size_t j, std::size_t k)
{
  return static_cast<std::uint32_t>((k * 32 + j) * 32 + i);
}

std::vector<std::uint32_t> filled(const VoxelExtent& e)
{
  std::vector<std::uint32_t> v;
  for (std::size_t k = e.first[2]; k <= e.last[2]; ++k)
    for (std::size_t j = e.first[1]; j <= e.last[1]; ++j)
      for (std::size_t i = e.first[0]; i <= e.last[0]; ++i)
        v.push_back(code(i, j, k));
  return v;
}

VoxelExtent randomBox(std::mt19937& rng)
{
  std::uniform_int_distribution<std::size_t> at(0, 31);
  VoxelExtent e;
  for (int a = 0; a < 3; ++a)
  {
    std::size_t x = at(rng), y = at(rng);
    e.first[a] = std::min(x, y);
    e.last[a] = std::max(x, y);
  }
  return e;
}
} // namespace

TEST(ExtentReuse, GrownPieceLeavesOnlyTheGhostSlabsToRead)
{
  // A rank's piece z 0..15 of 32^3, then the same piece grown by 6 ghost planes: one slab to read.
  const VoxelExtent piece = box(0, 31, 0, 31, 0, 15);
  const VoxelExtent grown = box(0, 31, 0, 31, 0, 21);
  const std::vector<VoxelExtent> rest = vtouch::extentDifference(grown, piece);
  ASSERT_EQ(rest.size(), 1u);
  EXPECT_EQ(rest[0].first[2], 16u);
  EXPECT_EQ(rest[0].last[2], 21u);
  EXPECT_EQ(rest[0].voxelCount(), 32u * 32u * 6u);
  // A 4-rank piece grown on two faces (y and z): two boxes.
  EXPECT_EQ(vtouch::extentDifference(box(0, 31, 0, 21, 0, 21), box(0, 31, 0, 15, 0, 15)).size(),
    2u);
  // Covered already: nothing to read. Apart: all of it.
  EXPECT_TRUE(vtouch::extentDifference(piece, grown).empty());
  const std::vector<VoxelExtent> apart =
    vtouch::extentDifference(box(0, 3, 0, 3, 0, 3), box(10, 12, 10, 12, 10, 12));
  ASSERT_EQ(apart.size(), 1u);
  EXPECT_EQ(apart[0].voxelCount(), 64u);
}

TEST(ExtentReuse, DifferenceAndOverlapTileTheWantedExtentExactlyOnce)
{
  std::mt19937 rng(7);
  for (int trial = 0; trial < 500; ++trial)
  {
    const VoxelExtent wanted = randomBox(rng);
    const VoxelExtent have = randomBox(rng);
    std::vector<int> hits(32 * 32 * 32, 0);
    auto mark = [&](const VoxelExtent& e)
    {
      for (std::size_t k = e.first[2]; k <= e.last[2]; ++k)
        for (std::size_t j = e.first[1]; j <= e.last[1]; ++j)
          for (std::size_t i = e.first[0]; i <= e.last[0]; ++i)
            ++hits[code(i, j, k)];
    };
    const std::vector<VoxelExtent> rest = vtouch::extentDifference(wanted, have);
    ASSERT_LE(rest.size(), 6u);
    for (const VoxelExtent& e : rest)
    {
      ASSERT_TRUE(vtouch::extentContains(wanted, e));
      ASSERT_FALSE(vtouch::intersectExtents(e, have).has_value()) << "a box to read overlaps";
      mark(e);
    }
    if (const auto both = vtouch::intersectExtents(wanted, have))
    {
      mark(*both);
    }
    for (std::size_t k = 0; k < 32; ++k)
      for (std::size_t j = 0; j < 32; ++j)
        for (std::size_t i = 0; i < 32; ++i)
        {
          const bool inside = i >= wanted.first[0] && i <= wanted.last[0] &&
            j >= wanted.first[1] && j <= wanted.last[1] && k >= wanted.first[2] &&
            k <= wanted.last[2];
          ASSERT_EQ(hits[code(i, j, k)], inside ? 1 : 0) << "voxel " << i << " " << j << " " << k;
        }
  }
}

TEST(ExtentReuse, CopiedVoxelsKeepTheirPosition)
{
  std::mt19937 rng(11);
  for (int trial = 0; trial < 200; ++trial)
  {
    const VoxelExtent from = randomBox(rng);
    const VoxelExtent to = randomBox(rng);
    const auto both = vtouch::intersectExtents(from, to);
    if (!both)
    {
      continue;
    }
    const std::vector<std::uint32_t> source = filled(from);
    std::vector<std::uint32_t> target(to.voxelCount(), 0xFFFFFFFFu);
    vtouch::copyExtentVoxels(
      source.data(), from, target.data(), to, *both, sizeof(std::uint32_t));
    std::size_t n = 0;
    for (std::size_t k = to.first[2]; k <= to.last[2]; ++k)
      for (std::size_t j = to.first[1]; j <= to.last[1]; ++j)
        for (std::size_t i = to.first[0]; i <= to.last[0]; ++i, ++n)
        {
          const bool copied = vtouch::extentContains(*both, box(i, i, j, j, k, k));
          ASSERT_EQ(target[n], copied ? code(i, j, k) : 0xFFFFFFFFu);
        }
  }
}

TEST(ExtentReuse, ABoxOutsideEitherExtentIsRefused)
{
  std::vector<std::uint8_t> a(8), b(8);
  EXPECT_THROW(vtouch::copyExtentVoxels(a.data(), box(0, 1, 0, 1, 0, 1), b.data(),
                 box(0, 1, 0, 1, 0, 1), box(0, 2, 0, 1, 0, 1), 1),
    vtouch::VolumeIOError);
}

// The distributed tests' shared helpers (vtouchDistributedTestScenes.h, vtouchSeedCodeRun.h,
// vtouchHeldFieldDifference.h, vtouchEveryRank.h) on cases with known answers: the tests that use
// them would pass vacuously if a capsule made no voxels, a comparison found no difference, or a
// rank got another rank's layout.
#include "vtouchDistributedTestScenes.h"
#include "vtouchEveryRank.h"
#include "vtouchHeldFieldDifference.h"
#include "vtouchPieceGrid.h"
#include "vtouchSeedCodeRun.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>

namespace vtouch
{
namespace
{

TEST(DistributedTestScenes, ABallAndACapsuleHaveTheirVoxels)
{
  // A ball of radius 1.2 voxels: its centre and 6 face neighbours (the edge ones are 1.41 away).
  EXPECT_EQ(
    test::capsuleMask({ 5, 5, 5 }, { { { 2, 2, 2 }, { 2, 2, 2 }, 1.2 } }).vesselCount(), 7U);
  // A capsule of radius 0.5 along x from 1 to 6: its 6 axis voxels.
  EXPECT_EQ(
    test::capsuleMask({ 8, 3, 3 }, { { { 1, 1, 1 }, { 6, 1, 1 }, 0.5 } }).vesselCount(), 6U);
}

TEST(DistributedTestScenes, RandomTreesAreSeededAndTheirVoxelIsAVesselVoxel)
{
  const test::Dims dims{ 44, 40, 48 };
  const SparseVesselMask a = test::randomTree(dims, 7), b = test::randomTree(dims, 7);
  EXPECT_EQ(a.vesselCount(), b.vesselCount());
  EXPECT_GT(a.vesselCount(), 100U); // a trunk at least, not the lone ball
  EXPECT_NE(test::randomTree(dims, 8).vesselCount(), a.vesselCount());
  std::mt19937 random(1);
  const test::VoxelIndex v = test::randomVesselVoxel(a, random);
  EXPECT_TRUE(a.test(static_cast<std::uint64_t>(v[0] + dims[0] * (v[1] + dims[1] * v[2]))));
  EXPECT_THROW(
    test::randomVesselVoxel(SparseVesselMask({ 2, 2, 2 }), random), std::invalid_argument);
}

TEST(HeldFieldDifference, CountsTheVoxelsThatDifferInTheBoxAndNamesTheFirst)
{
  const test::Dims dims{ 30, 6, 6 };
  const SparseVesselMask whole = test::capsuleMask(dims, { { { 1, 3, 3 }, { 28, 3, 3 }, 1.0 } });
  const std::vector<float> single = test::singleRunField(whole, { 1, 1, 1 }, { { 1, 3, 3 } });
  EXPECT_EQ(test::SeedCodeRun(whole, { 1, 1, 1 }).propagateFrom({ { 1, 3, 3 } }), single);
  const PieceLayout l = test::layouts(dims, { 2, 1, 1 }, 2)[1]; // x from 12 (held)
  const SparseVesselMask piece = test::pieceMask(whole, l);
  // The piece's field taken from the single run's: nothing differs, every voxel reached.
  std::vector<float> field(piece.vesselCount());
  const test::Dims d = l.pieceDims();
  piece.forEach(
    [&](std::uint64_t lin)
    {
      const auto li = static_cast<std::int64_t>(lin);
      const auto w = l.toWhole({ li % d[0], (li / d[0]) % d[1], li / (d[0] * d[1]) });
      field[piece.rank(lin)] = single[whole.rank(static_cast<std::uint64_t>(l.wholeLinear(w)))];
    });
  test::HeldFieldDifference same =
    test::compareWithSingleRun(whole, single, l, piece, field, l.mine());
  EXPECT_EQ(same.differing, 0);
  EXPECT_EQ(same.reached, static_cast<int>(piece.vesselCount()));
  // The axis voxel (20, 3, 3) changed: one differs, named; outside a box without it, none.
  const auto q = l.toLocal({ 20, 3, 3 });
  field[piece.rank(static_cast<std::uint64_t>(q[0] + d[0] * (q[1] + d[1] * q[2])))] += 1.0F;
  const test::HeldFieldDifference one =
    test::compareWithSingleRun(whole, single, l, piece, field, l.mine());
  EXPECT_EQ(one.differing, 1);
  EXPECT_EQ(one.firstDiffer.rfind("(20,3,3): ", 0), 0U) << one.firstDiffer;
  VoxelBox left = l.mine();
  left.hi[0] = 19;
  EXPECT_EQ(test::compareWithSingleRun(whole, single, l, piece, field, left).differing, 0);
  EXPECT_THROW(
    test::compareWithSingleRun(whole, single, l, piece, { 1.0F }, l.mine()), std::invalid_argument);
}

TEST(EveryRank, EachRankGetsItsLayoutAndItsOwnResult)
{
  const std::vector<PieceLayout> pieces = test::layouts({ 10, 10, 10 }, { 2, 2, 1 }, 1);
  const std::vector<std::string> seen = test::onEveryRank<std::string>(pieces,
    [](const PieceLayout& l, RankCollectives& c, std::string& out)
    {
      out =
        std::to_string(l.rank) + "/" + std::to_string(c.rank()) + "/" + std::to_string(c.ranks());
    });
  ASSERT_EQ(seen.size(), 4U);
  for (int r = 0; r < 4; ++r)
  {
    EXPECT_EQ(
      seen[static_cast<std::size_t>(r)], std::to_string(r) + "/" + std::to_string(r) + "/4");
  }
  EXPECT_THROW(test::onEveryRank<int>(pieces,
                 [](const PieceLayout& l, RankCollectives&, int&)
                 {
                   if (l.rank == 2)
                   {
                     throw std::runtime_error("rank 2");
                   }
                 }),
    std::runtime_error);
}

} // namespace
} // namespace vtouch

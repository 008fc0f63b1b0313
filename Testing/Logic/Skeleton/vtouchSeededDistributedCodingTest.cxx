// The seeded modes' global SS code for the coder (vtouch::SeededDistributedCoding, issue 19 item
// 2), ranks as threads (InProcessWorld, no MPI): every rank gets the single run's field from the
// single run's root; a rank whose run stopped before its coder joins and nobody waits; every
// failure is a verdict every rank reaches together; the coder's hook in VoxelCodingSkeletonFilter.
#include "vtouchSeededDistributedCoding.h"
#include "vtouchSeedVoxel.h"
#include "vtouchSinglePointPaths.h"

#include "vtouchEveryRank.h"
#include "vtouchHeldFieldDifference.h"
#include "vtouchPieceGrid.h"
#include "vtouchSeedCodeRun.h"
#include "vtouchSkeletonStageTestSupport.h"
#include "vtouchVoxelCodingSkeletonFilter.h"

#include <itkImage.h>

#include <gtest/gtest.h>

#include <string>

namespace vtouch
{
namespace
{
using test::layouts;
using test::onEveryRank;
using test::pieceMask;

const std::array<double, 3> kSpacing_mm{ 1.0, 1.0, 1.0 };

/// The single run's SS field from `root` on the whole mask (VoxelCoder's propagation).
std::vector<float> singleRun(const SparseVesselMask& mask, const std::array<std::int64_t, 3>& root)
{
  return test::singleRunField(mask, kSpacing_mm, { root });
}

/// What a rank's coding gave: its rounds and the voxels whose field differs from the single
/// run's (-1: the rank did not code).
struct RankField
{
  int rounds = 0;
  int wrong = -1;
};

/// The Y of the stage tests in a volume twice as deep (z 0..39, the Y at z = 10).
SparseVesselMask deepY()
{
  return skeleton::test::makeMask({ 40, 40, 40 },
    [](const skeleton::Point_mm& p) { return skeleton::test::distanceToY(p) <= 3.0; });
}

TEST(SeededDistributedCoding, EveryRankGetsTheSingleRunsFieldFromASeedOffTheVessel)
{
  const SparseVesselMask whole = skeleton::test::yShape();
  // One voxel off the trunk's surface (radius 3 around x = 20): the single run's rule moves it
  // onto the nearest vessel voxel of its block, (23, 10, 10).
  const std::array<std::int64_t, 3> seed{ 24, 10, 10 };
  const std::array<std::int64_t, 3> root{ 23, 10, 10 };
  ASSERT_EQ(nearestVesselVoxel(whole, seed), root);
  const std::vector<float> single = singleRun(whole, root);
  for (const std::array<int, 3>& counts :
    { std::array<int, 3>{ 2, 1, 1 }, std::array<int, 3>{ 2, 2, 1 }, std::array<int, 3>{ 1, 4, 1 } })
  {
    const std::vector<RankField> ranks = onEveryRank<RankField>(layouts(whole.dims(), counts, 2),
      [&](const PieceLayout& l, RankCollectives& c, RankField& out)
      {
        SparseVesselMask mask = pieceMask(whole, l);
        SeededDistributedCoding coding(c, l, kSpacing_mm, true, seed, {});
        const std::vector<float> field = coding.code(mask);
        out.rounds = coding.report().rounds;
        out.wrong = test::compareWithSingleRun(whole, single, l, mask, field, l.mine()).differing;
        EXPECT_EQ(coding.report().root_Whole, root);
        EXPECT_TRUE(coding.joined());
      });
    for (std::size_t r = 0; r < ranks.size(); ++r)
    {
      EXPECT_EQ(ranks[r].wrong, 0) << "rank " << r << " of " << ranks.size();
      EXPECT_EQ(ranks[r].rounds, ranks[0].rounds);
    }
    EXPECT_GE(ranks[0].rounds, 2) << "the field crosses a face: at least one relay";
  }
}

TEST(SeededDistributedCoding, ARankWhoseRunStoppedBeforeItsCoderJoinsAndNobodyWaits)
{
  // Split in z at 20 with the Y at z = 10: the upper piece (z >= 17 held) has no vessel voxel,
  // as a piece whose threshold mask is empty (its coder never runs: it joins afterwards).
  const SparseVesselMask whole = deepY();
  const std::array<std::int64_t, 3> seed{ 20, 10, 10 };
  const std::vector<float> single = singleRun(whole, seed);
  const std::vector<RankField> ranks = onEveryRank<RankField>(layouts(whole.dims(), { 2, 1, 2 }, 3),
    [&](const PieceLayout& l, RankCollectives& c, RankField& out)
    {
      SparseVesselMask mask = pieceMask(whole, l);
      SeededDistributedCoding coding(c, l, kSpacing_mm, true, seed, {});
      if (mask.vesselCount() == 0)
      {
        coding.join();
        EXPECT_TRUE(coding.joined());
        return;
      }
      const std::vector<float> field = coding.code(mask);
      out.wrong = test::compareWithSingleRun(whole, single, l, mask, field, l.mine()).differing;
    });
  ASSERT_EQ(ranks.size(), 4U);
  EXPECT_EQ(ranks[0].wrong, 0);
  EXPECT_EQ(ranks[1].wrong, 0);
  EXPECT_EQ(ranks[2].wrong, -1) << "the upper pieces hold no vessel";
  EXPECT_EQ(ranks[3].wrong, -1);
}

TEST(SeededDistributedCoding, EveryFailureIsOneVerdictOnEveryRank)
{
  const SparseVesselMask whole = skeleton::test::yShape();
  const std::vector<PieceLayout> pieces = layouts(whole.dims(), { 2, 2, 1 }, 2);
  const auto run = [&](const std::array<std::int64_t, 3>& seed, int noPieceRank)
  {
    // Each rank's error message ("" none).
    return onEveryRank<std::string>(pieces,
      [&](const PieceLayout& layout, RankCollectives& c, std::string& message)
      {
        const int r = layout.rank;
        PieceLayout l = layout;
        if (noPieceRank >= 0)
        {
          l.held[static_cast<std::size_t>(noPieceRank)] = VoxelBox{}; // that rank read nothing
        }
        SeededDistributedCoding coding(c, l, kSpacing_mm, true, seed, {});
        try
        {
          if (r == noPieceRank)
          {
            coding.join();
          }
          else
          {
            SparseVesselMask mask = pieceMask(whole, pieces[static_cast<std::size_t>(r)]);
            coding.code(mask);
          }
        }
        catch (const SeededDistributedCodingError& e)
        {
          message = e.what();
        }
      });
  };
  // A seed two voxels off the vessels (no vessel voxel in its block).
  std::vector<std::string> m = run({ 5, 5, 10 }, -1);
  for (const std::string& text : m)
  {
    EXPECT_NE(text.find("is not inside any vessel"), std::string::npos) << text;
    EXPECT_EQ(text, m[0]);
  }
  // A seed outside the volume.
  m = run({ 20, 10, 25 }, -1);
  for (const std::string& text : m)
  {
    EXPECT_NE(text.find("outside the volume"), std::string::npos) << text;
  }
  // Rank 2 holds no piece: every rank stops before the rounds and names it.
  m = run({ 20, 10, 10 }, 2);
  for (const std::string& text : m)
  {
    EXPECT_NE(text.find("rank 2 does not hold"), std::string::npos) << text;
  }
}

TEST(SeededDistributedCoding, TheRawModesOuterLayerIsClearedAndTheSeedsRankAloneProposesTheRoot)
{
  // As the raw seeded mode: only rank 1 knows the seed (the region's seed voxel), which rank 0
  // owns; the masks lose their outer layer on shared faces; every rank's field equals the single
  // run's on its evaluable box.
  const SparseVesselMask whole = skeleton::test::yShape();
  const std::array<std::int64_t, 3> seed{ 20, 18, 10 }; // owned by rank 0 (y < 19), held by 1
  const std::vector<float> single = singleRun(whole, seed);
  const std::vector<PieceLayout> pieces = layouts(whole.dims(), { 1, 2, 1 }, 3);
  ASSERT_EQ(pieces[0].ownerOf(seed), 0);
  ASSERT_TRUE(pieces[1].mine().contains(seed));
  struct Cleared
  {
    std::uint64_t voxels = 0;
    int wrong = -1;
  };
  const std::vector<Cleared> ranks = onEveryRank<Cleared>(pieces,
    [&](const PieceLayout& l, RankCollectives& c, Cleared& out)
    {
      const int r = l.rank;
      SparseVesselMask mask = pieceMask(whole, l);
      SeededDistributedCoding::Settings s;
      s.clearOuterLayer = true;
      SeededDistributedCoding coding(c, l, kSpacing_mm, r == 1, seed, s);
      const std::vector<float> field = coding.code(mask);
      EXPECT_EQ(field.size(), mask.vesselCount()) << "indexed by the mask as left";
      out.voxels = coding.report().clearedVoxels;
      out.wrong =
        test::compareWithSingleRun(whole, single, l, mask, field, l.evaluable(r)).differing;
      EXPECT_EQ(coding.report().root_Whole, seed);
    });
  EXPECT_GT(ranks[0].voxels, 0U) << "the trunk crosses rank 0's outer layer";
  EXPECT_GT(ranks[1].voxels, 0U);
  EXPECT_EQ(ranks[0].wrong, 0);
  EXPECT_EQ(ranks[1].wrong, 0);
}

TEST(SeededDistributedCoding, JoiningTwiceIsRefused)
{
  const SparseVesselMask whole = skeleton::test::yShape();
  onEveryRank<int>(layouts(whole.dims(), { 1, 1, 1 }, 0),
    [&](const PieceLayout& l, RankCollectives& c, int&)
    {
      SparseVesselMask mask = whole;
      SeededDistributedCoding coding(c, l, kSpacing_mm, true, { 20, 10, 10 }, {});
      coding.code(mask);
      EXPECT_THROW(coding.join(), std::logic_error);
    });
}

TEST(SinglePointPaths, OneVoxelPathsGoAndWhatHungOnThemHangsWhereTheyHung)
{
  // Path 0 the parent (x = 0..4, y = 0); path 1 one voxel attached to path 0 (junction 0) that
  // path 2 hangs on by its tail (junction 1); path 3 one free voxel at (9, 9, 0) that path 4
  // hangs on by its head (junction 2).
  RawSkeleton s;
  const auto path = [](int voxels, int y, int head, int tail)
  {
    RawSkeletonPath p;
    for (int i = 0; i < voxels; ++i)
    {
      p.voxels.push_back({ i, y, 0 });
      p.center_mm.push_back({ static_cast<double>(i), static_cast<double>(y), 0.0 });
      p.radius_mm.push_back(1.0);
    }
    p.headJunction = head;
    p.tailJunction = tail;
    return p;
  };
  RawSkeletonPath free = path(1, 0, -1, -1);
  free.voxels[0] = { 9, 9, 0 };
  s.paths = { path(5, 0, -1, -1), path(1, 1, 0, -1), path(2, 2, -1, 1), free, path(3, 8, 2, -1) };
  s.junctions = { { 1, false, 0, 2 }, { 2, true, 1, 0 }, { 4, false, 3, 0 } };
  EXPECT_EQ(dropSinglePointPaths(s), 2);
  ASSERT_EQ(s.paths.size(), 3U);
  ASSERT_EQ(s.junctions.size(), 1U);
  // The old path 2 now hangs on path 0 at point 2, where the dropped path 1 hung.
  EXPECT_EQ(s.paths[1].voxels.size(), 2U);
  EXPECT_EQ(s.paths[1].tailJunction, 0);
  EXPECT_EQ(s.junctions[0].childPath, 1);
  EXPECT_TRUE(s.junctions[0].childTail);
  EXPECT_EQ(s.junctions[0].parentPath, 0);
  EXPECT_EQ(s.junctions[0].parentPoint, 2);
  // The old path 4 ends free on the dropped free voxel (prepended to its head).
  EXPECT_EQ(s.paths[2].headJunction, -1);
  ASSERT_EQ(s.paths[2].voxels.size(), 4U);
  EXPECT_EQ(s.paths[2].voxels.front(), (std::array<std::int64_t, 3>{ 9, 9, 0 }));
  EXPECT_EQ(s.paths[2].radius_mm.size(), 4U);
  EXPECT_EQ(dropSinglePointPaths(s), 0);
}

using ByteImage = itk::Image<unsigned char, 3>;

ByteImage::Pointer imageOf(const SparseVesselMask& mask)
{
  auto image = ByteImage::New();
  ByteImage::SizeType size;
  for (int a = 0; a < 3; ++a)
  {
    size[a] = static_cast<itk::SizeValueType>(mask.dims()[a]);
  }
  image->SetRegions(ByteImage::RegionType(size));
  image->Allocate(true);
  mask.forEach([&](std::uint64_t lin) { image->GetBufferPointer()[lin] = 1; });
  return image;
}

TEST(VoxelCodingSkeletonFilterGlobalSeedCode, TheHookGetsTheFinalMaskOnceAndItsFieldIsCoded)
{
  const SparseVesselMask whole = skeleton::test::yShape();
  // The single run from the seed.
  using Filter = VoxelCodingSkeletonFilter<ByteImage>;
  auto seeded = Filter::New();
  seeded->SetInput(imageOf(whole));
  Filter::PointType p;
  p[0] = 20;
  p[1] = 10;
  p[2] = 10;
  seeded->SetSeedPoint(p);
  seeded->Update();
  // The hook: the single run's field on the mask it is given.
  auto hooked = Filter::New();
  hooked->SetInput(imageOf(whole));
  int calls = 0;
  hooked->SetGlobalSeedCode(
    [&](SparseVesselMask& mask)
    {
      ++calls;
      EXPECT_EQ(mask.vesselCount(), whole.vesselCount());
      return singleRun(mask, { 20, 10, 10 });
    });
  hooked->Update();
  EXPECT_EQ(calls, 1);
  EXPECT_EQ(hooked->GetEffectiveDownsampleFactor(), 1U);
  EXPECT_EQ(hooked->GetSkeleton().paths.size(), seeded->GetSkeleton().paths.size());
  EXPECT_EQ(hooked->GetSkeleton().junctions.size(), seeded->GetSkeleton().junctions.size());
  // A failing hook (a verdict of the rounds) is the filter's exception, with its message.
  auto failing = Filter::New();
  failing->SetInput(imageOf(whole));
  failing->SetGlobalSeedCode([](SparseVesselMask&) -> std::vector<float>
    { throw SeededDistributedCodingError("the verdict"); });
  try
  {
    failing->Update();
    FAIL() << "no exception";
  }
  catch (const itk::ExceptionObject& e)
  {
    EXPECT_NE(std::string(e.GetDescription()).find("the verdict"), std::string::npos);
  }
}

} // namespace
} // namespace vtouch

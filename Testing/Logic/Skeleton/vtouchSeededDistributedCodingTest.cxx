// The seeded modes' global SS code for the coder (vtouch::SeededDistributedCoding, issue 19 item
// 2), ranks as threads (InProcessWorld, no MPI): every rank gets the single run's field from the
// single run's root; a rank whose run stopped before its coder joins and nobody waits; every
// failure is a verdict every rank reaches together; the coder's hook in VoxelCodingSkeletonFilter.
#include "vtouchSeededDistributedCoding.h"
#include "vtouchSeedVoxel.h"
#include "vtouchSinglePointPaths.h"

#include "vtouchInProcessCollectives.h"
#include "vtouchPieceGrid.h"
#include "vtouchSkeletonStageTestSupport.h"
#include "vtouchVoxelCodingSkeletonFilter.h"

#include <itkImage.h>

#include <gtest/gtest.h>

#include <string>

namespace vtouch
{
namespace
{
using skeleton::test::Dims;
using test::InProcessWorld;
using test::layouts;
using test::pieceMask;

const std::array<double, 3> kSpacing_mm{ 1.0, 1.0, 1.0 };

/// The single run's SS field from `root` on the whole mask (VoxelCoder's propagation).
std::vector<float> singleRun(const SparseVesselMask& mask, const std::array<std::int64_t, 3>& root)
{
  skeleton::VoxelGrid grid(mask, kSpacing_mm, 0.0);
  skeleton::VoxelCodes codes;
  codes.ss.assign(mask.vesselCount(), skeleton::VoxelCodes::kInf);
  codes.flags.assign(mask.vesselCount(), 0);
  const std::function<bool(double)> none;
  skeleton::RunMeter meter(none);
  skeleton::SeedCodeStage stage(grid, meter, codes, 0.0);
  stage.propagate({ static_cast<std::uint32_t>(grid.linOf(root[0], root[1], root[2])) });
  return codes.ss;
}

/// Voxels of rank `l`'s piece mask whose field differs from the whole field, in `box` only.
int differing(const SparseVesselMask& whole,
  const std::vector<float>& single,
  const PieceLayout& l,
  const SparseVesselMask& piece,
  const std::vector<float>& field,
  const VoxelBox& box)
{
  int count = 0;
  const Dims d = l.pieceDims();
  piece.forEach(
    [&](std::uint64_t lin)
    {
      const auto li = static_cast<std::int64_t>(lin);
      const auto w = l.toWhole({ li % d[0], (li / d[0]) % d[1], li / (d[0] * d[1]) });
      if (box.contains(w))
      {
        const auto wl = static_cast<std::uint64_t>(l.wholeLinear(w));
        count += field[piece.rank(lin)] != single[whole.rank(wl)];
      }
    });
  return count;
}

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
    const std::vector<PieceLayout> pieces = layouts(whole.dims(), counts, 2);
    InProcessWorld world(static_cast<int>(pieces.size()));
    std::vector<int> rounds(pieces.size()), wrong(pieces.size());
    world.run(
      [&](int r, RankCollectives& c)
      {
        const PieceLayout& l = pieces[static_cast<std::size_t>(r)];
        SparseVesselMask mask = pieceMask(whole, l);
        SeededDistributedCoding coding(c, l, kSpacing_mm, true, seed, {});
        const std::vector<float> field = coding.code(mask);
        rounds[static_cast<std::size_t>(r)] = coding.report().rounds;
        wrong[static_cast<std::size_t>(r)] = differing(whole, single, l, mask, field, l.mine());
        EXPECT_EQ(coding.report().root_Whole, root);
        EXPECT_TRUE(coding.joined());
      });
    for (std::size_t r = 0; r < pieces.size(); ++r)
    {
      EXPECT_EQ(wrong[r], 0) << "rank " << r << " of " << pieces.size();
      EXPECT_EQ(rounds[r], rounds[0]);
    }
    EXPECT_GE(rounds[0], 2) << "the field crosses a face: at least one relay";
  }
}

TEST(SeededDistributedCoding, ARankWhoseRunStoppedBeforeItsCoderJoinsAndNobodyWaits)
{
  // Split in z at 20 with the Y at z = 10: the upper piece (z >= 17 held) has no vessel voxel,
  // as a piece whose threshold mask is empty (its coder never runs: it joins afterwards).
  const SparseVesselMask whole = deepY();
  const std::array<std::int64_t, 3> seed{ 20, 10, 10 };
  const std::vector<float> single = singleRun(whole, seed);
  const std::vector<PieceLayout> pieces = layouts(whole.dims(), { 2, 1, 2 }, 3);
  InProcessWorld world(static_cast<int>(pieces.size()));
  std::vector<int> wrong(pieces.size(), -1);
  world.run(
    [&](int r, RankCollectives& c)
    {
      const PieceLayout& l = pieces[static_cast<std::size_t>(r)];
      SparseVesselMask mask = pieceMask(whole, l);
      SeededDistributedCoding coding(c, l, kSpacing_mm, true, seed, {});
      if (mask.vesselCount() == 0)
      {
        coding.join();
        EXPECT_TRUE(coding.joined());
        return;
      }
      const std::vector<float> field = coding.code(mask);
      wrong[static_cast<std::size_t>(r)] = differing(whole, single, l, mask, field, l.mine());
    });
  EXPECT_EQ(wrong[0], 0);
  EXPECT_EQ(wrong[1], 0);
  EXPECT_EQ(wrong[2], -1) << "the upper pieces hold no vessel";
  EXPECT_EQ(wrong[3], -1);
}

/// Runs every rank of `pieces` with `body` and returns each rank's error message ("" none).
std::vector<std::string> verdicts(const std::vector<PieceLayout>& pieces,
  const std::function<void(int, RankCollectives&, std::vector<std::string>&)>& body)
{
  std::vector<std::string> messages(pieces.size());
  InProcessWorld world(static_cast<int>(pieces.size()));
  world.run([&](int r, RankCollectives& c) { body(r, c, messages); });
  return messages;
}

TEST(SeededDistributedCoding, EveryFailureIsOneVerdictOnEveryRank)
{
  const SparseVesselMask whole = skeleton::test::yShape();
  const std::vector<PieceLayout> pieces = layouts(whole.dims(), { 2, 2, 1 }, 2);
  const auto run = [&](const std::array<std::int64_t, 3>& seed, int noPieceRank)
  {
    return verdicts(pieces,
      [&](int r, RankCollectives& c, std::vector<std::string>& messages)
      {
        PieceLayout l = pieces[static_cast<std::size_t>(r)];
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
          messages[static_cast<std::size_t>(r)] = e.what();
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
  std::vector<std::uint64_t> cleared(2);
  std::vector<int> wrong(2);
  InProcessWorld world(2);
  world.run(
    [&](int r, RankCollectives& c)
    {
      const PieceLayout& l = pieces[static_cast<std::size_t>(r)];
      SparseVesselMask mask = pieceMask(whole, l);
      SeededDistributedCoding::Settings s;
      s.clearOuterLayer = true;
      SeededDistributedCoding coding(c, l, kSpacing_mm, r == 1, seed, s);
      const std::vector<float> field = coding.code(mask);
      EXPECT_EQ(field.size(), mask.vesselCount()) << "indexed by the mask as left";
      cleared[static_cast<std::size_t>(r)] = coding.report().clearedVoxels;
      wrong[static_cast<std::size_t>(r)] = differing(whole, single, l, mask, field, l.evaluable(r));
      EXPECT_EQ(coding.report().root_Whole, seed);
    });
  EXPECT_GT(cleared[0], 0U) << "the trunk crosses rank 0's outer layer";
  EXPECT_GT(cleared[1], 0U);
  EXPECT_EQ(wrong[0], 0);
  EXPECT_EQ(wrong[1], 0);
}

TEST(SeededDistributedCoding, JoiningTwiceIsRefused)
{
  const SparseVesselMask whole = skeleton::test::yShape();
  const std::vector<PieceLayout> pieces = layouts(whole.dims(), { 1, 1, 1 }, 0);
  InProcessWorld world(1);
  world.run(
    [&](int, RankCollectives& c)
    {
      SparseVesselMask mask = whole;
      SeededDistributedCoding coding(c, pieces[0], kSpacing_mm, true, { 20, 10, 10 }, {});
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

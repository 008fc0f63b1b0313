// The unseeded modes' global SS code for the coder (vtouch::AutomaticRootDistributedCoding, issue
// 19 item 2), ranks as threads (InProcessWorld, no MPI): every rank codes with the single run's
// field from the single run's automatic root (a piece without vessels takes part with its empty
// mask); a rank whose run stopped before its coder stops every rank with one message and nobody
// waits; a failing choice is one verdict; the coder's hook codes that field as the single run.
#include "vtouchAutomaticRootDistributedCoding.h"

#include "vtouchInProcessCollectives.h"
#include "vtouchPieceGrid.h"
#include "vtouchSkeletonStageTestSupport.h"
#include "vtouchVoxelCodingSkeletonFilter.h"

#include <itkImage.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <limits>
#include <string>

namespace vtouch
{
namespace
{
using skeleton::test::Dims;
using test::InProcessWorld;
using test::layouts;
using test::pieceMask;
using Index = std::array<std::int64_t, 3>;

const std::array<double, 3> kSpacing_mm{ 1.0, 1.0, 1.0 };

/// The Y of the stage tests in a volume twice as deep (z 0..39, the Y at z = 10) and a speck of
/// 7 voxels at (35, 35, 3) (below the default MinimumComponentSize of 100); nothing above z = 14.
SparseVesselMask deepYAndSpeck()
{
  return skeleton::test::makeMask({ 40, 40, 40 },
    [](const skeleton::Point_mm& p)
    {
      const double dx = p[0] - 35, dy = p[1] - 35, dz = p[2] - 3;
      return skeleton::test::distanceToY(p) <= 3.0 || dx * dx + dy * dy + dz * dz <= 1.0;
    });
}

/// The single run: VoxelCoder without a seed; its root (the extremity) and its field from it.
struct SingleRun
{
  RawComponentRoot root;
  std::vector<float> ss;
};

SingleRun singleRun(const SparseVesselMask& mask)
{
  VoxelCodingParameters p;
  p.spacing_mm = kSpacing_mm;
  const RawSkeleton skeleton = VoxelCoder(mask, p).run();
  SingleRun out;
  if (skeleton.roots.size() != 1)
  {
    return out;
  }
  out.root = skeleton.roots[0];
  skeleton::VoxelGrid grid(mask, kSpacing_mm, 0.0);
  std::vector<std::uint32_t> sources;
  for (const Index& v : out.root.extremity)
  {
    sources.push_back(static_cast<std::uint32_t>(grid.linOf(v[0], v[1], v[2])));
  }
  skeleton::VoxelCodes codes;
  codes.ss.assign(mask.vesselCount(), skeleton::VoxelCodes::kInf);
  codes.flags.assign(mask.vesselCount(), 0);
  const std::function<bool(double)> none;
  skeleton::RunMeter meter(none);
  skeleton::SeedCodeStage(grid, meter, codes, 0.0).propagate(sources);
  out.ss = codes.ss;
  return out;
}

/// Voxels of rank `l`'s piece mask, in its owned box, whose field differs from the whole field.
int differing(const SparseVesselMask& whole,
  const std::vector<float>& single,
  const PieceLayout& l,
  const SparseVesselMask& piece,
  const std::vector<float>& field)
{
  int count = 0;
  const Dims d = l.pieceDims();
  piece.forEach(
    [&](std::uint64_t lin)
    {
      const auto li = static_cast<std::int64_t>(lin);
      const auto w = l.toWhole({ li % d[0], (li / d[0]) % d[1], li / (d[0] * d[1]) });
      if (l.owned[static_cast<std::size_t>(l.rank)].contains(w))
      {
        const auto wl = static_cast<std::uint64_t>(l.wholeLinear(w));
        count += field[piece.rank(lin)] != single[whole.rank(wl)];
      }
    });
  return count;
}

TEST(AutomaticRootDistributedCoding, EveryRankCodesWithTheSingleRunsFieldFromItsAutomaticRoot)
{
  const SparseVesselMask whole = deepYAndSpeck();
  const SingleRun single = singleRun(whole);
  ASSERT_EQ(single.root.extremity.size(), 1U) << "one component coded (the speck is skipped)";
  for (const std::array<int, 3>& counts :
    { std::array<int, 3>{ 2, 1, 1 }, std::array<int, 3>{ 2, 2, 1 }, std::array<int, 3>{ 1, 1, 4 } })
  {
    const std::vector<PieceLayout> pieces = layouts(whole.dims(), counts, 2);
    InProcessWorld world(static_cast<int>(pieces.size()));
    std::vector<int> wrong(pieces.size(), -1), rounds(pieces.size(), -1);
    std::vector<std::uint64_t> vessel(pieces.size(), 0);
    world.run(
      [&](int r, RankCollectives& c)
      {
        const PieceLayout& l = pieces[static_cast<std::size_t>(r)];
        const SparseVesselMask mask = pieceMask(whole, l);
        AutomaticRootDistributedCoding coding(c, l, kSpacing_mm, {});
        // A piece without vessel voxels (the upper quarters in z) reaches its coder too.
        const std::vector<float> field = coding.code(mask);
        ASSERT_EQ(field.size(), mask.vesselCount());
        vessel[static_cast<std::size_t>(r)] = mask.vesselCount();
        wrong[static_cast<std::size_t>(r)] = differing(whole, single.ss, l, mask, field);
        rounds[static_cast<std::size_t>(r)] = coding.report().rounds;
        ASSERT_EQ(coding.report().components.size(), 1U);
        EXPECT_EQ(coding.report().components[0].roots_Whole, single.root.extremity);
        EXPECT_TRUE(coding.report().ss_mm.empty()) << "the field was handed over";
        EXPECT_TRUE(coding.joined());
      });
    for (std::size_t r = 0; r < pieces.size(); ++r)
    {
      EXPECT_EQ(wrong[r], 0) << "rank " << r << " of " << pieces.size();
      EXPECT_EQ(rounds[r], rounds[0]);
    }
    EXPECT_GE(rounds[0], 2) << "the fields cross a face: at least one relay";
    if (counts[2] == 4)
    {
      EXPECT_EQ(vessel[3], 0U) << "the upper quarter holds no vessel and took part";
    }
  }
}

/// Runs every rank of `pieces` with `body` and returns each rank's error message ("" none).
std::vector<std::string> verdicts(const std::vector<PieceLayout>& pieces,
  const std::function<void(int, RankCollectives&)>& body)
{
  std::vector<std::string> messages(pieces.size());
  InProcessWorld world(static_cast<int>(pieces.size()));
  world.run(
    [&](int r, RankCollectives& c)
    {
      try
      {
        body(r, c);
      }
      catch (const AutomaticRootCodingError& e)
      {
        messages[static_cast<std::size_t>(r)] = e.what();
      }
    });
  return messages;
}

TEST(AutomaticRootDistributedCoding, ARankWhoseRunStoppedBeforeItsCoderStopsEveryRankAsOne)
{
  const SparseVesselMask whole = skeleton::test::yShape();
  const std::vector<PieceLayout> pieces = layouts(whole.dims(), { 2, 2, 1 }, 2);
  std::vector<int> roundsTaken(pieces.size(), -1);
  const std::vector<std::string> m = verdicts(pieces,
    [&](int r, RankCollectives& c)
    {
      const PieceLayout& l = pieces[static_cast<std::size_t>(r)];
      AutomaticRootDistributedCoding coding(c, l, kSpacing_mm, {});
      if (r == 2)
      {
        coding.join(); // its run stopped before its coder (an error, a cancel)
      }
      else
      {
        coding.code(pieceMask(whole, l));
      }
      roundsTaken[static_cast<std::size_t>(r)] = coding.report().rounds;
    });
  for (const std::string& text : m)
  {
    EXPECT_NE(text.find("rank 2 stopped before its coder"), std::string::npos) << text;
    EXPECT_EQ(text, m[0]);
  }
  EXPECT_EQ(roundsTaken, std::vector<int>(pieces.size(), -1)) << "every rank threw";
}

TEST(AutomaticRootDistributedCoding, AFailingChoiceIsOneVerdictOnEveryRank)
{
  // A round cap of 1: the Y's field crosses the face in x, so the first propagation cannot
  // settle in one exchange.
  const SparseVesselMask whole = skeleton::test::yShape();
  const std::vector<PieceLayout> pieces = layouts(whole.dims(), { 2, 1, 1 }, 2);
  DistributedRootChoice::Parameters capped;
  capped.maximumRounds = 1;
  const std::vector<std::string> m = verdicts(pieces,
    [&](int r, RankCollectives& c)
    {
      const PieceLayout& l = pieces[static_cast<std::size_t>(r)];
      AutomaticRootDistributedCoding coding(c, l, kSpacing_mm, capped);
      coding.code(pieceMask(whole, l));
    });
  for (const std::string& text : m)
  {
    EXPECT_NE(text.find("the automatic root across the pieces failed"), std::string::npos) << text;
    EXPECT_EQ(text, m[0]);
  }
  EXPECT_FALSE(m[0].empty());
}

TEST(AutomaticRootDistributedCoding, JoiningTwiceIsRefused)
{
  const SparseVesselMask whole = skeleton::test::yShape();
  const std::vector<PieceLayout> pieces = layouts(whole.dims(), { 1, 1, 1 }, 0);
  InProcessWorld world(1);
  world.run(
    [&](int, RankCollectives& c)
    {
      AutomaticRootDistributedCoding coding(c, pieces[0], kSpacing_mm, {});
      coding.code(whole);
      EXPECT_THROW(coding.join(), std::logic_error);
      EXPECT_THROW(coding.code(whole), std::logic_error);
    });
}

/// The largest Chebyshev distance from a voxel of `from`'s paths to the nearest of `to`'s.
std::int64_t farthestChebyshev(const RawSkeleton& from, const RawSkeleton& to)
{
  std::int64_t farthest = 0;
  for (const RawSkeletonPath& p : from.paths)
  {
    for (const Index& v : p.voxels)
    {
      std::int64_t nearest = std::numeric_limits<std::int64_t>::max();
      for (const RawSkeletonPath& q : to.paths)
      {
        for (const Index& w : q.voxels)
        {
          nearest = std::min(nearest,
            std::max({ std::abs(v[0] - w[0]), std::abs(v[1] - w[1]), std::abs(v[2] - w[2]) }));
        }
      }
      farthest = std::max(farthest, nearest);
    }
  }
  return farthest;
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

TEST(VoxelCodingSkeletonFilterGlobalSeedCode, TheAutomaticRootsFieldCodesTheSingleRunsSkeleton)
{
  // Where the single run does not move its root to a thicker end (the Y: three ends of one
  // radius), its field from the automatic root is the one the single run codes with.
  const SparseVesselMask whole = deepYAndSpeck();
  ASSERT_FALSE(singleRun(whole).root.moved);
  using Filter = VoxelCodingSkeletonFilter<ByteImage>;
  auto single = Filter::New();
  single->SetInput(imageOf(whole));
  single->SetDownsampleFactor(1);
  single->Update();
  auto hooked = Filter::New();
  hooked->SetInput(imageOf(whole));
  InProcessWorld world(1);
  world.run(
    [&](int, RankCollectives& c)
    {
      const std::vector<PieceLayout> pieces = layouts(whole.dims(), { 1, 1, 1 }, 0);
      AutomaticRootDistributedCoding coding(c, pieces[0], kSpacing_mm, {});
      hooked->SetGlobalSeedCode([&](SparseVesselMask& mask) { return coding.code(mask); });
      hooked->Update();
      EXPECT_TRUE(coding.joined());
    });
  const RawSkeleton& a = single->GetRawSkeleton();
  const RawSkeleton& b = hooked->GetRawSkeleton();
  EXPECT_EQ(b.paths.size(), a.paths.size());
  EXPECT_EQ(b.junctions.size(), a.junctions.size());
  // Skeleton voxels at most one voxel apart (Chebyshev), both ways: tips tied in SS are traced
  // in index order with the given field (VoxelCoder's global-field mode), not in queue order.
  EXPECT_LE(farthestChebyshev(a, b), 1);
  EXPECT_LE(farthestChebyshev(b, a), 1);
}

/// A binary image of rank `l`'s piece of `whole` (indexed from the piece's first voxel).
ByteImage::Pointer pieceImage(const SparseVesselMask& whole, const PieceLayout& l)
{
  return imageOf(pieceMask(whole, l));
}

TEST(VoxelCodingSkeletonFilterGlobalSeedCode, EachComponentsTracesJoinTheirOwnRoot)
{
  // Four tubes along z (separate components) split in z: the automatic roots all lie at the top
  // (the extremity farthest from each tube's first voxel), so the upper piece codes a field with
  // four roots. The last tube reaches 4 voxels higher: its root is the last root cluster and its
  // tip the first traced. Every trace must join the root band of its own tube: before the fix
  // (TraceStage joined the last root cluster) the other tubes' traces joined the last tube's
  // root, paths 12 voxels or more across.
  const SparseVesselMask whole = skeleton::test::makeMask({ 52, 20, 40 },
    [](const skeleton::Point_mm& p)
    {
      for (double x : { 8.0, 20.0, 32.0, 44.0 })
      {
        const double dx = p[0] - x, dy = p[1] - 10;
        if (p[2] >= 3 && p[2] <= (x > 40 ? 37 : 33) && dx * dx + dy * dy <= 6.25)
        {
          return true;
        }
      }
      return false;
    });
  const std::vector<PieceLayout> pieces = layouts(whole.dims(), { 1, 1, 2 }, 2);
  std::vector<RawSkeleton> skeletons(pieces.size());
  std::vector<std::size_t> roots(pieces.size());
  InProcessWorld world(static_cast<int>(pieces.size()));
  using Filter = VoxelCodingSkeletonFilter<ByteImage>;
  {
    // ITK creates its global singletons on first use; the uninstrumented library's guard is
    // invisible to TSan, which reports the ranks' threads creating them at once: one run on this
    // thread first.
    auto first = Filter::New();
    first->SetInput(imageOf(whole));
    first->Update();
  }
  world.run(
    [&](int r, RankCollectives& c)
    {
      const PieceLayout& l = pieces[static_cast<std::size_t>(r)];
      AutomaticRootDistributedCoding coding(c, l, kSpacing_mm, {});
      auto filter = Filter::New();
      filter->SetInput(pieceImage(whole, l));
      filter->SetGlobalSeedCode([&](SparseVesselMask& mask) { return coding.code(mask); });
      filter->Update();
      skeletons[static_cast<std::size_t>(r)] = filter->GetRawSkeleton();
      roots[static_cast<std::size_t>(r)] = coding.report().components.size();
    });
  EXPECT_EQ(roots[0], 4U);
  for (std::size_t r = 0; r < pieces.size(); ++r)
  {
    const RawSkeleton& s = skeletons[r];
    EXPECT_GE(s.paths.size(), 4U) << "rank " << r << ": a path per tube at least";
    for (const RawSkeletonPath& p : s.paths)
    {
      // A path stays in its tube (radius 2.5 voxels around x = 8, 20, 32 or 44): a trace joined
      // to another tube's root runs 12 voxels or more across, through the background.
      std::int64_t lo = p.voxels.front()[0], hi = lo;
      for (const Index& v : p.voxels)
      {
        lo = std::min(lo, v[0]);
        hi = std::max(hi, v[0]);
      }
      EXPECT_LE(hi - lo, 4) << "rank " << r << ": a path across tubes, x " << lo << ".." << hi;
    }
  }
}

} // namespace
} // namespace vtouch

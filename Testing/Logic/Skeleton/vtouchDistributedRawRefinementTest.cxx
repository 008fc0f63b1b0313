// The raw path's refinement over the whole stitched paths (issue 19 item 2, h19r), ranks as
// threads of one process (InProcessWorld, no MPI), on the 112^3 raw phantom of
// vtouchDistributedRawStitchTest (ClientServer.DistributedRawSeeded's recipe):
//  - the pages of the volume (DistributedVolumePages) give the single run's in-range bit and
//    intensity at every voxel on 2, 4 and 8 pieces, held by the first rank only, as floats when
//    floats hold the values (doubles otherwise, exactly);
//  - RawSkeletonRefinement over the pages of a skeleton equals the single run's refinement of the
//    same skeleton exactly (every point of every path, the junctions, the counts), with the
//    prefetch bound and with none (the miss-and-re-run path);
//  - a rank with no piece, an owner that throws and a reader that throws end every rank's rounds
//    together (a hang fails: InProcessWorld's time-out), with the failure named on the first rank.
#include "vtouchDistributedRawRefinement.h"
#include "vtouchDistributedStitchRun.h"
#include "vtouchEveryRank.h"
#include "vtouchPieceGrid.h"
#include "vtouchRankPiece.h"
#include "vtouchRawPhantomVolume.h"
#include "vtouchVesselCandidateRegion.h"

#include <gtest/gtest.h>
#include <itkMultiThreaderBase.h>

#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace vtouch
{
namespace
{
using Index = std::array<std::int64_t, 3>;

/// The ghost margin of the client/server raw tests (LargestVesselRadius 4 voxels: G = 31).
constexpr int kMargin = 31;

/// The 112^3 raw phantom (60 segments, 4 clutter objects, seed 3, noise 10).
std::vector<float> rawPhantom112()
{
  test::FloatVolume v = test::rawPhantomVolume(112, 3, 60, 10.0);
  EXPECT_TRUE(v.ok) << v.error;
  return std::move(v.voxels);
}

constexpr Index kDims{ 112, 112, 112 };

/// Rank `l`'s owned voxels' intensities from its copy of its held box.
DistributedVolumePages::OwnedIntensity ownedFrom(const test::RankPiece& piece)
{
  return [&piece](const Index& w)
  { return static_cast<double>(piece.voxels[static_cast<std::size_t>(piece.linear(w))]); };
}

/// Bitwise equality of two doubles (+0 and -0 differ, NaN equals itself).
bool same(double a, double b)
{
  return std::memcmp(&a, &b, sizeof a) == 0;
}

/// How many points, ends and junctions of `a` differ from `b`'s, bit for bit.
int differences(const QSkeleton& a, const QSkeleton& b)
{
  if (a.paths.size() != b.paths.size() || a.junctions.size() != b.junctions.size())
  {
    return 1000000;
  }
  int n = 0;
  for (std::size_t p = 0; p < a.paths.size(); ++p)
  {
    const SkeletonPath& pa = a.paths[p];
    const SkeletonPath& pb = b.paths[p];
    n += pa.head.junction != pb.head.junction || pa.tail.junction != pb.tail.junction;
    if (pa.points.size() != pb.points.size())
    {
      n += 1000;
      continue;
    }
    for (std::size_t i = 0; i < pa.points.size(); ++i)
    {
      const SkeletonPoint& x = pa.points[i];
      const SkeletonPoint& y = pb.points[i];
      n += !(same(x.position_World_mm.x, y.position_World_mm.x) &&
             same(x.position_World_mm.y, y.position_World_mm.y) &&
             same(x.position_World_mm.z, y.position_World_mm.z) &&
             same(x.tangent_World.x, y.tangent_World.x) &&
             same(x.tangent_World.y, y.tangent_World.y) &&
             same(x.tangent_World.z, y.tangent_World.z) && same(x.radius_mm, y.radius_mm) &&
             same(x.curvature_per_mm, y.curvature_per_mm) &&
             same(x.torsion_per_mm, y.torsion_per_mm) && x.label == y.label);
    }
  }
  for (std::size_t j = 0; j < a.junctions.size(); ++j)
  {
    const Junction& x = a.junctions[j];
    const Junction& y = b.junctions[j];
    n += x.childPath != y.childPath || x.childEnd != y.childEnd || x.parentPath != y.parentPath ||
         x.parentPoint != y.parentPoint;
  }
  return n;
}

TEST(DistributedVolumePages,
  GiveTheSingleRunsInRangeBitAndIntensityAtEveryVoxelOnTwoFourAndEightPieces)
{
  const std::vector<float> voxels = rawPhantom112();
  VolumeView<float> whole;
  whole.voxels = voxels.data();
  whole.dims = kDims;
  const IntensityRange range = IntensityRangeEstimator::fromVolume(whole);
  ASSERT_TRUE(range.ok) << range.message;
  // The single run's predicate (rangeForeground's) and intensities on the whole volume.
  const auto n = static_cast<std::uint64_t>(voxels.size());
  for (const std::array<int, 3>& counts : test::kSplitsIn2And4And8)
  {
    struct Seen
    {
      std::uint64_t bitsDiffer = 0, valuesDiffer = 0, inRange = 0;
      DistributedVolumePages::Outcome outcome;
    };
    const std::vector<Seen> seen = test::onEveryRank<Seen>(test::layouts(kDims, counts, kMargin),
      [&](const PieceLayout& l, RankCollectives& c, Seen& mine)
      {
        const test::RankPiece piece(voxels, kDims, l);
        DistributedVolumePages pages(c, l, ownedFrom(piece));
        const std::array<std::int64_t, 3>& per = pages.pagesPerAxis();
        std::vector<std::int64_t> all(static_cast<std::size_t>(per[0] * per[1] * per[2]));
        for (std::size_t p = 0; p < all.size(); ++p)
        {
          all[p] = static_cast<std::int64_t>(p);
        }
        const SectionForeground fg = pages.inRange(range.lower, range.upper);
        const SectionIntensity in = pages.intensity();
        mine.outcome = pages.run(all,
          [&]
          {
            for (std::uint64_t lin = 0; lin < n; ++lin)
            {
              const double v = static_cast<double>(voxels[lin]);
              const bool bit = inIntensityRange(v, range.lower, range.upper);
              mine.inRange += bit;
              mine.bitsDiffer += fg.inside(lin) != bit;
              mine.valuesDiffer += !same(in.value(lin), v);
            }
          });
      });
    const int pieces = counts[0] * counts[1] * counts[2];
    const DistributedVolumePages::Outcome& o = seen[0].outcome;
    EXPECT_TRUE(o.completed) << o.message;
    EXPECT_EQ(seen[0].bitsDiffer, 0U) << pieces << " pieces";
    EXPECT_EQ(seen[0].valuesDiffer, 0U) << pieces << " pieces";
    EXPECT_GT(seen[0].inRange, 0U);
    EXPECT_EQ(o.pagesFetched, 7 * 7 * 7) << pieces << " pieces";
    EXPECT_EQ(o.rounds, 1);
    EXPECT_EQ(o.runs, 1);
    // Floats, not doubles: 4 bytes a voxel and the parts' headers (3 words, half a word of
    // padding at most), every page's part from each of its owners.
    EXPECT_LE(o.bytesGathered, static_cast<std::int64_t>(4 * n + 32 * 343 * pieces));
    for (int r = 1; r < pieces; ++r)
    {
      EXPECT_EQ(seen[static_cast<std::size_t>(r)].outcome.pagesFetched, 0) << "rank " << r;
      EXPECT_EQ(seen[static_cast<std::size_t>(r)].outcome.rounds, 1) << "rank " << r;
    }
    std::printf("%d pieces: %lld pages, %lld bytes gathered\n",
      pieces,
      static_cast<long long>(o.pagesFetched),
      static_cast<long long>(o.bytesGathered));
  }
}

TEST(DistributedVolumePages, KeepDoublesThatAFloatDoesNotHoldExactly)
{
  const Index dims{ 40, 36, 30 };
  std::vector<double> voxels(static_cast<std::size_t>(dims[0] * dims[1] * dims[2]));
  for (std::size_t i = 0; i < voxels.size(); ++i)
  {
    voxels[i] = 0.1 * static_cast<double>(i); // 0.1 k: not a float's value
  }
  std::uint64_t differ = 0;
  std::int64_t bytes = 0;
  test::onEveryRank<int>(test::layouts(dims, { 1, 1, 2 }, 3),
    [&](const PieceLayout& l, RankCollectives& c, int&)
    {
      DistributedVolumePages pages(
        c, l, [&](const Index& w) { return voxels[static_cast<std::size_t>(l.wholeLinear(w))]; });
      const SectionIntensity in = pages.intensity();
      const std::vector<std::int64_t> all{ 0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11 };
      const DistributedVolumePages::Outcome o = pages.run(all,
        [&]
        {
          for (std::uint64_t lin = 0; lin < voxels.size(); ++lin)
          {
            differ += !same(in.value(lin), voxels[lin]);
          }
        });
      if (c.rank() == 0)
      {
        EXPECT_TRUE(o.completed) << o.message;
        bytes = o.bytesGathered;
      }
    });
  EXPECT_EQ(differ, 0U);
  EXPECT_GE(bytes, static_cast<std::int64_t>(8 * voxels.size()));
}

/// The single run's candidate region of the 112^3 raw phantom, its skeleton before the
/// refinement (the coder's), the range and the volume: what the refinement tests share.
struct RawScene
{
  std::vector<float> voxels;
  IntensityRange range;
  QSkeleton coded;
};

const RawScene& rawScene()
{
  static const RawScene scene = []
  {
    itk::MultiThreaderBase::SetGlobalDefaultNumberOfThreads(1);
    RawScene s;
    s.voxels = rawPhantom112();
    VolumeView<float> whole;
    whole.voxels = s.voxels.data();
    whole.dims = kDims;
    const VesselCandidateRegion::Result region =
      VesselCandidateRegion::extract(whole, VesselCandidateRegion::Settings{});
    EXPECT_TRUE(region.ok) << region.message;
    s.range = region.range;
    std::vector<float> mask(s.voxels.size(), 0.0F);
    region.mask.forEach([&mask](std::uint64_t lin) { mask[lin] = 1000.0F; });
    s.coded = test::runDistributedStitch(mask, kDims, 500.0, { 1, 1, 1 }, kMargin).single;
    return s;
  }();
  return scene;
}

DistributedRawRefinement::Settings settingsOf(const IntensityRange& range)
{
  DistributedRawRefinement::Settings s;
  s.smoothingWindow_mm = 0.0; // the filter's default (automatic windows)
  s.lower = range.lower;
  s.upper = range.upper;
  s.background = range.background;
  s.backgroundNoise = range.backgroundNoise;
  return s;
}

/// The single run's refinement (ExtractVolume's) of `coded` on the whole volume.
RawSkeletonRefinement singleRefinement(const RawScene& scene, QSkeleton& skeleton)
{
  const float* v = scene.voxels.data();
  const double lower = scene.range.lower, upper = scene.range.upper;
  const SectionForeground inRange{ kDims,
    [v, lower, upper](std::uint64_t lin)
    { return inIntensityRange(static_cast<double>(v[lin]), lower, upper); } };
  const TurnedDimTipTrimmer::Evidence tips{
    { kDims, [v](std::uint64_t lin) { return static_cast<double>(v[lin]); } },
    lower,
    scene.range.background,
    scene.range.backgroundNoise
  };
  return RawSkeletonRefinement::apply(skeleton, inRange, SectionGeometry{}, 0.0, &tips);
}

/// The refinement over the pages on `counts` pieces; the first rank's result and skeleton.
DistributedRawRefinement::Result distributedRefinement(const RawScene& scene,
  const std::array<int, 3>& counts,
  const DistributedRawRefinement::Settings& settings,
  QSkeleton& skeleton)
{
  const std::vector<DistributedRawRefinement::Result> results =
    test::onEveryRank<DistributedRawRefinement::Result>(test::layouts(kDims, counts, kMargin),
      [&](const PieceLayout& l, RankCollectives& c, DistributedRawRefinement::Result& mine)
      {
        const test::RankPiece piece(scene.voxels, kDims, l);
        mine = DistributedRawRefinement::run(
          c, l, ownedFrom(piece), l.rank == 0 ? &skeleton : nullptr, SectionGeometry{}, settings);
      });
  return results[0];
}

TEST(DistributedRawRefinement, OverThePagesIsTheSingleRunsRefinementOfTheSameSkeleton)
{
  const RawScene& scene = rawScene();
  ASSERT_FALSE(scene.coded.empty());
  QSkeleton single = scene.coded;
  const RawSkeletonRefinement expected = singleRefinement(scene, single);
  // The phantom's clutter exercises the stages: the comparison is not of an untouched skeleton.
  EXPECT_GT(expected.tracked.stretchesTracked + expected.tracked.stretchesCut +
              expected.pruned.pathsRemoved,
    0);
  for (const std::array<int, 3>& counts : test::kSplitsIn2And4And8)
  {
    const int pieces = counts[0] * counts[1] * counts[2];
    QSkeleton skeleton = scene.coded;
    const DistributedRawRefinement::Result got =
      distributedRefinement(scene, counts, settingsOf(scene.range), skeleton);
    ASSERT_TRUE(got.refined) << got.message;
    EXPECT_EQ(differences(skeleton, single), 0) << pieces << " pieces";
    EXPECT_EQ(got.refinement.tracked.stretchesTracked, expected.tracked.stretchesTracked);
    EXPECT_EQ(got.refinement.tracked.stretchesCut, expected.tracked.stretchesCut);
    EXPECT_EQ(got.refinement.pruned.pathsRemoved, expected.pruned.pathsRemoved);
    EXPECT_EQ(got.refinement.tips.tipsTrimmed, expected.tips.tipsTrimmed);
    std::printf("%d pieces: %lld pages prefetched, %lld fetched of 343, %d rounds, %d runs, %lld "
                "bytes gathered; retraced %d, cut %d, removed %d\n",
      pieces,
      static_cast<long long>(got.pagesPrefetched),
      static_cast<long long>(got.pages.pagesFetched),
      got.pages.rounds,
      got.pages.runs,
      static_cast<long long>(got.pages.bytesGathered),
      got.refinement.tracked.stretchesTracked,
      got.refinement.tracked.stretchesCut,
      got.refinement.pruned.pathsRemoved);
  }
}

TEST(DistributedRawRefinement, MissedPagesAreFetchedAndTheRunRepeatedToTheSameResult)
{
  const RawScene& scene = rawScene();
  QSkeleton single = scene.coded;
  singleRefinement(scene, single);
  DistributedRawRefinement::Settings settings = settingsOf(scene.range);
  settings.prefetchRadii = 0.0; // only the points' own pages: the sections' rays miss
  settings.prefetchMargin_voxels = 0.0;
  QSkeleton skeleton = scene.coded;
  const DistributedRawRefinement::Result got =
    distributedRefinement(scene, { 1, 1, 2 }, settings, skeleton);
  ASSERT_TRUE(got.refined) << got.message;
  EXPECT_GT(got.pages.runs, 1);
  EXPECT_EQ(got.pages.rounds, got.pages.runs); // the prefetch's round, then one per miss
  EXPECT_EQ(differences(skeleton, single), 0);
  std::printf("prefetch bound 0: %lld pages prefetched, %lld fetched, %d rounds, %d runs\n",
    static_cast<long long>(got.pagesPrefetched),
    static_cast<long long>(got.pages.pagesFetched),
    got.pages.rounds,
    got.pages.runs);
}

TEST(DistributedRawRefinement, ARankWithoutAPieceEndsEveryRanksRoundsWithAMessage)
{
  const RawScene& scene = rawScene();
  QSkeleton skeleton = scene.coded;
  const std::vector<DistributedRawRefinement::Result> results =
    test::onEveryRank<DistributedRawRefinement::Result>(test::layouts(kDims, { 1, 2, 2 }, kMargin),
      [&](const PieceLayout& l, RankCollectives& c, DistributedRawRefinement::Result& mine)
      {
        const test::RankPiece piece(scene.voxels, kDims, l);
        mine = DistributedRawRefinement::run(c,
          l,
          l.rank == 2 ? DistributedVolumePages::OwnedIntensity{} : ownedFrom(piece),
          l.rank == 0 ? &skeleton : nullptr,
          SectionGeometry{},
          settingsOf(scene.range));
      });
  EXPECT_FALSE(results[0].refined);
  EXPECT_NE(results[0].message.find("rank 2 holds no piece"), std::string::npos)
    << results[0].message;
  EXPECT_EQ(differences(skeleton, scene.coded), 0); // left as it was
  for (const DistributedRawRefinement::Result& r : results)
  {
    EXPECT_EQ(r.pages.rounds, results[0].pages.rounds); // every rank made the same rounds
  }
}

TEST(DistributedVolumePages, AnOwnerOrTheReaderThatThrowsEndsEveryRanksRounds)
{
  const Index dims{ 40, 40, 40 };
  for (const bool ownerThrows : { true, false })
  {
    const std::vector<DistributedVolumePages::Outcome> outcomes =
      test::onEveryRank<DistributedVolumePages::Outcome>(test::layouts(dims, { 2, 2, 1 }, 3),
        [&](const PieceLayout& l, RankCollectives& c, DistributedVolumePages::Outcome& mine)
        {
          DistributedVolumePages pages(c,
            l,
            [&](const Index& w) -> double
            {
              if (ownerThrows && l.rank == 3)
              {
                throw std::runtime_error("unreadable voxel");
              }
              return static_cast<double>(w[0]);
            });
          const SectionIntensity in = pages.intensity();
          mine = pages.run({ 0 },
            [&]
            {
              for (std::uint64_t lin = 0; lin < 40U * 40U * 40U; ++lin)
              {
                in.value(lin); // misses until every page is held
              }
              throw std::runtime_error("the reader gave up");
            });
        });
    const std::string expected = ownerThrows ? "rank 3: unreadable voxel" : "the reader gave up";
    EXPECT_FALSE(outcomes[0].completed);
    EXPECT_EQ(outcomes[0].message, expected);
    for (const DistributedVolumePages::Outcome& o : outcomes)
    {
      EXPECT_EQ(o.rounds, outcomes[0].rounds);
    }
  }
}

} // namespace
} // namespace vtouch

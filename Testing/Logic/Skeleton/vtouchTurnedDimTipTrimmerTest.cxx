// TurnedDimTipTrimmer (issue 16 item 2): a thin vessel whose dim tip has one dim noise voxel
// beside it, grown, coded by the real voxel coder and refined as VesselCenterline does, ends at
// its tip and not on the noise voxel; the same vessel without the noise voxel keeps its real dim
// tip; a tip that bends through voxels holding part of the tube stays. Unit spacing, origin 0.
#include "vtouchTurnedDimTipTrimmer.h"
#include "vtouchRawAngiogramTestImages.h"
#include "vtouchSeededRegionGrower.h"

#include "vtouchMaskSceneSupport.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdint>

using namespace vtouch;

namespace
{
using test::SyntheticAngiogram;

const SectionGeometry kUnit{};

/// Background 100 with noise sigma 20 (the range estimator's B and S for the images below);
/// vessel 1000, lower bound 550, weak lower B + 3 S.
IntensityRange range()
{
  IntensityRange r;
  r.ok = true;
  r.lower = 550.0;
  r.upper = 2000.0;
  r.weakLower = 160.0;
  r.background = 100.0;
  r.backgroundNoise = 20.0;
  return r;
}

TurnedDimTipTrimmer::Evidence evidence(const SyntheticAngiogram& g)
{
  TurnedDimTipTrimmer::Evidence e;
  e.intensity.dims = g.dims;
  const float* v = g.voxels.data();
  e.intensity.value = [v](std::uint64_t lin) { return static_cast<double>(v[lin]); };
  e.lower = range().lower;
  e.background = range().background;
  e.backgroundNoise = range().backgroundNoise;
  return e;
}

/// A thin vessel (radius 0.55 voxel, partial volume, noise sigma 20) along the diagonal
/// (i, i, 12) from i = 4 to 19, its voxel (20, 20, 12) in the range, then its dim tip (partial
/// volume under noise): (21, 21, 12) and (22, 22, 12), below the range.
SyntheticAngiogram diagonalVesselWithDimTip()
{
  SyntheticAngiogram g({ 32, 32, 24 });
  g.addTube({ 4, 4, 12 }, { 19, 19, 12 }, 0.55, 900.0);
  g.addNoise(20.0, 7);
  g.at(20, 20, 12) = 600.0F;
  g.at(21, 21, 12) = 260.0F; // 8 S above B
  g.at(22, 22, 12) = 240.0F; // 7 S
  return g;
}

/// The voxel coder's skeleton of `g` grown from the vessel's first voxel as VesselCenterline grows
/// it (the ridge rule and the dim dead-end rule of step 2).
QSkeleton coded(const SyntheticAngiogram& g)
{
  const SparseVesselMask mask = SeededRegionGrower::grow(g.view(), range(), { 4, 4, 12 });
  return mask_scenes::codeFromSeed(g.dims, mask, { 4, 4, 12 });
}

/// The free end farthest from the seed: the vessel's tip as extracted.
Vec3 farthestEnd(const QSkeleton& s)
{
  const Vec3 seed{ 4, 4, 12 };
  Vec3 best = seed;
  for (const SkeletonPath& path : s.paths)
  {
    for (const SkeletonPoint* q : { &path.points.front(), &path.points.back() })
    {
      if ((q->position_World_mm - seed).norm() > (best - seed).norm())
      {
        best = q->position_World_mm;
      }
    }
  }
  return best;
}

double offAxis(const Vec3& p)
{
  return mask_scenes::segmentDistance(p, { 4, 4, 12 }, { 22, 22, 12 });
}
} // namespace

TEST(TurnedDimTipTrimmer, ThinVesselEndsAtItsTipNotOnADimNoiseVoxelBesideIt)
{
  SyntheticAngiogram g = diagonalVesselWithDimTip();
  // One dim noise voxel (6.5 S) touching the tip's last voxel by a corner, 90 degrees off the
  // vessel's direction: a ridge voxel the growth admits, kept with the dim strand (its summed
  // contrast passes Rose's criterion).
  g.at(23, 21, 13) = 230.0F;
  QSkeleton with = coded(g);
  ASSERT_EQ(with.validate(), "");
  const Vec3 endWithout = farthestEnd(with);
  // The scene is what the rule is for: the coder ends on the noise voxel, 1.7 voxels off the
  // vessel's axis.
  EXPECT_GT(offAxis(endWithout), 1.5) << endWithout.x << " " << endWithout.y << " " << endWithout.z;
  EXPECT_EQ(TurnedDimTipTrimmer::trim(with, evidence(g), kUnit).tipsTrimmed, 1);
  EXPECT_EQ(with.validate(), "");
  const Vec3 end = farthestEnd(with);
  EXPECT_LT(offAxis(end), 0.5) << end.x << " " << end.y << " " << end.z;
  EXPECT_GT(end.x, 21.5) << "the vessel's own dim tip stays";
  for (const SkeletonPath& path : with.paths)
  {
    for (const SkeletonPoint& q : path.points)
    {
      EXPECT_LT(offAxis(q.position_World_mm), 1.0);
    }
  }
}

TEST(TurnedDimTipTrimmer, KeepsAThinVesselsRealDimTip)
{
  const SyntheticAngiogram g = diagonalVesselWithDimTip();
  QSkeleton with = coded(g);
  const std::size_t before = with.pointCount();
  EXPECT_EQ(TurnedDimTipTrimmer::trim(with, evidence(g), kUnit).tipsTrimmed, 0);
  EXPECT_EQ(with.validate(), "");
  EXPECT_EQ(with.pointCount(), before);
  const Vec3 end = farthestEnd(with);
  EXPECT_GT(end.x, 20.5) << "the path runs into the dim tip (the coder ends it there)";
  EXPECT_LT(offAxis(end), 0.5);
}

TEST(TurnedDimTipTrimmer, JudgesTheLastStepByItsTurnItsBridgeAndItsIntensity)
{
  SyntheticAngiogram g = diagonalVesselWithDimTip();
  g.at(23, 21, 13) = 230.0F;
  const TurnedDimTipTrimmer::Settings s;
  const Vec3 heading{ 1, 1, 0 }, p{ 22, 22, 12 }, q{ 23, 21, 13 };
  EXPECT_TRUE(TurnedDimTipTrimmer::isTurnedDimTip(evidence(g), kUnit, heading, p, q, s));
  // Straight on (a turn under 60 degrees): the vessel's own run, whatever its bridge.
  EXPECT_FALSE(
    TurnedDimTipTrimmer::isTurnedDimTip(evidence(g), kUnit, heading, { 21, 21, 12 }, p, s));
  // A face step has no bridge: never dropped.
  g.at(22, 22, 13) = 230.0F;
  EXPECT_FALSE(
    TurnedDimTipTrimmer::isTurnedDimTip(evidence(g), kUnit, heading, p, { 22, 22, 13 }, s));
  // The tube bends: the voxels between p and q hold part of it (partial volume, here 4 S above
  // B on average: more than 3 S / sqrt(6)).
  for (const std::array<std::int64_t, 3>& v : { std::array<std::int64_t, 3>{ 23, 22, 12 },
         { 22, 21, 12 },
         { 22, 22, 13 },
         { 23, 21, 12 },
         { 23, 22, 13 },
         { 22, 21, 13 } })
  {
    g.at(v[0], v[1], v[2]) = 180.0F;
  }
  EXPECT_FALSE(TurnedDimTipTrimmer::isTurnedDimTip(evidence(g), kUnit, heading, p, q, s));
  // A bright last point is vessel by the range, turned or not.
  SyntheticAngiogram bright = diagonalVesselWithDimTip();
  bright.at(23, 21, 13) = 900.0F;
  EXPECT_FALSE(TurnedDimTipTrimmer::isTurnedDimTip(evidence(bright), kUnit, heading, p, q, s));
  // Without a noise figure the rule is off.
  TurnedDimTipTrimmer::Evidence none = evidence(diagonalVesselWithDimTip());
  none.backgroundNoise = 0.0;
  EXPECT_FALSE(TurnedDimTipTrimmer::isTurnedDimTip(none, kUnit, heading, p, q, s));
}

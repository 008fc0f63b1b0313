// The owner of every point, the ghost margin rule, the grown extent and the fragment codec.
#include "vtouchPieceOwnership.h"
#include "vtouchSkeletonFragmentCodec.h"

#include <gtest/gtest.h>

#include <random>

namespace
{
using vtouch::PieceOwnership;
using vtouch::Vec3;
using vtouch::VoxelExtent6;

TEST(PieceOwnership, EveryPositionHasOneOwnerAndSharedFacesBelongToTheUpperPiece)
{
  // The executive's split of 0..63 in x: 0..32 and 32..63 (the face layer x = 32 shared).
  const VoxelExtent6 whole{ 0, 63, 0, 31, 0, 31 };
  const PieceOwnership o({ { 0, 32, 0, 31, 0, 31 }, { 32, 63, 0, 31, 0, 31 } }, whole);
  EXPECT_EQ(o.owner({ 31.99, 5, 5 }), 0);
  EXPECT_EQ(o.owner({ 32.0, 5, 5 }), 1);
  EXPECT_EQ(o.owner({ -0.4, 5, 5 }), 0); // beyond the volume's face: the piece on that face
  EXPECT_EQ(o.owner({ 63.4, 40, 5 }), 1);
  std::mt19937 random(7);
  std::uniform_real_distribution<double> u(-1.0, 65.0);
  for (int i = 0; i < 1000; ++i)
  {
    const Vec3 p{ u(random), u(random) / 2, u(random) / 2 };
    const int owner = o.owner(p);
    EXPECT_EQ(owner, p.x < 32.0 ? 0 : 1);
  }
}

TEST(PieceOwnership, AGapBetweenPiecesGoesToTheNearestPiece)
{
  const VoxelExtent6 whole{ 0, 63, 0, 9, 0, 9 };
  const PieceOwnership o({ { 0, 30, 0, 9, 0, 9 }, { 32, 63, 0, 9, 0, 9 } }, whole);
  EXPECT_EQ(o.owner({ 30.2, 1, 1 }), 0);
  EXPECT_EQ(o.owner({ 31.9, 1, 1 }), 1);
  const PieceOwnership none({ { 0, -1, 0, -1, 0, -1 } }, whole);
  EXPECT_EQ(none.owner({ 1, 1, 1 }), -1);
}

TEST(GhostMarginRule, GrowsWithTheRadiusTheSpurRuleAndTheVesselnessScale)
{
  vtouch::GhostMarginRule rule;
  rule.largestRadius_mm = 2.0;
  // 7 R + 1 voxel = 15 mm on 1 mm voxels, + 2.
  EXPECT_EQ(rule.voxels({ 1.0, 1.0, 1.0 }), 17);
  rule.minimumBranchLength = 10.0; // (10 + 1) R = 22 mm
  EXPECT_EQ(rule.voxels({ 1.0, 1.0, 1.0 }), 24);
  rule.useVesselness = true;
  rule.vesselnessSigmaMaximum_mm = 1.0; // + 3 mm
  EXPECT_EQ(rule.voxels({ 1.0, 1.0, 1.0 }), 27);
  EXPECT_EQ(rule.voxels({ 0.5, 1.0, 2.0 }), 52); // in voxels of the smallest spacing
}

TEST(GrownExtent, GrowsOnlySharedFacesAndStaysInTheWholeExtent)
{
  const VoxelExtent6 whole{ 0, 63, 0, 63, 0, 63 };
  const VoxelExtent6 grown = vtouch::grownExtent({ 0, 32, 0, 63, 20, 40 }, whole, 10);
  EXPECT_EQ(grown, (VoxelExtent6{ 0, 42, 0, 63, 10, 50 }));
  EXPECT_EQ(vtouch::grownExtent({ 0, 32, 0, 63, 0, 63 }, whole, 100), whole);
}

TEST(SkeletonFragmentCodec, RoundTripsExactlyAndRefusesBadArrays)
{
  vtouch::SkeletonFragment f;
  f.piece = 3;
  f.head.kind = vtouch::FragmentEnd::Kind::Cut;
  f.head.position_World_mm = { 1.25, -2.5, 3.125 };
  f.head.neighbourPiece = 1;
  f.tail.kind = vtouch::FragmentEnd::Kind::Attached;
  f.tail.position_World_mm = { 0.1, 0.2, 0.3 };
  for (int i = 0; i < 4; ++i)
  {
    vtouch::SkeletonPoint p;
    p.position_World_mm = { 0.1 * i, 1.0 / 3.0, -7.0 };
    p.tangent_World = { 1, 0, 0 };
    p.radius_mm = 1.5 + i;
    p.curvature_per_mm = 0.01 * i;
    p.torsion_per_mm = -0.02;
    p.label = i == 3 ? vtouch::PointLabel::Bifurcation : vtouch::PointLabel::Ordinary;
    f.points.push_back(p);
  }
  const std::vector<double> data = vtouch::SkeletonFragmentCodec::encode({ f, f });
  std::vector<vtouch::SkeletonFragment> back;
  std::string error;
  ASSERT_TRUE(vtouch::SkeletonFragmentCodec::decode(data.data(), data.size(), back, error))
    << error;
  ASSERT_EQ(back.size(), 2u);
  EXPECT_EQ(back[1].piece, 3);
  EXPECT_EQ(back[1].head.neighbourPiece, 1);
  EXPECT_EQ(back[1].tail.kind, vtouch::FragmentEnd::Kind::Attached);
  ASSERT_EQ(back[1].points.size(), 4u);
  EXPECT_EQ(back[1].points[3].position_World_mm.x, f.points[3].position_World_mm.x);
  EXPECT_EQ(back[1].points[1].position_World_mm.y, 1.0 / 3.0);
  EXPECT_EQ(back[1].points[3].label, vtouch::PointLabel::Bifurcation);
  // Truncated, with trailing values, or with an impossible label: refused with a reason.
  back.clear();
  EXPECT_FALSE(vtouch::SkeletonFragmentCodec::decode(data.data(), data.size() - 3, back, error));
  EXPECT_FALSE(error.empty());
  std::vector<double> longer = data;
  longer.push_back(0.0);
  EXPECT_FALSE(vtouch::SkeletonFragmentCodec::decode(longer.data(), longer.size(), back, error));
  std::vector<double> badLabel = data;
  badLabel.back() = 7.0;
  EXPECT_FALSE(
    vtouch::SkeletonFragmentCodec::decode(badLabel.data(), badLabel.size(), back, error));
  EXPECT_FALSE(vtouch::SkeletonFragmentCodec::decode(nullptr, 0, back, error));
}
} // namespace

// BlobCrossingBridge on hand-made networks (1 mm voxels): a thin vessel's path pulled into a
// blob's centre goes back onto the chord between the tube on either side; a path joined inside
// the run keeps its place on the parent; a thin vessel through a plate, with the tube on both
// sides, goes on its chord too; plates at a junction's zone, runs without a tube on one side,
// runs longer than a blob and runs with a path joined inside them are left as they are.
#include "vtouchBlobCrossingBridge.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <vector>

using namespace vtouch;

namespace
{
using Section = BlobCrossingBridge::Section;

/// A path along x (points every mm, radius 1 mm), with its points first..last pulled `off_mm`
/// along y (the coder's centre in a blob) and their sections `blob_voxels` wide; the others
/// are tube-like, 1 voxel wide.
struct Scene
{
  QSkeleton skeleton;
  BlobCrossingBridge::Sections sections;

  Scene(int n, int first, int last, double off_mm, double blob_voxels)
  {
    SkeletonPath path;
    path.id = 0;
    std::vector<Section> judged;
    std::vector<double> width;
    for (int k = 0; k < n; ++k)
    {
      SkeletonPoint p;
      const bool inBlob = k >= first && k <= last;
      p.position_World_mm = Vec3{ static_cast<double>(k), inBlob ? off_mm : 0.0, 0.0 };
      p.tangent_World = Vec3{ 1, 0, 0 };
      p.radius_mm = inBlob ? 3.0 : 1.0;
      path.points.push_back(p);
      judged.push_back(Section::TubeLike);
      width.push_back(inBlob ? blob_voxels : 1.0);
    }
    path.points.front().label = PointLabel::EndPoint;
    path.points.back().label = PointLabel::EndPoint;
    skeleton.paths.push_back(path);
    sections.judged.push_back(judged);
    sections.width_voxels.push_back(width);
  }

  /// A second path, joined by its head to point `at` of path 0.
  void joinChild(int at)
  {
    SkeletonPath child;
    child.id = static_cast<int>(skeleton.paths.size());
    for (int k = 0; k < 6; ++k)
    {
      SkeletonPoint p;
      p.position_World_mm =
        skeleton.paths[0].points[static_cast<std::size_t>(at)].position_World_mm +
        Vec3{ 0, 0, static_cast<double>(k) };
      p.tangent_World = Vec3{ 0, 0, 1 };
      p.radius_mm = 1.0;
      child.points.push_back(p);
    }
    Junction j;
    j.childPath = child.id;
    j.childEnd = Junction::End::Head;
    j.parentPath = 0;
    j.parentPoint = at;
    child.head.junction = static_cast<int>(skeleton.junctions.size());
    skeleton.junctions.push_back(j);
    skeleton.paths[0].points[static_cast<std::size_t>(at)].label = PointLabel::Bifurcation;
    skeleton.paths.push_back(child);
    sections.judged.emplace_back(6, Section::TubeLike);
    sections.width_voxels.emplace_back(6, 1.0);
  }

  /// Path 0's head joined to a new parent path (3 mm radius, across x = 0), its first `zone`
  /// points unjudged (the junction's zone).
  void joinHeadToParent(int zone)
  {
    for (int k = 0; k < zone; ++k)
    {
      sections.judged[0][static_cast<std::size_t>(k)] = Section::Unjudged;
    }
    SkeletonPath parent;
    parent.id = static_cast<int>(skeleton.paths.size());
    for (int k = -5; k <= 5; ++k)
    {
      SkeletonPoint p;
      p.position_World_mm = Vec3{ 0, static_cast<double>(k), 0 };
      p.tangent_World = Vec3{ 0, 1, 0 };
      p.radius_mm = 3.0;
      parent.points.push_back(p);
    }
    Junction j;
    j.childPath = 0;
    j.childEnd = Junction::End::Head;
    j.parentPath = parent.id;
    j.parentPoint = 5;
    skeleton.paths[0].head.junction = static_cast<int>(skeleton.junctions.size());
    skeleton.junctions.push_back(j);
    skeleton.paths.push_back(parent);
    sections.judged.emplace_back(11, Section::TubeLike);
    sections.width_voxels.emplace_back(11, 3.0);
  }

  /// Points from..to of path 0 in a plate's band.
  void plate(int from, int to)
  {
    for (int k = from; k <= to; ++k)
    {
      sections.judged[0][static_cast<std::size_t>(k)] = Section::NotTubeLike;
    }
  }

  double farthestOffAxis_mm() const
  {
    double far = 0.0;
    for (const SkeletonPoint& p : skeleton.paths[0].points)
    {
      far = std::max(far, std::hypot(p.position_World_mm.y, p.position_World_mm.z));
    }
    return far;
  }
};

constexpr double kVoxel_mm = 1.0;
} // namespace

TEST(BlobCrossingBridge, ThinVesselThroughABlobGoesOnTheChordBetweenItsTubes)
{
  Scene scene(30, 10, 16, 3.0, 4.0);
  scene.joinChild(24); // beyond the run: its index moves with the new points
  const Vec3 joinedAt = scene.skeleton.paths[0].points[24].position_World_mm;
  std::vector<std::array<int, 3>> replaced;
  const int bridged = BlobCrossingBridge::bridge(scene.skeleton,
    scene.sections,
    kVoxel_mm,
    {},
    [&](std::size_t path, int first, int count, int inserted)
    {
      EXPECT_EQ(path, 0u);
      replaced.push_back({ first, count, inserted });
    });
  ASSERT_EQ(bridged, 1);
  ASSERT_EQ(replaced.size(), 1u);
  EXPECT_EQ(replaced[0][0], 10);
  EXPECT_EQ(replaced[0][1], 7);
  EXPECT_EQ(replaced[0][2], 7); // points 9 and 17 are 8 mm apart: 7 points in between, 1 mm apart
  const SkeletonPath& path = scene.skeleton.paths[0];
  ASSERT_EQ(path.points.size(), 30u);
  EXPECT_LT(scene.farthestOffAxis_mm(), 1e-9);
  for (int k = 10; k <= 16; ++k)
  {
    const SkeletonPoint& p = path.points[static_cast<std::size_t>(k)];
    EXPECT_NEAR(p.position_World_mm.x, static_cast<double>(k), 1e-9);
    EXPECT_NEAR(p.tangent_World.x, 1.0, 1e-12);
    EXPECT_NEAR(p.radius_mm, 1.0, 1e-12) << "the tube's radius, not the blob's";
    EXPECT_EQ(scene.sections.judged[0][static_cast<std::size_t>(k)], Section::TubeLike);
    EXPECT_NEAR(scene.sections.width_voxels[0][static_cast<std::size_t>(k)], 1.0, 1e-12);
  }
  const Junction& j = scene.skeleton.junctions[0];
  const Vec3 parentPoint = path.points[static_cast<std::size_t>(j.parentPoint)].position_World_mm;
  EXPECT_NEAR((parentPoint - joinedAt).norm(), 0.0, 1e-12);
  EXPECT_EQ(path.points[static_cast<std::size_t>(j.parentPoint)].label, PointLabel::Bifurcation);
  // A second run changes nothing.
  EXPECT_EQ(BlobCrossingBridge::bridge(scene.skeleton, scene.sections, kVoxel_mm, {}), 0);
}

TEST(BlobCrossingBridge, BranchEnteringABlobFromItsJunctionIsBridgedFromTheZone)
{
  // A child path whose head zone (unjudged) reaches the run: the zone's last point anchors it.
  Scene scene(20, 3, 8, 3.0, 4.0);
  scene.joinChild(15); // a path on the tube beyond the run
  scene.joinHeadToParent(3);
  ASSERT_EQ(BlobCrossingBridge::bridge(scene.skeleton, scene.sections, kVoxel_mm, {}), 1);
  EXPECT_LT(scene.farthestOffAxis_mm(), 1e-9);
  EXPECT_EQ(scene.skeleton.paths[0].points.size(), 20u);
}

TEST(BlobCrossingBridge, TheTubeSideGoesOnAcrossABranchsJunctionZone)
{
  // A thin vessel leaves the blob and a branch leaves it one point later (128^3 seed 47 noise
  // 35, session 20): one tube-like point, the branch's junction zone, then the tube again. The
  // zone does not end the tube; before session 20 the run was kept (15 points 2-5 voxels off).
  Scene scene(30, 10, 16, 3.0, 4.0);
  scene.joinChild(19);
  for (int k = 18; k <= 20; ++k)
  {
    scene.sections.judged[0][static_cast<std::size_t>(k)] = Section::Unjudged;
  }
  ASSERT_EQ(BlobCrossingBridge::bridge(scene.skeleton, scene.sections, kVoxel_mm, {}), 1);
  EXPECT_LT(scene.farthestOffAxis_mm(), 1e-9);
  EXPECT_EQ(scene.skeleton.junctions[0].parentPoint, 19) << "the branch stays where it joined";
}

TEST(BlobCrossingBridge, AThinVesselThroughAPlateGoesOnTheChordWhenTheTubeGoesOnBothSides)
{
  // 128^3 seed 44 noise 35 (session 20): a vessel of radius 0.91 runs along a plate's face, and
  // the coder's path dips 2-3 voxels into the plate over 15 points, 13 of them in its band. Its
  // path along the plate is 20.5 voxels long, its chord 16: the chord is what the bridge draws.
  Scene scene(30, 10, 16, 3.0, 4.0);
  scene.plate(10, 15);
  for (int k = 10; k <= 16; ++k)
  {
    // A zigzag, 2 mm either side along z, as the coder's path wanders over a plate: about 32 mm
    // along the path from point 9 to point 17, more than 3 x 4 + 2 mm; the chord is 8 mm.
    scene.skeleton.paths[0].points[static_cast<std::size_t>(k)].position_World_mm.z =
      k % 2 ? 2.0 : -2.0;
  }
  ASSERT_EQ(BlobCrossingBridge::bridge(scene.skeleton, scene.sections, kVoxel_mm, {}), 1);
  EXPECT_LT(scene.farthestOffAxis_mm(), 1e-9);
  // Where the tube does not go on on one side (a junction's zone there), a plate stays for the
  // pruner's plate rules.
  Scene zone(20, 3, 8, 3.0, 4.0);
  zone.joinHeadToParent(3);
  zone.plate(3, 6);
  EXPECT_EQ(BlobCrossingBridge::bridge(zone.skeleton, zone.sections, kVoxel_mm, {}), 0);
}

TEST(BlobCrossingBridge, PlatesShortTubesLongRunsAndJoinedRunsAreKept)
{
  struct Case
  {
    const char* what;
    int n, first, last;
    double blob_voxels;
    std::function<void(Scene&)> change;
  };
  const std::vector<Case> cases{
    { "two tube-like points after the run (a plate's face, or noise): no tube there",
      19,
      10,
      16,
      4.0,
      nullptr },
    { "one tube-like point, then a junction's zone to the path's end: no tube there",
      20,
      10,
      16,
      4.0,
      [](Scene& scene)
      {
        scene.sections.judged[0][18] = Section::Unjudged;
        scene.sections.judged[0][19] = Section::Unjudged;
      } },
    { "a tube side broken by a plate's section",
      30,
      10,
      16,
      4.0,
      [](Scene& scene) { scene.plate(18, 18); } },
    { "not wider than the tube by the blob criterion", 30, 10, 16, 1.9, nullptr },
    { "longer than a blob: 3 x its widest section + 2 voxels", 40, 5, 25, 4.0, nullptr },
    { "another path joined inside the run",
      30,
      10,
      16,
      4.0,
      [](Scene& scene) { scene.joinChild(13); } },
    { "two points wide: noise, not a blob", 30, 10, 11, 4.0, nullptr },
  };
  for (const Case& c : cases)
  {
    SCOPED_TRACE(c.what);
    Scene scene(c.n, c.first, c.last, 3.0, c.blob_voxels);
    if (c.change)
    {
      c.change(scene);
    }
    EXPECT_EQ(BlobCrossingBridge::bridge(scene.skeleton, scene.sections, kVoxel_mm, {}), 0);
  }
}

#include "vtouchHapticsTestUtilities.h"
#include "vtouchViewModel.h"
#include "vtouchViewModelBuilder.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace vtouch
{
namespace
{
using namespace vtouch::testing;

TEST(HostCamera, OrthographicMapsFocalPointToViewportCentre)
{
  const HostCamera cam = topCamera({ 10, 20, 30 }, 0.25);
  Vec2 s;
  ASSERT_TRUE(cam.eyeToScreen(cam.worldToEye({ 10, 20, 30 }), s));
  EXPECT_NEAR(s.x, 400.0, 1e-9);
  EXPECT_NEAR(s.y, 300.0, 1e-9);
  ASSERT_TRUE(cam.eyeToScreen(cam.worldToEye({ 11, 21, 30 }), s));
  EXPECT_NEAR(s.x, 404.0, 1e-9); // 0.25 mm per pixel, x right
  EXPECT_NEAR(s.y, 304.0, 1e-9); // y up
  EXPECT_NEAR(cam.mmPerPixelAt(123.0), 0.25, 1e-12);
  EXPECT_STREQ(cam.validate(), "");
}

TEST(HostCamera, PerspectiveScaleGrowsWithDistance)
{
  HostCamera cam;
  cam.view_WorldToEye = lookAt({ 0, 0, 100 }, { 0, 0, 0 }, { 0, 1, 0 });
  cam.projection_EyeToClip = perspective(30.0, 800.0 / 600.0, 1.0, 1000.0);
  const double near = cam.mmPerPixelAt(50.0);
  const double far = cam.mmPerPixelAt(100.0);
  EXPECT_NEAR(far / near, 2.0, 1e-12);
  Vec2 s;
  ASSERT_TRUE(cam.eyeToScreen(cam.worldToEye({ 0, 0, 0 }), s));
  EXPECT_NEAR(s.x, 400.0, 1e-9);
  EXPECT_FALSE(cam.eyeToScreen(cam.worldToEye({ 0, 0, 200 }), s)); // behind the camera
}

TEST(ViewModelBuilder, SlopeEqualsTanBetaOnInclinedLine)
{
  // A line rising toward the viewer (+z) by 0.5 mm per mm along x: depth decreases, tan(beta) 0.5.
  const QSkeleton s = straightLine({ -20, 0, 0 }, { 20, 0, 20 }, 0.25);
  auto vm = buildView(s, topCamera({ 0, 0, 0 }));
  const int mid = vm->pointCount() / 2;
  EXPECT_NEAR(vm->dz_mm(mid) / vm->dl_mm(mid), -0.5, 1e-6);
  EXPECT_NEAR(vm->eta(mid).x, 1.0, 1e-6);
  EXPECT_NEAR(vm->eta(mid).y, 0.0, 1e-6);
  EXPECT_NEAR(vm->frameStrength(mid), 2.0 / std::sqrt(5.0), 1e-6);
  EXPECT_NEAR(vm->mmPerPixel(mid), 0.25, 1e-12);
  // Screen position and depth of the middle point (the focal point).
  EXPECT_NEAR(vm->screen_px(mid).x, 400.0, 0.5);
  EXPECT_NEAR(vm->depth_mm(mid) + 10.0, 1000.0, 0.3);
}

TEST(ViewModelBuilder, SlopeStencilKeepsTheSignOfTheDepthChangeAcrossACorner)
{
  // A flat vessel along +x meets a rise toward the viewer at `deg` degrees to the screen plane,
  // then goes on flat (0.25 mm sampling, 1 mm stencil). Around both corners every point's depth
  // change dz along increasing index is <= 0 and its projected tangent points along +x: the
  // Richardson extrapolation overshot there before (dz > 0 on the flat side, eta along -x on the
  // rise side: a slope force of the wrong sign), and is faded out where the chords disagree.
  // Away from the corners the slope is exact (0 on the flats, tan(deg) on the rise).
  for (double deg : { 30.0, 60.0, 89.0 })
  {
    const double beta = deg * kPi / 180.0;
    const Vec3 up{ std::cos(beta), 0.0, std::sin(beta) };
    QSkeleton s;
    SkeletonPath path;
    auto add = [&path](const Vec3& p, const Vec3& t)
    {
      SkeletonPoint q;
      q.position_World_mm = p;
      q.tangent_World = t;
      path.points.push_back(q);
    };
    for (int i = -20; i < 0; ++i)
    {
      add({ 0.25 * i, 0, 0 }, { 1, 0, 0 });
    }
    for (int i = 0; i < 40; ++i)
    {
      add(up * (0.25 * i), up);
    }
    for (int i = 0; i <= 20; ++i)
    {
      add(up * 10.0 + Vec3{ 0.25 * i, 0, 0 }, { 1, 0, 0 });
    }
    s.paths.push_back(path);
    auto vm = buildView(s, topCamera({ 0, 0, 0 }));
    for (int g = 0; g < vm->pointCount(); ++g)
    {
      EXPECT_LE(vm->dz_mm(g), 1e-12) << deg << " point " << g;
      EXPECT_GT(vm->eta(g).x, 0.99) << deg << " point " << g;
    }
    EXPECT_NEAR(vm->dz_mm(10), 0.0, 1e-12);                            // the first flat
    EXPECT_NEAR(-vm->dz_mm(40) / vm->dl_mm(40), std::tan(beta), 1e-6); // the rise
    EXPECT_NEAR(vm->dz_mm(70), 0.0, 1e-12);                            // the second flat
  }
}

TEST(ViewModelBuilder, ContactMapMatchesBruteForceNearestSplat)
{
  std::mt19937 rng(12345);
  std::uniform_real_distribution<double> u(-40.0, 40.0);
  QSkeleton s;
  for (int p = 0; p < 5; ++p)
  {
    const Vec3 a{ u(rng), u(rng), u(rng) };
    const Vec3 b{ u(rng), u(rng), u(rng) };
    QSkeleton line = straightLine(a, b, 2.0); // sparse: splats are isolated pixels
    line.paths[0].id = p;
    s.paths.push_back(line.paths[0]);
  }
  const HostCamera cam = topCamera({ 0, 0, 0 }, 0.25, 200, 160);
  const double radius = 6.0;
  auto vm = buildView(s, cam, radius);
  // Brute force: seed pixels with the nearest-in-depth point.
  std::vector<int> seed(200 * 160, -1);
  for (int g = 0; g < vm->pointCount(); ++g)
  {
    const Vec2 p = vm->screen_px(g);
    if (p.x < 0 || p.y < 0 || p.x >= 200 || p.y >= 160)
    {
      continue;
    }
    int& k = seed[static_cast<int>(p.y) * 200 + static_cast<int>(p.x)];
    if (k < 0 || vm->depth_mm(g) < vm->depth_mm(k))
    {
      k = g;
    }
  }
  int checked = 0;
  for (int y = 0; y < 160; ++y)
  {
    for (int x = 0; x < 200; ++x)
    {
      double best = 1e300;
      for (int k = 0; k < 200 * 160; ++k)
      {
        if (seed[k] >= 0)
        {
          const double dx = x - k % 200;
          const double dy = y - k / 200;
          best = std::min(best, dx * dx + dy * dy);
        }
      }
      const int g = vm->contactAt(x, y);
      if (best > radius * radius)
      {
        EXPECT_EQ(g, -1) << x << "," << y;
        continue;
      }
      ASSERT_GE(g, 0) << x << "," << y;
      const Vec2 p = vm->screen_px(g);
      const double dx = x - std::floor(p.x);
      const double dy = y - std::floor(p.y);
      EXPECT_NEAR(dx * dx + dy * dy, best, 1e-9) << x << "," << y;
      ++checked;
    }
  }
  EXPECT_GT(checked, 1000);
  EXPECT_EQ(vm->contactAt(-1, 0), -1);
  EXPECT_EQ(vm->contactAt(0, 160), -1);
}

TEST(ViewModelBuilder, ContactMapPrefersNearestInDepthWhereVesselsOverlap)
{
  // Two lines crossing on screen: the x line is in front (z = +10, closer to the viewer).
  QSkeleton s = straightLine({ -20, 0, 10 }, { 20, 0, 10 }, 0.25);
  QSkeleton back = straightLine({ 0, -20, -10 }, { 0, 20, -10 }, 0.25);
  back.paths[0].id = 1;
  s.paths.push_back(back.paths[0]);
  auto vm = buildView(s, topCamera({ 0, 0, 0 }));
  const int g = vm->contactAt(400, 300);
  ASSERT_GE(g, 0);
  EXPECT_EQ(vm->topology().pathOf(g), 0);
  // Away from the crossing each line owns its own neighbourhood.
  EXPECT_EQ(vm->topology().pathOf(vm->contactAt(400, 340)), 1);
  EXPECT_EQ(vm->topology().pathOf(vm->contactAt(440, 300)), 0);
}

TEST(ViewModelBuilder, RecycledSnapshotIsRebuiltInPlace)
{
  const QSkeleton s = straightLine({ -20, 0, 0 }, { 20, 0, 0 }, 0.25);
  ViewModelBuilder b;
  auto topo = SceneTopology::build(s, 1.0);
  auto first = b.build(topo, topCamera({ 0, 0, 0 }));
  ViewModel* address = first.get();
  const std::uint64_t g1 = first->generation();
  auto second = b.build(topo, topCamera({ 5, 0, 0 }), std::move(first));
  EXPECT_EQ(second.get(), address);
  EXPECT_GT(second->generation(), g1);
  EXPECT_NEAR(second->screen_px(second->pointCount() / 2).x, 380.0, 0.5);
}

TEST(SceneTopology, JunctionsAndLoopsAreGraphEdges)
{
  QSkeleton s = straightLine({ 0, 0, 0 }, { 10, 0, 0 }, 1.0); // path 0: 11 points
  QSkeleton b = straightLine({ 5, 1, 0 }, { 5, 10, 0 }, 1.0); // path 1
  b.paths[0].id = 1;
  s.paths.push_back(b.paths[0]);
  join(s, 1, Junction::End::Head, 0, 5);
  join(s, 0, Junction::End::Tail, 0, 0); // close path 0 into a loop
  ASSERT_EQ(s.validate(), "");
  auto topo = SceneTopology::build(s, 1.0);
  int nb[8];
  ASSERT_EQ(topo->neighbours(5, nb, 8), 3);
  EXPECT_EQ(nb[2], topo->globalIndex(1, 0));
  ASSERT_EQ(topo->neighbours(10, nb, 8), 2); // the tail wraps to the head
  EXPECT_EQ(nb[1], 0);
  EXPECT_EQ(topo->maxDegree(), 3);
  EXPECT_EQ(topo->pathOf(topo->globalIndex(1, 3)), 1);
  EXPECT_EQ(topo->pointOf(topo->globalIndex(1, 3)), 3);
}

TEST(SceneTopology, BifurcationOffsetIsSignedArcToTheNearestBranchOfThePath)
{
  // Path 0 along x (0..20 mm, 1 mm apart); path 1 joins point 5, path 2 joins point 15; path 0
  // also closes on its own end, which is no branch.
  QSkeleton s = straightLine({ 0, 0, 0 }, { 20, 0, 0 }, 1.0);
  for (int k = 1; k <= 2; ++k)
  {
    QSkeleton b = straightLine({ 10.0 * k - 5.0, 1, 0 }, { 10.0 * k - 5.0, 10, 0 }, 1.0);
    b.paths[0].id = k;
    s.paths.push_back(b.paths[0]);
    join(s, k, Junction::End::Head, 0, 10 * k - 5);
  }
  join(s, 0, Junction::End::Tail, 0, 0);
  ASSERT_EQ(s.validate(), "");
  auto topo = SceneTopology::build(s, 1.0);
  EXPECT_TRUE(topo->isBifurcation(5));
  EXPECT_TRUE(topo->isBifurcation(15));
  EXPECT_TRUE(topo->isBifurcation(topo->globalIndex(1, 0))); // the child's joining end
  EXPECT_FALSE(topo->isBifurcation(0));                      // the loop closure
  EXPECT_FALSE(topo->isBifurcation(20));
  EXPECT_NEAR(topo->pathArc_mm(12), 12.0, 1e-12);
  // Signed: negative before a branch (toward increasing index), positive after it; the nearer
  // branch wins, between points too.
  EXPECT_NEAR(topo->bifurcationOffset_mm(3, 4, 0.5), -1.5, 1e-12);
  EXPECT_NEAR(topo->bifurcationOffset_mm(7, -1, 0.0), 2.0, 1e-12);
  EXPECT_NEAR(topo->bifurcationOffset_mm(11, 10, 0.25), -4.25, 1e-12); // backward edge: 10.75
  EXPECT_NEAR(topo->bifurcationOffset_mm(19, 20, 0.0), 4.0, 1e-12);
  // On the child, the branch is its own joined end; on a junction edge the agent is at it.
  EXPECT_NEAR(topo->bifurcationOffset_mm(topo->globalIndex(1, 2), -1, 0.0), 2.0, 1e-12);
  EXPECT_EQ(topo->bifurcationOffset_mm(5, topo->globalIndex(1, 0), 0.5), 0.0);
  // A path without branches has none.
  auto lone = SceneTopology::build(straightLine({ 0, 0, 0 }, { 5, 0, 0 }, 1.0), 1.0);
  EXPECT_TRUE(std::isnan(lone->bifurcationOffset_mm(2, 3, 0.5)));
}

} // namespace
} // namespace vtouch

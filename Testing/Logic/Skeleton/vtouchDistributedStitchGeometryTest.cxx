// The distributed run's geometry against the single run (issue 19 item 2, h19q): the filter's
// distributed path with ranks as threads (vtouchDistributedStitchRun.h: the global SS field,
// the clip to the owned box and its band, the stitch) on ClientServer.DistributedExtraction's Y
// and ClientServer.VesselAlongPieceFace's tubes; each rank's own skeleton and the stitched one
// compared point by point with the single run's (as vtouch_skeleton_graph does through a
// pvserver: these reproduce the pvserver's numbers, 0.581 and 0.121 voxel).
//
// Asserted: the Y on 2 and 4 pieces and the tubes along a face are the single run's within 0.1
// voxel (the Y on 4 pieces departed by 0.581 voxel until the face tips' order across the pieces,
// DistributedFaceTips, h19n; the tubes by 0.121 until the clusters' shared numbering), and where
// the stitched skeleton departs at all, the rank owning the point coded it so (the stitch adds no
// departure of its own). Docs/CLIENT-SERVER.md, "Where the distributed geometry departs".
#include "vtouchDistributedStitchRun.h"
#include "vtouchStitchRunExpectations.h"

#include "vtouchPieceOwnership.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

namespace vtouch
{
namespace
{
constexpr double kTolerance_voxels = 0.1; // the 0.1 voxel (1 mm voxels here)

PhantomSpec phantom128(PhantomShape shape)
{
  PhantomSpec spec;
  spec.shape = shape;
  spec.dimensions = { 128, 128, 128 };
  spec.radiusFraction = 0.025; // 3.2 voxels: ClientServer.DistributedExtraction's
  return spec;
}

/// The filter's ghost margin for LargestVesselRadius `radius_mm` (1 mm voxels).
int ghostFor(double radius_mm)
{
  GhostMarginRule rule;
  rule.largestRadius_mm = radius_mm;
  return rule.voxels({ 1.0, 1.0, 1.0 });
}

double nearest_mm(const Vec3& p, const QSkeleton& s)
{
  double best = 1e300;
  for (const SkeletonPath& path : s.paths)
  {
    for (const SkeletonPoint& q : path.points)
    {
      best = std::min(best, (p - q.position_World_mm).norm());
    }
  }
  return best;
}

/// `s` as text: a line "path P head H tail T" per path (H, T: junction or -1), then a line
/// "P I x y z radius" per point, then "junction J child C end E parent P point I" per junction.
void dumpSkeleton(const std::string& file, const QSkeleton& s)
{
  std::ofstream out(file);
  for (std::size_t p = 0; p < s.paths.size(); ++p)
  {
    const SkeletonPath& path = s.paths[p];
    out << "path " << p << " head " << path.head.junction << " tail " << path.tail.junction << "\n";
    for (std::size_t i = 0; i < path.points.size(); ++i)
    {
      const SkeletonPoint& q = path.points[i];
      out << p << ' ' << i << ' ' << q.position_World_mm.x << ' ' << q.position_World_mm.y << ' '
          << q.position_World_mm.z << ' ' << q.radius_mm << "\n";
    }
  }
  for (std::size_t j = 0; j < s.junctions.size(); ++j)
  {
    const Junction& k = s.junctions[j];
    out << "junction " << j << " child " << k.childPath << " end "
        << (k.childEnd == Junction::End::Head ? 0 : 1) << " parent " << k.parentPath << " point "
        << k.parentPoint << "\n";
  }
}

/// `s`'s voxel chains as text: "P I x y z cx cy cz radius" per point (whole voxel index, the
/// coder's centre before the geometry stage), after a line "path P head H tail T".
void dumpRawSkeleton(const std::string& file, const RawSkeleton& s)
{
  std::ofstream out(file);
  for (std::size_t p = 0; p < s.paths.size(); ++p)
  {
    const RawSkeletonPath& path = s.paths[p];
    out << "path " << p << " head " << path.headJunction << " tail " << path.tailJunction << "\n";
    for (std::size_t i = 0; i < path.voxels.size(); ++i)
    {
      out << p << ' ' << i << ' ' << path.voxels[i][0] << ' ' << path.voxels[i][1] << ' '
          << path.voxels[i][2] << ' ' << path.center_mm[i][0] << ' ' << path.center_mm[i][1] << ' '
          << path.center_mm[i][2] << ' ' << path.radius_mm[i] << "\n";
    }
  }
  for (std::size_t j = 0; j < s.junctions.size(); ++j)
  {
    const RawJunction& k = s.junctions[j];
    out << "junction " << j << " child " << k.childPath << " end " << (k.childTail ? 1 : 0)
        << " parent " << k.parentPath << " point " << k.parentPoint << "\n";
  }
}

/// Every stitched point beyond the tolerance from the single run is, before the whole paths'
/// smoothing, a centre of its owner's own skeleton (the stitch moved nothing there); printed
/// with its distance and owner.
void expectDeparturesAreTheOwnersCoding(const char* scene, const test::DistributedStitchRun& run)
{
  int departing = 0;
  ASSERT_EQ(run.stitched.paths.size(), run.stitchedCentres.paths.size());
  for (std::size_t pi = 0; pi < run.stitched.paths.size(); ++pi)
  {
    const SkeletonPath& path = run.stitched.paths[pi];
    ASSERT_EQ(path.points.size(), run.stitchedCentres.paths[pi].points.size());
    for (std::size_t i = 0; i < path.points.size(); ++i)
    {
      const Vec3& p = path.points[i].position_World_mm;
      const double d = nearest_mm(p, run.single);
      if (d <= kTolerance_voxels)
      {
        continue;
      }
      ++departing;
      const Vec3& centre = run.stitchedCentres.paths[pi].points[i].position_World_mm;
      const int owner = run.ownership.owner(centre);
      ASSERT_GE(owner, 0);
      const double own = nearest_mm(centre, run.pieces[static_cast<std::size_t>(owner)]);
      std::printf("%s: stitched point (%.2f, %.2f, %.2f) %.3f voxel from the single run, owned "
                  "by rank %d, %.1e from its own skeleton\n",
        scene,
        p.x,
        p.y,
        p.z,
        d,
        owner,
        own);
      EXPECT_LE(own, 1e-9) << scene << ": a departure the stitch made, not rank " << owner;
    }
  }
  std::printf("%s: %d stitched points beyond %.1f voxel; farthest %.3f / %.3f voxel (stitched "
              "from single / single from stitched)\n",
    scene,
    departing,
    kTolerance_voxels,
    test::farthestPoint_mm(run.stitched, run.single),
    test::farthestPoint_mm(run.single, run.stitched));
}

using test::expectSameNetwork;

TEST(DistributedStitchGeometry, TheYOnTwoPiecesIsTheSingleRun)
{
  const test::DistributedStitchRun run = test::runDistributedStitch(
    phantom128(PhantomShape::YBifurcation), 550.0, { 1, 1, 2 }, ghostFor(3.2));
  expectSameNetwork(run);
  EXPECT_GE(run.report.cutEndsJoined, 1); // a vessel crosses the face
  EXPECT_LE(test::farthestPoint_mm(run.stitched, run.single), kTolerance_voxels);
  EXPECT_LE(test::farthestPoint_mm(run.single, run.stitched), kTolerance_voxels);
}

TEST(DistributedStitchGeometry, TheYOnFourPiecesIsTheSingleRun)
{
  // Ranks 0 and 2 cut both branches at y = 89: by their own SS they traced the trunk's tip
  // through the junction first (0.581 voxel); with the face tips' order across the pieces they
  // trace the far branch's cut tip first, as the single run traces the tip beyond it.
  const test::DistributedStitchRun run = test::runDistributedStitch(
    phantom128(PhantomShape::YBifurcation), 550.0, { 1, 2, 2 }, ghostFor(3.2));
  expectSameNetwork(run);
  expectDeparturesAreTheOwnersCoding("Y on 4 pieces", run);
  EXPECT_LE(test::farthestPoint_mm(run.stitched, run.single), kTolerance_voxels);
  EXPECT_LE(test::farthestPoint_mm(run.single, run.stitched), kTolerance_voxels);
}

/// ClientServer.VesselAlongPieceFace's tubes (test_cs_vessel_along_face.py): radius 3, 1000
/// inside, 0 outside, 128^3.
std::vector<float> alongFaceVolume()
{
  using Line = std::vector<Vec3>;
  std::vector<Line> lines;
  const double offsets[5] = { -0.7, -0.3, 0.0, 0.3, 0.7 };
  const double turns[5] = { 8.0, 118.0, 8.0, 118.0, 8.0 };
  for (int k = 0; k < 5; ++k)
  {
    const double y = 14.0 + 19.0 * k, z = 63.0 + offsets[k];
    lines.push_back({ { 14.0, y, z }, { 96.0, y, z }, { 112.0, y, turns[k] } });
  }
  lines.push_back({ { 56.0, 90.0, 63.7 }, { 44.0, 90.0, 92.0 } });
  lines.push_back({ { 10.0, 116.0, 8.0 },
    { 22.0, 116.0, 45.0 },
    { 104.0, 116.0, 70.0 },
    { 116.0, 116.0, 118.0 } });
  const int n = 128;
  std::vector<float> v(std::size_t(n) * n * n, 0.0f);
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
      {
        const Vec3 p{ double(i), double(j), double(k) };
        bool inside = false;
        for (std::size_t li = 0; li < lines.size(); ++li)
          for (std::size_t s = 0; s + 1 < lines[li].size() && !inside; ++s)
          {
            const Line& l = lines[li];
            const Vec3 ab = l[s + 1] - l[s];
            const double t = std::clamp((p - l[s]).dot(ab) / ab.dot(ab), 0.0, 1.0);
            inside = (p - (l[s] + ab * t)).norm() <= 3.0;
          }
        v[std::size_t(i + n * (j + n * k))] = inside ? 1000.0f : 0.0f;
      }
  return v;
}

TEST(DistributedStitchGeometry, VesselsAlongAFaceAreTheSingleRunsAsOnOnePiece)
{
  const std::vector<float> volume = alongFaceVolume();
  const test::DistributedStitchRun two =
    test::runDistributedStitch(volume, { 128, 128, 128 }, 550.0, { 1, 1, 2 }, ghostFor(3.0));
  expectSameNetwork(two);
  EXPECT_GE(two.report.duplicatesRemoved, 1); // the tubes along the face were sent twice
  expectDeparturesAreTheOwnersCoding("tubes along a face, 2 pieces", two);
  // The whole volume as one piece coded with the same field: what the pieces add to the global
  // field's own coding is within the tolerance.
  const test::DistributedStitchRun one =
    test::runDistributedStitch(volume, { 128, 128, 128 }, 550.0, { 1, 1, 1 }, 0);
  std::printf("one piece with the global field: %.3f / %.3f voxel from the single run\n",
    test::farthestPoint_mm(one.stitched, one.single),
    test::farthestPoint_mm(one.single, one.stitched));
  EXPECT_LE(test::farthestPoint_mm(two.stitched, one.stitched), kTolerance_voxels);
  EXPECT_LE(test::farthestPoint_mm(one.stitched, two.stitched), kTolerance_voxels);
  // With the clusters numbered in the key order in both runs (27 Nov; 0.121 voxel before, the
  // two tubes' far ends), the global field's coding is the single run's, on one piece and on two.
  EXPECT_LE(test::farthestPoint_mm(one.stitched, one.single), kTolerance_voxels);
  EXPECT_LE(test::farthestPoint_mm(one.single, one.stitched), kTolerance_voxels);
  EXPECT_LE(test::farthestPoint_mm(two.stitched, two.single), kTolerance_voxels);
  EXPECT_LE(test::farthestPoint_mm(two.single, two.stitched), kTolerance_voxels);
}

/// A diagnostic, run by hand (not in CI: it reads a file): the departures of a volume written
/// by Utilities/bench's scaling_bench.write_tree_nrrd (raw NRRD, uint16, 1 mm voxels):
///   VESSELTOUCH_STITCH_VOLUME=tree.nrrd VESSELTOUCH_STITCH_SPLIT="1 2 2"
///     vtouchDistributedStitchGeometryTests --gtest_also_run_disabled_tests
///     --gtest_filter='*DISABLED_AVolumeFromAFile'
/// (threshold 500, the ghost margin of LargestVesselRadius 0: 10 voxels, 73). With
/// VESSELTOUCH_STITCH_DUMP=dir it also writes every skeleton as text there (single, stitched,
/// each rank's, and the single run's and each rank's coder output before ToWorld, raw*.txt:
/// whole voxel indices), to tell a coding cause (raw chains differ) from a fit cause.
TEST(DistributedStitchGeometry, DISABLED_AVolumeFromAFile)
{
  const char* path = std::getenv("VESSELTOUCH_STITCH_VOLUME");
  ASSERT_NE(path, nullptr) << "set VESSELTOUCH_STITCH_VOLUME";
  std::ifstream in(path, std::ios::binary);
  ASSERT_TRUE(in) << path;
  std::string line;
  std::array<std::int64_t, 3> dims{ 0, 0, 0 };
  while (std::getline(in, line) && !line.empty())
  {
    if (line.rfind("sizes:", 0) == 0)
    {
      std::istringstream(line.substr(6)) >> dims[0] >> dims[1] >> dims[2];
    }
  }
  ASSERT_GT(dims[0] * dims[1] * dims[2], 0);
  std::vector<std::uint16_t> raw(std::size_t(dims[0] * dims[1] * dims[2]));
  in.read(reinterpret_cast<char*>(raw.data()), std::streamsize(raw.size() * 2));
  ASSERT_TRUE(in) << "short file";
  const std::vector<float> voxels(raw.begin(), raw.end());
  std::array<int, 3> split{ 1, 1, 2 };
  if (const char* s = std::getenv("VESSELTOUCH_STITCH_SPLIT"))
  {
    std::istringstream(s) >> split[0] >> split[1] >> split[2];
  }
  const test::DistributedStitchRun run = test::runDistributedStitch(voxels, dims, 500.0, split, 73);
  expectDeparturesAreTheOwnersCoding("volume", run);
  std::printf("paths %zu / %zu, free ends %d / %d, junctions %zu / %zu (stitched / single)\n",
    run.stitched.paths.size(),
    run.single.paths.size(),
    test::freeEnds(run.stitched),
    test::freeEnds(run.single),
    run.stitched.junctions.size(),
    run.single.junctions.size());
  expectSameNetwork(run);
  std::printf("stitch: %d cut ends joined, %d unmatched, %d duplicates removed\n",
    run.report.cutEndsJoined,
    run.report.cutEndsUnmatched,
    run.report.duplicatesRemoved);
  for (const std::string& note : run.report.notes)
  {
    std::printf("  %s\n", note.c_str());
  }
  std::printf("root voxel (%lld, %lld, %lld)\n",
    static_cast<long long>(run.root[0]),
    static_cast<long long>(run.root[1]),
    static_cast<long long>(run.root[2]));
  if (const char* dir = std::getenv("VESSELTOUCH_STITCH_DUMP"))
  {
    // For tracing a departure by hand: every skeleton as text (dumpSkeleton's format).
    dumpSkeleton(std::string(dir) + "/single.txt", run.single);
    dumpSkeleton(std::string(dir) + "/stitched.txt", run.stitched);
    dumpRawSkeleton(std::string(dir) + "/rawsingle.txt", run.rawSingle);
    for (std::size_t r = 0; r < run.pieces.size(); ++r)
    {
      dumpSkeleton(std::string(dir) + "/piece" + std::to_string(r) + ".txt", run.pieces[r]);
      dumpRawSkeleton(
        std::string(dir) + "/rawpiece" + std::to_string(r) + ".txt", run.rawPieces[r]);
    }
  }
}

} // namespace
} // namespace vtouch

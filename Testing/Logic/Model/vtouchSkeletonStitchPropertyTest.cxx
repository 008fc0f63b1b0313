// A property of the distributed stitch (issue 19, item 2): random vessels, and random vessels
// with a branch, crossing the faces, edges and corners of 2, 4 and 8 pieces, each piece coding
// its own copy (shifted by a fraction of a voxel, wobbled, sampled at its own arc positions, the
// branch's junction placed up to 4 points apart along the parent): every stitched path has at
// least two points and no zero-length segment; an unbranched vessel across 2 or 4 pieces keeps
// the single-piece input's topology.
#include "vtouchStitchTestHelpers.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <random>
#include <sstream>

namespace
{
using namespace vtouch;
using namespace vtouch_test;

/// The whole extent 0..40 split at 20 along the first `axes` axes (the executive's split: the
/// layer 20 is shared).
PieceOwnership piecesSplitAlong(int axes)
{
  const VoxelExtent6 whole{ 0, 40, 0, 40, 0, 40 };
  std::vector<VoxelExtent6> pieces;
  for (int k = 0; k < (1 << axes); ++k)
  {
    VoxelExtent6 e = whole;
    for (int a = 0; a < axes; ++a)
    {
      const bool upper = (k >> a) & 1;
      e[2 * a] = upper ? 20 : 0;
      e[2 * a + 1] = upper ? 40 : 20;
    }
    pieces.push_back(e);
  }
  return PieceOwnership(pieces, whole);
}

/// A smooth curve: `start`, unit `direction` turning by `turn` radians a voxel about `axis`.
struct Curve
{
  Vec3 start, direction, axis;
  double turn = 0.0;
  Vec3 at(double s) const
  {
    // Integrates the turning direction in steps of 0.05 voxel (exact enough for copies).
    Vec3 p = start, d = direction;
    const int steps = static_cast<int>(std::round(s / 0.05));
    for (int k = 0; k < steps; ++k)
    {
      p = p + d * 0.05;
      const double c = std::cos(turn * 0.05), sn = std::sin(turn * 0.05);
      d = d * c + axis.cross(d) * sn + axis * (axis.dot(d) * (1.0 - c));
    }
    return p;
  }
};

/// A piece's copy of `curve` from arc length `from` to `to`: shifted by `shift`, wobbled by
/// `wobble` along `axis`, sampled a voxel apart from `from + phase`.
std::vector<SkeletonPoint> copyOf(const Curve& curve,
  double from,
  double to,
  double phase,
  const Vec3& shift,
  double wobble)
{
  std::vector<SkeletonPoint> points;
  for (double s = from + phase; s <= to; s += 1.0)
  {
    const Vec3 p = curve.at(s) + shift + curve.axis * (wobble * std::sin(1.3 * s + 7.0 * phase));
    points.push_back(point(p.x, p.y, p.z, 1.5));
  }
  return points;
}

Vec3 randomUnit(std::mt19937& rng)
{
  std::normal_distribution<double> n(0.0, 1.0);
  Vec3 v{ n(rng), n(rng), n(rng) };
  return v * (1.0 / v.norm());
}

void expectValidPaths(const QSkeleton& s, const std::string& what)
{
  for (const SkeletonPath& p : s.paths)
  {
    EXPECT_GE(p.points.size(), 2u) << what << " path " << p.id;
    for (std::size_t i = 0; i + 1 < p.points.size(); ++i)
    {
      EXPECT_GT((p.points[i + 1].position_World_mm - p.points[i].position_World_mm).norm(),
        kCoincidentPointVoxels)
        << what << " path " << p.id << " point " << i;
    }
  }
}

TEST(SkeletonStitchProperty, RandomVesselsAcrossFacesEdgesAndCornersKeepTheirTopology)
{
  std::mt19937 rng(19);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int topologyDiffers = 0; // branched: not asserted, printed for Docs/CLIENT-SERVER.md
  int cornerStrays = 0;    // 8 pieces: stray points dropped, printed
  for (int axes = 1; axes <= 3; ++axes)
  {
    const PieceOwnership ownership = piecesSplitAlong(axes);
    const int pieces = 1 << axes;
    for (int trial = 0; trial < 60; ++trial)
    {
      const bool branched = trial % 2 == 1;
      Curve parent;
      parent.direction = randomUnit(rng);
      // Through the pieces' common edge or corner (20, 20, 20), give or take 3 voxels.
      const Vec3 centre{
        20.0 + 6.0 * unit(rng) - 3.0, 20.0 + 6.0 * unit(rng) - 3.0, 20.0 + 6.0 * unit(rng) - 3.0
      };
      const double length = 30.0;
      parent.start = centre - parent.direction * (0.5 * length);
      parent.axis = randomUnit(rng);
      parent.axis = parent.axis - parent.direction * parent.axis.dot(parent.direction);
      parent.axis = parent.axis * (1.0 / parent.axis.norm());
      parent.turn = 0.02 * unit(rng);
      Curve child;
      const double junction_s = 12.0 + 6.0 * unit(rng);
      if (branched)
      {
        // Leaves the parent at 25 .. 60 degrees.
        const double angle = (25.0 + 35.0 * unit(rng)) * 3.14159265358979 / 180.0;
        child.start = parent.at(junction_s);
        child.direction = parent.direction * std::cos(angle) + parent.axis * std::sin(angle);
        child.axis = parent.axis;
        child.turn = 0.0;
      }
      std::vector<QSkeleton> perPiece(static_cast<std::size_t>(pieces));
      for (int r = 0; r < pieces; ++r)
      {
        const Vec3 shift = randomUnit(rng) * (0.3 * unit(rng));
        const double phase = unit(rng), wobble = 0.1 * unit(rng);
        QSkeleton& s = perPiece[static_cast<std::size_t>(r)];
        s.paths.push_back(path(0, copyOf(parent, 0.0, length, phase, shift, wobble)));
        if (branched)
        {
          // The junction on the parent point nearest the branch's start, up to 4 points apart.
          const int shiftPoints = static_cast<int>(std::floor(9.0 * unit(rng))) - 4;
          const int j =
            std::clamp(static_cast<int>(std::lround(junction_s - phase)) + shiftPoints, 1, 28);
          const Vec3 onParent = s.paths[0].points[static_cast<std::size_t>(j)].position_World_mm;
          std::vector<SkeletonPoint> branch{ point(onParent.x, onParent.y, onParent.z, 1.5) };
          const double from = std::max(1.0, (onParent - child.start - shift).norm());
          for (const SkeletonPoint& q : copyOf(child, from, 14.0, phase, shift, 0.0))
          {
            branch.push_back(q);
          }
          s.paths.push_back(path(1, branch));
          attach(s, 1, Junction::End::Head, 0, j);
        }
      }
      StitchReport report;
      const QSkeleton s = clipAndStitch(perPiece, ownership, report);
      std::ostringstream what;
      what << pieces << " pieces, trial " << trial << (branched ? " (branched)" : "");
      EXPECT_EQ(s.validate(), "") << what.str();
      expectValidPaths(s, what.str());
      // The topology is asserted for an unbranched vessel across the faces, edges and corners
      // of 2, 4 and 8 pieces. Not yet for a branch whose junction each piece places up to 4
      // points apart at 25-60 degrees (35 of 90 trials with this seed: the pieces' first branch
      // points are then up to 3.5 voxels apart, not copies, and both are kept): counted and
      // printed, Docs/CLIENT-SERVER.md.
      if (branched)
      {
        const bool same = s.paths.size() == (branched ? 2u : 1u) &&
                          freeEnds(s) == (branched ? 3 : 2) && cycleRank(s) == 0;
        topologyDiffers += same ? 0 : 1;
        continue;
      }
      EXPECT_EQ(s.paths.size(), 1u) << what.str();
      EXPECT_TRUE(s.junctions.empty()) << what.str();
      EXPECT_EQ(freeEnds(s), 2) << what.str();
      EXPECT_EQ(report.pointsDropped, 0) << what.str();
      // At the corner of 8 pieces a lone kept point between three pieces' copies may find no
      // partner (1 of 30 trials): dropped as a stray, its two cut ends reported unmatched, the
      // vessel joined whole around it. Counted, printed; on faces and edges asserted absent.
      if (pieces == 8)
      {
        cornerStrays += report.strayPointsDropped;
        continue;
      }
      EXPECT_EQ(report.cutEndsUnmatched, 0) << what.str();
      EXPECT_EQ(report.strayPointsDropped, 0) << what.str();
    }
  }
  std::cout << "topology differs in " << topologyDiffers << " of the 90 trials with a branch; "
            << cornerStrays << " stray points dropped in the 30 unbranched trials of 8 pieces\n";
}
} // namespace

#include "vtouchBlobCrossingBridge.h"

#include <algorithm>
#include <cmath>

namespace vtouch
{

namespace
{

/// One side of a run: the tube (>= minimumTubePoints consecutive judged points from `anchor`
/// away from the run), or a junction's zone reaching the path's joined end.
struct Side
{
  bool tube = false;
  bool junctionZone = false;
  double tube_voxels = 0.0;
  double radius_mm = 0.0;
};

double median(std::vector<double> v)
{
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
  return v[v.size() / 2];
}

using Section = BlobCrossingBridge::Section;

Side sideOf(const SkeletonPath& path,
  const std::vector<Section>& judged,
  const std::vector<double>& width,
  int anchor,
  int dir,
  const BlobCrossingBridge::Settings& s)
{
  Side side;
  const int n = static_cast<int>(path.points.size());
  if (anchor < 0 || anchor >= n)
  {
    return side;
  }
  // The tube's points from the anchor on. A junction's zone after the first of them is stepped
  // over: a branch leaving the tube there does not end it (128^3 seed 47 noise 35, session 20).
  std::vector<double> widths, radii;
  for (int q = anchor; q >= 0 && q < n && static_cast<int>(widths.size()) < s.tubePoints; q += dir)
  {
    const Section j = judged[static_cast<std::size_t>(q)];
    if (j == Section::Unjudged && !widths.empty())
    {
      continue;
    }
    if (j != Section::TubeLike)
    {
      break;
    }
    widths.push_back(width[static_cast<std::size_t>(q)]);
    radii.push_back(path.points[static_cast<std::size_t>(q)].radius_mm);
  }
  if (static_cast<int>(widths.size()) >= std::max(1, s.minimumTubePoints))
  {
    side.tube = true;
    side.tube_voxels = median(widths);
    side.radius_mm = median(radii);
    return side;
  }
  if (!widths.empty() || judged[static_cast<std::size_t>(anchor)] != Section::Unjudged)
  {
    return side; // a few tube-like points, or a plate's section: no tube to trust
  }
  // The anchor is unjudged: a junction's zone. It counts when it reaches the path's joined end.
  for (int q = anchor; q >= 0 && q < n; q += dir)
  {
    if (judged[static_cast<std::size_t>(q)] != Section::Unjudged)
    {
      return side;
    }
  }
  const PathEnd& end = dir < 0 ? path.head : path.tail;
  side.junctionZone = end.junction >= 0;
  return side;
}

double threshold(double tube_voxels, const BlobCrossingBridge::Settings& s)
{
  return tube_voxels + std::max(s.excess_voxels, s.excessFraction * tube_voxels);
}

} // namespace

BlobCrossingBridge::Crossing BlobCrossingBridge::findCrossing(const QSkeleton& skeleton,
  const Sections& sections,
  std::size_t pathIndex,
  int from,
  double voxel_mm,
  const Settings& s)
{
  const SkeletonPath& path = skeleton.paths[pathIndex];
  const std::vector<Section>& judged = sections.judged[pathIndex];
  const std::vector<double>& width = sections.width_voxels[pathIndex];
  const int n = static_cast<int>(path.points.size());
  // Points where another path (or a loop's other front) joins this one: never inside a bridge.
  std::vector<char> joined(static_cast<std::size_t>(n), 0);
  for (const Junction& j : skeleton.junctions)
  {
    if (j.parentPath == path.id && j.parentPoint >= 0 && j.parentPoint < n)
    {
      joined[static_cast<std::size_t>(j.parentPoint)] = 1;
    }
  }
  for (int a = std::max(1, from); a + 1 < n; ++a)
  {
    if (judged[static_cast<std::size_t>(a)] == Section::Unjudged ||
        width[static_cast<std::size_t>(a)] < s.minimumWidth_voxels)
    {
      continue;
    }
    const Side before = sideOf(path, judged, width, a - 1, -1, s);
    if (!before.tube && !before.junctionZone)
    {
      continue;
    }
    if (before.tube && !(width[static_cast<std::size_t>(a)] > threshold(before.tube_voxels, s)))
    {
      continue;
    }
    double narrowest = width[static_cast<std::size_t>(a)], widest = narrowest;
    int plate = 0;
    for (int b = a; b + 1 < n; ++b)
    {
      const double w = width[static_cast<std::size_t>(b)];
      plate += judged[static_cast<std::size_t>(b)] == Section::NotTubeLike ? 1 : 0;
      if (judged[static_cast<std::size_t>(b)] == Section::Unjudged ||
          joined[static_cast<std::size_t>(b)] || w < s.minimumWidth_voxels ||
          (before.tube && !(w > threshold(before.tube_voxels, s))))
      {
        break;
      }
      narrowest = std::min(narrowest, w);
      widest = std::max(widest, w);
      if (b - a + 1 < s.minimumRunPoints)
      {
        continue;
      }
      const Side after = sideOf(path, judged, width, b + 1, +1, s);
      if (!(after.tube || after.junctionZone) || !(before.tube || after.tube))
      {
        continue;
      }
      const double tube =
        std::max(before.tube ? before.tube_voxels : 0.0, after.tube ? after.tube_voxels : 0.0);
      // The run ends where the tube resumes: the tube's points next to it are not wide. A plate's
      // run is left to the pruner's plate rules unless the tube goes on on both sides of it (a
      // thin vessel through or along a plate, session 20).
      const double bound = threshold(tube, s);
      const bool plateRun = plate >= s.plateFraction * (b - a + 1);
      if (!(narrowest > bound) || (plateRun && !(before.tube && after.tube)) ||
          (after.tube && width[static_cast<std::size_t>(b + 1)] > bound) ||
          (before.tube && width[static_cast<std::size_t>(a - 1)] > bound))
      {
        continue;
      }
      // The chord the bridge draws, not the coder's path (which detours to the blob's centre).
      const double length_mm = (path.points[static_cast<std::size_t>(b + 1)].position_World_mm -
                                path.points[static_cast<std::size_t>(a - 1)].position_World_mm)
                                 .norm();
      if (length_mm > (s.maximumLengthWidths * widest + 2.0) * voxel_mm)
      {
        break; // longer than a blob: a plate or a wide structure (the other rules' business)
      }
      Crossing c;
      c.first = a;
      c.last = b;
      c.tube_voxels = tube;
      c.radius_mm = before.tube && after.tube ? 0.5 * (before.radius_mm + after.radius_mm)
                                              : (before.tube ? before.radius_mm : after.radius_mm);
      return c;
    }
  }
  return Crossing{};
}

int BlobCrossingBridge::replace(QSkeleton& skeleton,
  Sections& sections,
  std::size_t pathIndex,
  const Crossing& c,
  double voxel_mm)
{
  SkeletonPath& path = skeleton.paths[pathIndex];
  const Vec3 a = path.points[static_cast<std::size_t>(c.first - 1)].position_World_mm;
  const Vec3 b = path.points[static_cast<std::size_t>(c.last + 1)].position_World_mm;
  const Vec3 chord = b - a;
  const double length_mm = chord.norm();
  const int inserted =
    std::max(0, static_cast<int>(std::lround(length_mm / std::max(voxel_mm, 1e-12))) - 1);
  std::vector<SkeletonPoint> line;
  for (int q = 1; q <= inserted; ++q)
  {
    SkeletonPoint p;
    p.position_World_mm = a + chord * (static_cast<double>(q) / (inserted + 1));
    p.tangent_World = length_mm > 0.0
                        ? chord * (1.0 / length_mm)
                        : path.points[static_cast<std::size_t>(c.first)].tangent_World;
    p.radius_mm = c.radius_mm;
    line.push_back(p);
  }
  const int removed = c.last - c.first + 1;
  path.points.erase(path.points.begin() + c.first, path.points.begin() + c.last + 1);
  path.points.insert(path.points.begin() + c.first, line.begin(), line.end());
  std::vector<Section>& judged = sections.judged[pathIndex];
  judged.erase(judged.begin() + c.first, judged.begin() + c.last + 1);
  judged.insert(judged.begin() + c.first, static_cast<std::size_t>(inserted), Section::TubeLike);
  std::vector<double>& width = sections.width_voxels[pathIndex];
  width.erase(width.begin() + c.first, width.begin() + c.last + 1);
  width.insert(width.begin() + c.first, static_cast<std::size_t>(inserted), c.tube_voxels);
  for (Junction& j : skeleton.junctions)
  {
    if (j.parentPath == path.id && j.parentPoint > c.last)
    {
      j.parentPoint += inserted - removed;
    }
  }
  return inserted;
}

} // namespace vtouch

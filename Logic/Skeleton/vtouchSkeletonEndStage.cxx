// Voxel coding stage 6: where the paths end. Stubs beyond the last junction are cut, and a vessel
// that ends inside the volume ends at its cap's centre.
//
// The medial axis of a rounded end cap runs on to the cap's apex; the vessel's centerline ends at
// the cap's centre, one radius back from the apex. The points in between are dropped.
#include "vtouchSkeletonEndStage.h"

#include "vtouchSkeletonPaths.h"

#include <algorithm>
#include <cmath>
#include <optional>

namespace vtouch
{
namespace skeleton
{
namespace
{
using Point = Point_mm;

Point unit(const Point& v)
{
  const double n = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  return n > 0.0 ? Point{ v[0] / n, v[1] / n, v[2] / n } : Point{ 0.0, 0.0, 0.0 };
}

double dot(const Point& a, const Point& b)
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

Point cross(const Point& a, const Point& b)
{
  return { a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0] };
}

/// Two unit vectors perpendicular to the unit `t` and to each other.
std::pair<Point, Point> crossSectionAxes(const Point& t)
{
  const Point helper = std::abs(t[0]) < 0.9 ? Point{ 1.0, 0.0, 0.0 } : Point{ 0.0, 1.0, 0.0 };
  const Point u = unit(cross(t, helper));
  return { u, cross(t, u) };
}

/// Mean of the points `at(k)` of `path` whose distance to `end` lies in [lo, hi]; false if fewer
/// than two.
template<typename At>
bool meanInShell(const RawSkeletonPath& path,
  std::size_t count,
  const At& at,
  const Point& end,
  double lo,
  double hi,
  Point& mean)
{
  mean = { 0.0, 0.0, 0.0 };
  int n = 0;
  for (std::size_t k = 0; k < count; ++k)
  {
    const Point& c = path.center_mm[at(k)];
    const double d = std::hypot(c[0] - end[0], c[1] - end[1], c[2] - end[2]);
    if (d >= lo && d <= hi)
    {
      for (int a = 0; a < 3; ++a)
      {
        mean[a] += c[a];
      }
      ++n;
    }
  }
  for (int a = 0; a < 3; ++a)
  {
    mean[a] /= std::max(n, 1);
  }
  return n >= 2;
}

/// The vessel's radius near a free end: the median radius of the cross section (Yi & Hayward
/// §3.1: each point of the Q-skeleton carries one; here the BS code of their ref. [32], the
/// radius of the inscribed ball) of the end's points, from the end point `at(0)` in, while they
/// lie within three inscribed balls (widened by `tolerance_mm`) of the end: the points the cap
/// scan of EndStage::measureEndCap reaches with its base tolerance. It stops, as that scan does,
/// at the point before the path's other end and after a point other paths attach to (`pinned`).
/// The median, not the largest: the cap's points (BS falling toward the apex) and the first
/// points of a thicker vessel beyond are the few at either side (on the raw phantom family the
/// largest trimmed ends of thin vessels by a point more: recall r >= 0.5 -0.0008 on two cases).
/// Only points within 3 (R + tolerance) of the end are read, R the largest radius there: less
/// than the ghost margin (GhostMarginRule: 7 R + 3 voxels), so a rank that owns the end and
/// whose piece cuts the path beyond them reads the single run's radius.
template<typename At>
double radiusNearEnd(const RawSkeletonPath& path,
  std::size_t count,
  const At& at,
  const std::vector<char>& pinned,
  double tolerance_mm)
{
  const Point& end = path.center_mm[at(0)];
  std::vector<double> radii{ path.radius_mm[at(0)] };
  for (std::size_t k = 1; k + 1 < count && !pinned[at(k - 1)]; ++k)
  {
    if (distance(path.center_mm[at(k)], end) > 3.0 * (path.radius_mm[at(k)] + tolerance_mm))
    {
      break;
    }
    radii.push_back(path.radius_mm[at(k)]);
  }
  const auto middle = radii.begin() + static_cast<std::ptrdiff_t>(radii.size() / 2);
  std::nth_element(radii.begin(), middle, radii.end());
  return *middle;
}
} // namespace

EndStage::EndStage(const VoxelGrid& g,
  double minimumBranchLength_radii,
  SkeletonDraft& d,
  std::size_t first,
  const std::vector<float>* ss)
  : grid(g)
  , minimumBranchLength(minimumBranchLength_radii)
  , draft(d)
  , firstPath(first)
  , ss_mm(ss)
{
}

void EndStage::run()
{
  pruneStubEnds();
  trimClosedEnds();
}

void EndStage::pruneStubEnds()
{
  RawSkeleton& out = draft.skeleton;
  for (std::size_t p = firstPath; p < out.paths.size(); ++p)
  {
    RawSkeletonPath& path = out.paths[p];
    const int n = static_cast<int>(path.center_mm.size());
    int first = n, last = -1; // the outermost points other paths attach to
    for (const RawJunction& j : out.junctions)
    {
      if (j.parentPath == static_cast<int>(p))
      {
        first = std::min(first, j.parentPoint);
        last = std::max(last, j.parentPoint);
      }
    }
    if (last < 0)
    {
      continue;
    }
    const auto stubLength = [&](int from, int to)
    {
      double length = 0.0;
      for (int i = std::min(from, to); i < std::max(from, to); ++i)
      {
        length += distance(path.center_mm[i], path.center_mm[i + 1]);
      }
      return length;
    };
    // The root's own end: its voxel in the SS code's first band.
    const auto atRoot = [&](int end)
    {
      if (ss_mm == nullptr)
      {
        return false;
      }
      const auto& v = path.voxels[static_cast<std::size_t>(end)];
      const std::uint64_t lin = grid.linOf(v[0], v[1], v[2]);
      return grid.mask.test(lin) &&
             static_cast<double>((*ss_mm)[grid.mask.rank(lin)]) < grid.bandWidth;
    };
    const auto isStub = [&](int junctionPoint, int end)
    {
      // The vessel's radius there: the junction can be on a strand of noise on the wall.
      const double radius = std::max(nearbyRadius(path, junctionPoint),
        vesselRadiusNear(path, junctionPoint, 2.0 * grid.maxSpacing));
      const double spur = (atRoot(end) ? 1.0 : minimumBranchLength) * radius;
      return junctionPoint != end &&
             stubLength(junctionPoint, end) < std::max(spur, 2.0 * grid.bandWidth);
    };
    if (path.tailJunction < 0 && isStub(last, n - 1))
    {
      path.voxels.resize(static_cast<std::size_t>(last) + 1);
      path.center_mm.resize(static_cast<std::size_t>(last) + 1);
      path.radius_mm.resize(static_cast<std::size_t>(last) + 1);
    }
    if (path.headJunction < 0 && first < static_cast<int>(path.center_mm.size()) - 1 &&
        isStub(first, 0))
    {
      path.voxels.erase(path.voxels.begin(), path.voxels.begin() + first);
      path.center_mm.erase(path.center_mm.begin(), path.center_mm.begin() + first);
      path.radius_mm.erase(path.radius_mm.begin(), path.radius_mm.begin() + first);
      for (RawJunction& j : out.junctions)
      {
        if (j.parentPath == static_cast<int>(p))
        {
          j.parentPoint -= first;
        }
      }
    }
  }
}

double EndStage::maskValueAt(const Point& p_mm) const
{
  const std::int64_t size[3] = { grid.nx, grid.ny, grid.nz };
  std::int64_t base[3];
  double w[3];
  for (int a = 0; a < 3; ++a)
  {
    // Whole-lattice mm to the whole index and its weights (the single run's numbers on every
    // rank, VoxelGrid::first_Whole), then the mask's index.
    const double x = p_mm[a] / grid.sp[a];
    const auto baseWhole = static_cast<std::int64_t>(std::floor(x));
    w[a] = x - static_cast<double>(baseWhole);
    base[a] = baseWhole - grid.first_Whole[a];
    if (base[a] < 0 || base[a] + 1 >= size[a])
    {
      return -1.0;
    }
  }
  double value = 0.0;
  for (int corner = 0; corner < 8; ++corner)
  {
    std::int64_t index[3];
    double weight = 1.0;
    for (int a = 0; a < 3; ++a)
    {
      const int up = (corner >> a) & 1;
      index[a] = base[a] + up;
      weight *= up ? w[a] : 1.0 - w[a];
    }
    if (weight > 0.0 && grid.mask.test(grid.linOf(index[0], index[1], index[2])))
    {
      value += weight;
    }
  }
  return value;
}

double EndStage::distanceToWall(const Point& from, const Point& dir, double limit_mm) const
{
  const double step = 0.25 * grid.minSpacing;
  double previous = maskValueAt(from);
  if (previous < 0.5)
  {
    return -1.0; // not inside the vessel, or at the volume's edge
  }
  for (double s = step; s <= limit_mm; s += step)
  {
    const double value =
      maskValueAt({ from[0] + s * dir[0], from[1] + s * dir[1], from[2] + s * dir[2] });
    if (value < 0.0)
    {
      return -1.0; // the vessel is cut by the volume's edge here
    }
    if (value < 0.5)
    {
      return s - step * (0.5 - value) / (previous - value);
    }
    previous = value;
  }
  return -1.0;
}

EndStage::EndCap EndStage::measureEndCap(const RawSkeletonPath& path,
  bool fromTail,
  const std::vector<char>& pinned) const
{
  const std::size_t n = path.voxels.size();
  const auto at = [&](std::size_t k) { return fromTail ? n - 1 - k : k; };
  const Point end = path.center_mm[at(0)];
  // The medial-axis rule: the end points that lie inside the inscribed ball (BS) of a point
  // further in, widened by a tolerance for the discretisation. It answers where the cap cannot be
  // measured (below); elsewhere it misses the cap's centre by up to two voxels either way,
  // depending on how the voxels fall: BS reaches the nearest background voxel centre, half a
  // voxel beyond the wall, the end point sits inside the apex voxel, and BS dips near the cap.
  // Project rule: half a voxel (the BS of a voxel centre is the distance to the nearest
  // background voxel's centre, half a voxel beyond the wall) plus 0.1 of the vessel's radius near
  // the end (radiusNearEnd: the median BS of the points the scan below reaches with the half
  // voxel alone). A discretisation tolerance scales with the vessel where the cap is; the radius
  // at the path's middle point (until h19e) is a property of the whole path: it can be several
  // times the end's on a tapering vessel, and a rank whose piece cuts the path (a distributed
  // run) has another middle point, so it kept one point more at a free end than the single run
  // (1.62 voxels on the 112^3 raw phantom; Docs/CLIENT-SERVER.md, "Departures and what is still
  // to come").
  const double baseTolerance = 0.5 * grid.minSpacing;
  const double tolerance = baseTolerance + 0.1 * radiusNearEnd(path, n, at, pinned, baseTolerance);
  std::size_t widened = 0;
  std::size_t candidates = 1;
  double radius = path.radius_mm[at(0)];
  for (std::size_t k = 1; k + 1 < n && !pinned[at(k - 1)]; ++k)
  {
    const double d = distance(path.center_mm[at(k)], end);
    if (d > 3.0 * (path.radius_mm[at(k)] + tolerance))
    {
      break;
    }
    candidates = k + 1;
    radius = std::max(radius, path.radius_mm[at(k)]);
    widened = d <= path.radius_mm[at(k)] + tolerance ? k : widened;
  }
  if (widened == 0)
  {
    return {};
  }
  // The cap measured on the mask: the vessel's axis from the centres one to three and a half radii
  // in, then from a point on it about one and a half radii in (the mean of the centres one to two
  // radii in), the distance to the apex along the axis and the radius
  // across it, both to where the trilinear interpolation of the mask crosses one half (the wall,
  // to a fraction of a voxel in any direction; the nearest voxel's value would read diagonal
  // rays up to a voxel long). The cap's centre is one radius back from the apex. A flattened
  // cap (a vessel cut flat) gives a centre one radius in from its face: the end of the medial
  // axis there.
  Point near, far;
  if (!meanInShell(path, candidates, at, end, radius, 2.0 * radius, near) ||
      !meanInShell(path, candidates, at, end, 2.0 * radius, 3.5 * radius, far))
  {
    return { widened, std::nullopt }; // too short an end to measure
  }
  const Point axis = unit({ near[0] - far[0], near[1] - far[1], near[2] - far[2] });
  const double toApex = distanceToWall(near, axis, 4.0 * radius + 2.0 * grid.maxSpacing);
  const auto [u, v] = crossSectionAxes(axis);
  std::vector<double> across;
  for (int i = 0; i < 8; ++i)
  {
    const double angle = i * 0.25 * 3.14159265358979323846;
    const Point dir = unit({ std::cos(angle) * u[0] + std::sin(angle) * v[0],
      std::cos(angle) * u[1] + std::sin(angle) * v[1],
      std::cos(angle) * u[2] + std::sin(angle) * v[2] });
    const double d = distanceToWall(near, dir, 3.0 * radius + 2.0 * grid.maxSpacing);
    if (d > 0.0)
    {
      across.push_back(d);
    }
  }
  if (toApex <= 0.0 || across.size() < 5)
  {
    return { widened, std::nullopt }; // the cap or the lumen reaches the volume's edge
  }
  double acrossMean = 0.0;
  for (double d : across)
  {
    acrossMean += d / static_cast<double>(across.size());
  }
  const double capCentre = toApex - acrossMean; // along the axis, from `near`
  // The new end: the point on the axis nearest the cap's centre, slid along the axis onto it.
  // Toward the apex the trace leaves the axis for the voxel farthest from the root, which need
  // not be the apex (by several voxels on thick caps coded on blocks); "on the axis" allows for
  // the discretisation and for a vessel that bends (the axis is a line).
  const double offAxis = 0.5 * grid.maxSpacing + 0.1 * radius;
  EndCap cap{ widened, std::nullopt };
  double best = grid.maxSpacing; // the end moves by at most a voxel
  for (std::size_t k = 0; k < candidates; ++k)
  {
    const Point& c = path.center_mm[at(k)];
    const Point offset{ c[0] - near[0], c[1] - near[1], c[2] - near[2] };
    const double along = dot(offset, axis);
    const double lateral = std::sqrt(std::max(0.0, dot(offset, offset) - along * along));
    if (lateral <= offAxis && std::abs(along - capCentre) < best)
    {
      best = std::abs(along - capCentre);
      const double shift = capCentre - along;
      cap = { k, Point{ c[0] + shift * axis[0], c[1] + shift * axis[1], c[2] + shift * axis[2] } };
    }
  }
  return cap;
}

void EndStage::trimClosedEnds()
{
  RawSkeleton& out = draft.skeleton;
  std::vector<char> pinned;
  for (std::size_t p = firstPath; p < out.paths.size(); ++p)
  {
    RawSkeletonPath& path = out.paths[p];
    pinned.assign(path.voxels.size(), 0);
    for (const RawJunction& j : out.junctions)
    {
      if (j.parentPath == static_cast<int>(p))
      {
        pinned[j.parentPoint] = 1;
      }
    }
    if (draft.closedEnd[p][1] && path.tailJunction < 0)
    {
      const EndCap cap = measureEndCap(path, true, pinned);
      const std::size_t k = cap.trim;
      path.voxels.resize(path.voxels.size() - k);
      path.center_mm.resize(path.center_mm.size() - k);
      path.radius_mm.resize(path.radius_mm.size() - k);
      if (cap.centre_mm)
      {
        path.center_mm.back() = *cap.centre_mm;
      }
    }
    if (draft.closedEnd[p][0] && path.headJunction < 0)
    {
      const EndCap cap = measureEndCap(path, false, pinned);
      const std::size_t k = cap.trim;
      path.voxels.erase(path.voxels.begin(), path.voxels.begin() + static_cast<std::ptrdiff_t>(k));
      path.center_mm.erase(
        path.center_mm.begin(), path.center_mm.begin() + static_cast<std::ptrdiff_t>(k));
      path.radius_mm.erase(
        path.radius_mm.begin(), path.radius_mm.begin() + static_cast<std::ptrdiff_t>(k));
      if (cap.centre_mm)
      {
        path.center_mm.front() = *cap.centre_mm;
      }
      for (RawJunction& j : out.junctions)
      {
        if (j.parentPath == static_cast<int>(p))
        {
          j.parentPoint -= static_cast<int>(k);
        }
      }
    }
  }
}

} // namespace skeleton
} // namespace vtouch

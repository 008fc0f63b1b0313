#include "vtouchBranchEntry.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

namespace vtouch
{
namespace
{

// The bounds of the rule (project rules, vtouchBranchEntry.h).
constexpr double kAxisFitRadii = 1.0;            // the branch's axis: its centres over one radius
constexpr std::size_t kAxisFitMinimumPoints = 3; // ... and at least three centres
constexpr double kMeetWithinParentRadius = 0.5;  // the line meets the parent's axis
constexpr double kReachParentRadii = 4.0;        // ... within four parent radii
constexpr double kMinimumAngle_deg = 10.0;       // ... and is not along it

double distance(const Vec3& a, const Vec3& b)
{
  return (a - b).norm();
}

// The principal direction of `points` (largest eigenvector of their scatter, power iteration
// from the chord `seed`).
Vec3 principalDirection(const std::vector<Vec3>& points, Vec3 seed)
{
  Vec3 mean{ 0.0, 0.0, 0.0 };
  for (const Vec3& p : points)
  {
    mean = mean + p;
  }
  mean = mean * (1.0 / static_cast<double>(points.size()));
  std::array<std::array<double, 3>, 3> c{};
  for (const Vec3& p : points)
  {
    const Vec3 d = p - mean;
    const std::array<double, 3> v{ d.x, d.y, d.z };
    for (int r = 0; r < 3; ++r)
    {
      for (int k = 0; k < 3; ++k)
      {
        c[r][k] += v[r] * v[k];
      }
    }
  }
  Vec3 u = seed;
  for (int iteration = 0; iteration < 50; ++iteration)
  {
    const Vec3 next{ c[0][0] * u.x + c[0][1] * u.y + c[0][2] * u.z,
      c[1][0] * u.x + c[1][1] * u.y + c[1][2] * u.z,
      c[2][0] * u.x + c[2][1] * u.y + c[2][2] * u.z };
    const double n = next.norm();
    if (n <= 0.0)
    {
      break;
    }
    u = next * (1.0 / n);
  }
  return u.dot(seed) < 0.0 ? u * -1.0 : u;
}

// The parent's unit axis direction at point i (its neighbours' chord).
Vec3 parentAxis(const std::vector<SkeletonPoint>& parent, std::size_t i)
{
  const std::size_t a = i > 0 ? i - 1 : i;
  const std::size_t b = i + 1 < parent.size() ? i + 1 : i;
  const Vec3 d = parent[b].position_World_mm - parent[a].position_World_mm;
  const double n = d.norm();
  return n > 0.0 ? d * (1.0 / n) : Vec3{ 0.0, 0.0, 0.0 };
}

struct Nearest
{
  std::size_t index = 0;
  double distance_mm = std::numeric_limits<double>::infinity();
};

Nearest nearestPoint(const std::vector<SkeletonPoint>& path, const Vec3& x)
{
  Nearest best;
  for (std::size_t i = 0; i < path.size(); ++i)
  {
    const double d = distance(path[i].position_World_mm, x);
    if (d < best.distance_mm)
    {
      best = { i, d };
    }
  }
  return best;
}

// The entry of one junction's branch, or false when the rule keeps it as coded.
struct Entry
{
  std::size_t exit = 0;        // first branch centre (from the attached end) out of the tube
  std::size_t parentPoint = 0; // where the branch's axis meets the parent's
};

bool findEntry(const std::vector<SkeletonPoint>& branch, // from the attached end outward
  const std::vector<SkeletonPoint>& parent,
  std::size_t codedParentPoint,
  Entry& entry)
{
  if (branch.size() < 3 || parent.size() < 3)
  {
    return false;
  }
  // A branch hanging on an end of its parent joins two paths there: moving it would leave that
  // end free (a vessel end the network did not have).
  if (codedParentPoint == 0 || codedParentPoint + 1 == parent.size())
  {
    return false;
  }
  const double parentRadius = parent[codedParentPoint].radius_mm;
  if (!(parentRadius > 0.0))
  {
    return false;
  }
  // The first centre outside the parent's tube, within four parent radii of the attached end.
  double along = 0.0;
  std::size_t exit = 0;
  for (std::size_t k = 1; k < branch.size(); ++k)
  {
    along += distance(branch[k].position_World_mm, branch[k - 1].position_World_mm);
    if (along > kReachParentRadii * parentRadius)
    {
      return false;
    }
    const Nearest n = nearestPoint(parent, branch[k].position_World_mm);
    if (n.distance_mm >= parent[n.index].radius_mm)
    {
      exit = k;
      break;
    }
  }
  if (exit < 2)
  {
    return false; // out of the tube at once (exit 1) or never: nothing inside to replace
  }
  // The branch's own axis beyond the exit: its centres over two of its radii (three at least).
  const Vec3& start = branch[exit].position_World_mm;
  const double fitLength = kAxisFitRadii * std::max(branch[exit].radius_mm, 0.0);
  std::vector<Vec3> fit{ start };
  double fitted = 0.0;
  for (std::size_t k = exit + 1; k < branch.size(); ++k)
  {
    fitted += distance(branch[k].position_World_mm, branch[k - 1].position_World_mm);
    fit.push_back(branch[k].position_World_mm);
    if (fitted >= fitLength && fit.size() >= kAxisFitMinimumPoints)
    {
      break;
    }
  }
  if (fitted < fitLength || fit.size() < kAxisFitMinimumPoints)
  {
    return false; // too short a branch to have an axis of its own
  }
  const Vec3 chord = start - fit.back();
  if (!(chord.norm() > 0.0))
  {
    return false;
  }
  const Vec3 inward = principalDirection(fit, chord * (1.0 / chord.norm()));
  // Where that line meets the parent's axis: the parent centre closest to it, ahead of the exit
  // (an interior point: an attached parent end would change the network's topology).
  const double cosMinimum = std::cos(kMinimumAngle_deg * 3.14159265358979323846 / 180.0);
  double bestPerpendicular = std::numeric_limits<double>::infinity();
  std::size_t best = 0;
  for (std::size_t i = 1; i + 1 < parent.size(); ++i)
  {
    const Vec3 rel = parent[i].position_World_mm - start;
    const double ahead = rel.dot(inward);
    if (ahead <= 0.0)
    {
      continue;
    }
    const double perpendicular = (rel - inward * ahead).norm();
    if (perpendicular < bestPerpendicular)
    {
      bestPerpendicular = perpendicular;
      best = i;
    }
  }
  if (best == 0)
  {
    return false;
  }
  const double radiusThere = parent[best].radius_mm;
  const double ahead = (parent[best].position_World_mm - start).dot(inward);
  if (bestPerpendicular > kMeetWithinParentRadius * radiusThere ||
      ahead > kReachParentRadii * radiusThere ||
      std::abs(inward.dot(parentAxis(parent, best))) > cosMinimum)
  {
    return false;
  }
  entry = { exit, best };
  return true;
}

// The number of steps of the entry line of `length_mm`: the branch's own mean spacing over its
// first centres past the exit (its coded centres are 26-neighbours), at least one step.
std::size_t entrySegments(const std::vector<SkeletonPoint>& branch,
  std::size_t exit,
  double length_mm)
{
  double spanned = 0.0;
  std::size_t steps = 0;
  for (std::size_t k = exit + 1; k < branch.size() && steps < 4; ++k, ++steps)
  {
    spanned += distance(branch[k].position_World_mm, branch[k - 1].position_World_mm);
  }
  const double step = steps > 0 ? spanned / static_cast<double>(steps) : 0.0;
  if (!(step > 0.0) || !(length_mm > 0.0))
  {
    return 1;
  }
  return std::max<std::size_t>(1, static_cast<std::size_t>(std::lround(length_mm / step)));
}

} // namespace

BranchEntryReport placeBranchEntries(QSkeleton& skeleton)
{
  BranchEntryReport report;
  for (std::size_t j = 0; j < skeleton.junctions.size(); ++j)
  {
    Junction& junction = skeleton.junctions[j];
    if (junction.childPath < 0 || junction.parentPath < 0 ||
        junction.childPath == junction.parentPath ||
        static_cast<std::size_t>(junction.childPath) >= skeleton.paths.size() ||
        static_cast<std::size_t>(junction.parentPath) >= skeleton.paths.size())
    {
      continue;
    }
    SkeletonPath& child = skeleton.paths[static_cast<std::size_t>(junction.childPath)];
    const SkeletonPath& parentPath = skeleton.paths[static_cast<std::size_t>(junction.parentPath)];
    const std::vector<SkeletonPoint>& parent = parentPath.points;
    if (junction.parentPoint < 0 || static_cast<std::size_t>(junction.parentPoint) >= parent.size())
    {
      continue;
    }
    const bool fromTail = junction.childEnd == Junction::End::Tail;
    std::vector<SkeletonPoint> branch = child.points;
    if (fromTail)
    {
      std::reverse(branch.begin(), branch.end());
    }
    Entry entry;
    if (!findEntry(branch, parent, static_cast<std::size_t>(junction.parentPoint), entry))
    {
      continue;
    }
    // Centres [0, exit) of the branch (from its attached end) are replaced: not when another
    // path hangs on one of them, or the other end of the branch is among them.
    const std::size_t n = child.points.size();
    bool held = entry.exit >= n - 1;
    for (const Junction& other : skeleton.junctions)
    {
      if (other.parentPath == junction.childPath && other.parentPoint >= 0)
      {
        const std::size_t p = static_cast<std::size_t>(other.parentPoint);
        const std::size_t fromEnd = fromTail ? n - 1 - p : p;
        held = held || fromEnd < entry.exit;
      }
    }
    if (held)
    {
      continue;
    }
    // The new entry: the parent's centre, then the straight line to the exit centre, sampled at
    // the branch's own spacing there; radii from the parent's to the branch's, linearly.
    const SkeletonPoint& meet = parent[entry.parentPoint];
    const SkeletonPoint& exitPoint = branch[entry.exit];
    const double length = distance(meet.position_World_mm, exitPoint.position_World_mm);
    const std::size_t segments = entrySegments(branch, entry.exit, length);
    // The line's own geometry (the paths are smoothed already): its direction toward increasing
    // point index, no curvature or torsion; the attached end is the bifurcation.
    const Vec3 line = exitPoint.position_World_mm - meet.position_World_mm;
    const Vec3 tangent = line * ((fromTail ? -1.0 : 1.0) / std::max(line.norm(), 1e-12));
    std::vector<SkeletonPoint> entryPoints;
    for (std::size_t s = 0; s < segments; ++s)
    {
      const double t = static_cast<double>(s) / static_cast<double>(segments);
      SkeletonPoint q;
      q.position_World_mm = meet.position_World_mm + line * t;
      q.tangent_World = tangent;
      q.radius_mm = meet.radius_mm + (exitPoint.radius_mm - meet.radius_mm) * t;
      q.label = s == 0 ? PointLabel::Bifurcation : PointLabel::Ordinary;
      entryPoints.push_back(q);
    }
    std::vector<SkeletonPoint> rebuilt = entryPoints;
    rebuilt.insert(
      rebuilt.end(), branch.begin() + static_cast<std::ptrdiff_t>(entry.exit), branch.end());
    // Indices on the branch that other junctions name: shifted when the head was replaced.
    const long shift = static_cast<long>(entryPoints.size()) - static_cast<long>(entry.exit);
    if (fromTail)
    {
      std::reverse(rebuilt.begin(), rebuilt.end());
    }
    else
    {
      for (Junction& other : skeleton.junctions)
      {
        if (other.parentPath == junction.childPath && other.parentPoint >= 0)
        {
          other.parentPoint = static_cast<int>(static_cast<long>(other.parentPoint) + shift);
        }
      }
    }
    // The coded parent point is no longer a bifurcation unless another path still hangs there.
    const int coded = junction.parentPoint;
    junction.parentPoint = static_cast<int>(entry.parentPoint);
    bool stillJoined = false;
    for (const Junction& other : skeleton.junctions)
    {
      stillJoined =
        stillJoined || (other.parentPath == junction.parentPath && other.parentPoint == coded);
    }
    SkeletonPath& parentMutable = skeleton.paths[static_cast<std::size_t>(junction.parentPath)];
    if (!stillJoined)
    {
      parentMutable.points[static_cast<std::size_t>(coded)].label = PointLabel::Ordinary;
    }
    parentMutable.points[entry.parentPoint].label = PointLabel::Bifurcation;
    child.points = std::move(rebuilt);
    ++report.junctionsMoved;
    report.pointsReplaced += entry.exit;
  }
  return report;
}

} // namespace vtouch

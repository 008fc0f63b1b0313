#include "vtouchJunctionRecentring.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <utility>
#include <vector>

namespace vtouch
{
namespace
{
using P3 = std::array<double, 3>;

/// Arms whose outward directions are at least this far apart may be one vessel running through...
constexpr double kThroughAngle_deg = 120.0;
/// ...when their calibres (median radius) differ by less than this ratio.
constexpr double kThroughCalibre = 0.9;
/// An arm line must pass this close to the new centre (junction radii).
constexpr double kLineMiss = 0.5;

P3 sub(const P3& a, const P3& b)
{
  return { a[0] - b[0], a[1] - b[1], a[2] - b[2] };
}
P3 add(const P3& a, const P3& b)
{
  return { a[0] + b[0], a[1] + b[1], a[2] + b[2] };
}
P3 scale(const P3& a, double s)
{
  return { a[0] * s, a[1] * s, a[2] * s };
}
double dot(const P3& a, const P3& b)
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
double norm(const P3& a)
{
  return std::sqrt(dot(a, a));
}
double dist(const P3& a, const P3& b)
{
  return norm(sub(a, b));
}

/// Distance from q to the line through c along the unit vector u.
double lineDistance(const P3& q, const P3& c, const P3& u)
{
  const P3 w = sub(q, c);
  return std::sqrt(std::max(0.0, dot(w, w) - dot(w, u) * dot(w, u)));
}

/// One vessel leaving a junction: the points of `path` from `end` (the junction point) in steps
/// of `step`.
struct Arm
{
  int path = -1;
  int end = -1;
  int step = 1;
  std::vector<int> inner; ///< within the zone, junction excluded, in order outward
  int edge = -1;          ///< the first point beyond the zone
  std::vector<int> outer; ///< beyond the zone, within zone + reach: where the axis is measured
  P3 centroid{};          ///< of the outer points
  P3 direction{};         ///< principal direction of the outer points, pointing outward
};

Arm makeArm(int path, int end, int step)
{
  Arm arm;
  arm.path = path;
  arm.end = end;
  arm.step = step;
  return arm;
}

/// Walks an arm outward. False when the arm does not reach far enough beyond the zone, or runs
/// into another junction point within reach.
bool walkArm(const RawSkeleton& s,
  Arm& arm,
  const P3& junction,
  double zone,
  double reach,
  const std::set<std::pair<int, int>>& pinned)
{
  const RawSkeletonPath& path = s.paths[arm.path];
  const int n = static_cast<int>(path.center_mm.size());
  double farthest = 0.0;
  for (int i = arm.end + arm.step; i >= 0 && i < n; i += arm.step)
  {
    const double d = dist(path.center_mm[i], junction);
    if (d > zone + reach)
    {
      break;
    }
    if (pinned.count({ arm.path, i }))
    {
      return false; // another junction within reach: the arms are not its own vessel's axis
    }
    if (arm.edge < 0 && d <= zone)
    {
      arm.inner.push_back(i);
      continue;
    }
    if (arm.edge < 0)
    {
      arm.edge = i;
    }
    arm.outer.push_back(i);
    farthest = std::max(farthest, d);
  }
  if (arm.edge < 0 || arm.outer.size() < 3 || farthest < zone + 0.5 * reach)
  {
    return false;
  }
  P3 c{ 0.0, 0.0, 0.0 };
  for (int i : arm.outer)
  {
    c = add(c, path.center_mm[i]);
  }
  arm.centroid = scale(c, 1.0 / static_cast<double>(arm.outer.size()));
  // Principal direction by power iteration on the scatter matrix, started outward.
  double m[3][3] = {};
  for (int i : arm.outer)
  {
    const P3 w = sub(path.center_mm[i], arm.centroid);
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b)
        m[a][b] += w[a] * w[b];
  }
  P3 u = sub(path.center_mm[arm.outer.back()], path.center_mm[arm.outer.front()]);
  if (norm(u) <= 0.0)
  {
    return false;
  }
  for (int it = 0; it < 32; ++it)
  {
    const P3 v{ dot({ m[0][0], m[0][1], m[0][2] }, u),
      dot({ m[1][0], m[1][1], m[1][2] }, u),
      dot({ m[2][0], m[2][1], m[2][2] }, u) };
    const double len = norm(v);
    if (len <= 0.0)
    {
      break;
    }
    u = scale(v, 1.0 / len);
  }
  u = scale(u, 1.0 / norm(u));
  if (dot(u, sub(arm.centroid, junction)) < 0.0)
  {
    u = scale(u, -1.0);
  }
  arm.direction = u;
  return true;
}

/// A quadratic space curve q(s) = c0 + c1 s + c2 s^2, least squares per coordinate.
struct Quadratic
{
  P3 c[3]{};
  P3 at(double s) const { return add(c[0], add(scale(c[1], s), scale(c[2], s * s))); }
};

bool fitQuadratic(const std::vector<std::pair<double, P3>>& samples, Quadratic& q)
{
  double a[3][3] = {};
  P3 rhs[3] = {};
  for (const auto& [s, p] : samples)
  {
    const double basis[3] = { 1.0, s, s * s };
    for (int i = 0; i < 3; ++i)
    {
      for (int j = 0; j < 3; ++j)
      {
        a[i][j] += basis[i] * basis[j];
      }
      rhs[i] = add(rhs[i], scale(p, basis[i]));
    }
  }
  // Cramer's rule on the 3x3 normal equations (the same matrix for the three coordinates).
  const auto det3 = [](const double x[3][3])
  {
    return x[0][0] * (x[1][1] * x[2][2] - x[1][2] * x[2][1]) -
           x[0][1] * (x[1][0] * x[2][2] - x[1][2] * x[2][0]) +
           x[0][2] * (x[1][0] * x[2][1] - x[1][1] * x[2][0]);
  };
  const double d = det3(a);
  if (!(std::abs(d) > 1e-12 * std::max(1.0, a[0][0] * a[1][1] * a[2][2])))
  {
    return false;
  }
  for (int coord = 0; coord < 3; ++coord)
  {
    for (int k = 0; k < 3; ++k)
    {
      double x[3][3];
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
          x[i][j] = j == k ? rhs[i][coord] : a[i][j];
      q.c[k][coord] = det3(x) / d;
    }
  }
  return true;
}

/// Cumulative fraction of arc length from the junction (0) to the edge point (1) of each inner
/// point of an arm.
std::vector<double> innerFractions(const RawSkeletonPath& path, const Arm& arm)
{
  std::vector<double> cumulative;
  double length = 0.0;
  P3 previous = path.center_mm[arm.end];
  for (int i : arm.inner)
  {
    length += dist(previous, path.center_mm[i]);
    cumulative.push_back(length);
    previous = path.center_mm[i];
  }
  length += dist(previous, path.center_mm[arm.edge]);
  for (double& c : cumulative)
  {
    c = length > 0.0 ? c / length : 1.0;
  }
  return cumulative;
}

struct Node
{
  int path = -1;
  int point = -1;
  std::vector<int> junctions;
};

/// Re-centres one node. False (and nothing changed) where the evidence is weak.
bool recentreNode(RawSkeleton& s,
  const Node& node,
  const std::set<std::pair<int, int>>& pinned,
  double minSpacing_mm,
  const JunctionRecentringParameters& par)
{
  const RawSkeletonPath& parent = s.paths[node.path];
  const P3 j0 = parent.center_mm[node.point];
  const double radius = nearbyRadius(parent, node.point);
  const double zone = std::max(par.zoneRadii * radius, par.minimumZone_vox * minSpacing_mm);
  const double reach = std::max(par.reachRadii * radius, 2.0 * minSpacing_mm);
  std::vector<Arm> arms;
  const int n = static_cast<int>(parent.center_mm.size());
  if (node.point > 0)
  {
    arms.push_back(makeArm(node.path, node.point, -1));
  }
  if (node.point < n - 1)
  {
    arms.push_back(makeArm(node.path, node.point, 1));
  }
  for (int j : node.junctions)
  {
    const RawJunction& rj = s.junctions[j];
    const int m = static_cast<int>(s.paths[rj.childPath].center_mm.size());
    arms.push_back(makeArm(rj.childPath, rj.childTail ? m - 1 : 0, rj.childTail ? -1 : 1));
  }
  if (arms.size() < 3)
  {
    return false;
  }
  for (Arm& arm : arms)
  {
    if (!walkArm(s, arm, j0, zone, reach, pinned))
    {
      return false;
    }
  }
  // The through vessel: among the pairs of arms that continue each other (outward directions at
  // least kThroughAngle apart), the pair of most similar calibre, if that is within
  // kThroughCalibre. A side branch leaves a vessel that keeps its calibre; at a bifurcation both
  // children are thinner than the trunk (Murray's law: 0.79 of it for equal children), and no
  // vessel runs through.
  std::vector<double> calibre;
  for (const Arm& arm : arms)
  {
    std::vector<double> r;
    for (int i : arm.outer)
    {
      r.push_back(s.paths[arm.path].radius_mm[i]);
    }
    std::nth_element(r.begin(), r.begin() + static_cast<std::ptrdiff_t>(r.size() / 2), r.end());
    calibre.push_back(r[r.size() / 2]);
  }
  const double minimumCos = std::cos(kThroughAngle_deg * 3.14159265358979323846 / 180.0);
  std::size_t ta = arms.size(), tb = arms.size();
  double bestRatio = kThroughCalibre;
  for (std::size_t a = 0; a < arms.size(); ++a)
  {
    for (std::size_t b = a + 1; b < arms.size(); ++b)
    {
      const double ratio = std::min(calibre[a], calibre[b]) / std::max(calibre[a], calibre[b]);
      if (dot(arms[a].direction, arms[b].direction) <= minimumCos && ratio >= bestRatio)
      {
        bestRatio = ratio;
        ta = a;
        tb = b;
      }
    }
  }
  if (ta == arms.size())
  {
    return false;
  }
  // The through axis: one quadratic in the position along the chord between the two arms.
  const P3 chordMid = scale(add(arms[ta].centroid, arms[tb].centroid), 0.5);
  P3 chordDir = sub(arms[tb].centroid, arms[ta].centroid);
  if (norm(chordDir) <= 0.0)
  {
    return false;
  }
  chordDir = scale(chordDir, 1.0 / norm(chordDir));
  const auto param = [&](const P3& p) { return dot(sub(p, chordMid), chordDir); };
  std::vector<std::pair<double, P3>> samples;
  for (std::size_t k : { ta, tb })
  {
    for (int i : arms[k].outer)
    {
      const P3& p = s.paths[arms[k].path].center_mm[i];
      samples.push_back({ param(p), p });
    }
  }
  Quadratic axis;
  if (!fitQuadratic(samples, axis))
  {
    return false;
  }
  const double sEdgeA = param(s.paths[arms[ta].path].center_mm[arms[ta].edge]);
  const double sEdgeB = param(s.paths[arms[tb].path].center_mm[arms[tb].edge]);
  if (!(sEdgeA < sEdgeB))
  {
    return false;
  }
  std::vector<const Arm*> branches;
  for (std::size_t k = 0; k < arms.size(); ++k)
  {
    if (k != ta && k != tb)
    {
      branches.push_back(&arms[k]);
    }
  }
  // The centre: the point of the through axis nearest to the branches' lines (a sampled search,
  // then a golden-section refinement around the best sample).
  const auto cost = [&](double t)
  {
    double c = 0.0;
    for (const Arm* arm : branches)
    {
      const double d = lineDistance(axis.at(t), arm->centroid, arm->direction);
      c += d * d;
    }
    return c;
  };
  constexpr int kSteps = 64;
  const double step = (sEdgeB - sEdgeA) / kSteps;
  double sCentre = sEdgeA;
  for (int k = 1; k <= kSteps; ++k)
  {
    if (cost(sEdgeA + k * step) < cost(sCentre))
    {
      sCentre = sEdgeA + k * step;
    }
  }
  double lo = std::max(sEdgeA, sCentre - step), hi = std::min(sEdgeB, sCentre + step);
  for (int it = 0; it < 24; ++it)
  {
    const double m1 = lo + 0.382 * (hi - lo), m2 = lo + 0.618 * (hi - lo);
    if (cost(m1) < cost(m2))
    {
      hi = m2;
    }
    else
    {
      lo = m1;
    }
  }
  sCentre = 0.5 * (lo + hi);
  const P3 centre = axis.at(sCentre);
  if (dist(centre, j0) > zone)
  {
    return false;
  }
  for (const Arm* arm : branches)
  {
    if (lineDistance(centre, arm->centroid, arm->direction) > kLineMiss * radius)
    {
      return false;
    }
  }
  // Re-lay the inner points.
  for (std::size_t k = 0; k < arms.size(); ++k)
  {
    const Arm& arm = arms[k];
    RawSkeletonPath& path = s.paths[arm.path];
    const std::vector<double> t = innerFractions(path, arm);
    const P3 edge = path.center_mm[arm.edge];
    const bool onAxis = k == ta || k == tb;
    const double sEdge = k == ta ? sEdgeA : sEdgeB;
    for (std::size_t i = 0; i < arm.inner.size(); ++i)
    {
      path.center_mm[arm.inner[i]] = onAxis ? axis.at(sCentre + t[i] * (sEdge - sCentre))
                                            : add(centre, scale(sub(edge, centre), t[i]));
    }
  }
  s.paths[node.path].center_mm[node.point] = centre;
  for (int j : node.junctions)
  {
    const RawJunction& rj = s.junctions[j];
    RawSkeletonPath& child = s.paths[rj.childPath];
    child.center_mm[rj.childTail ? child.center_mm.size() - 1 : 0] = centre;
  }
  return true;
}

} // namespace

std::vector<bool> recentreJunctions(RawSkeleton& skeleton,
  std::size_t firstPath,
  double minSpacing_mm,
  const JunctionRecentringParameters& parameters)
{
  // One node per parent point: several children may attach at the same point.
  std::map<std::pair<int, int>, Node> nodes;
  std::set<std::pair<int, int>> pinned;
  for (std::size_t j = 0; j < skeleton.junctions.size(); ++j)
  {
    const RawJunction& rj = skeleton.junctions[j];
    if (rj.parentPath < 0 || rj.childPath < 0)
    {
      continue;
    }
    pinned.insert({ rj.parentPath, rj.parentPoint });
    const int m = static_cast<int>(skeleton.paths[rj.childPath].center_mm.size());
    pinned.insert({ rj.childPath, rj.childTail ? m - 1 : 0 });
    if (static_cast<std::size_t>(rj.parentPath) < firstPath)
    {
      continue;
    }
    Node& node = nodes[{ rj.parentPath, rj.parentPoint }];
    node.path = rj.parentPath;
    node.point = rj.parentPoint;
    node.junctions.push_back(static_cast<int>(j));
  }
  std::vector<bool> recentred(skeleton.junctions.size(), false);
  for (const auto& entry : nodes)
  {
    if (recentreNode(skeleton, entry.second, pinned, minSpacing_mm, parameters))
    {
      for (int j : entry.second.junctions)
      {
        recentred[j] = true;
      }
    }
  }
  return recentred;
}

} // namespace vtouch

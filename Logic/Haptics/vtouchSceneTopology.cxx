#include "vtouchSceneTopology.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <utility>

namespace vtouch
{

namespace
{
std::atomic<std::uint64_t> NextTopologyId{ 1 };

int endPoint(const QSkeleton& s, const Junction& j)
{
  return j.childEnd == Junction::End::Head
           ? 0
           : static_cast<int>(s.paths[j.childPath].points.size()) - 1;
}
} // namespace

namespace
{
/// Walks from point i of a path (m points, `closed`: tail wraps to head) in direction `dir` until
/// the arc length reaches `target` (within 5 %, so a sampling a hair finer than window/2 does not
/// add a whole step). Returns the index reached and the arc length walked.
std::pair<int, double> walk(const std::vector<SkeletonPoint>& pts,
  int i,
  int dir,
  bool closed,
  double target)
{
  const int m = static_cast<int>(pts.size());
  int j = i;
  double s = 0.0;
  for (int guard = 0; s < 0.95 * target && guard < m; ++guard)
  {
    int next = j + dir;
    if (next < 0 || next >= m)
    {
      if (!closed)
      {
        break;
      }
      next = (next + m) % m;
    }
    s += (pts[next].position_World_mm - pts[j].position_World_mm).norm();
    j = next;
  }
  return { j, s };
}

bool isClosedLoop(const QSkeleton& skeleton, int p)
{
  const int m = static_cast<int>(skeleton.paths[p].points.size());
  for (const Junction& j : skeleton.junctions)
  {
    if (j.childPath == p && j.parentPath == p &&
        ((j.childEnd == Junction::End::Tail && j.parentPoint == 0) ||
          (j.childEnd == Junction::End::Head && j.parentPoint == m - 1)))
    {
      return true;
    }
  }
  return false;
}
} // namespace

std::shared_ptr<const SceneTopology> SceneTopology::build(const QSkeleton& skeleton,
  double slopeWindow_mm)
{
  auto t = std::make_shared<SceneTopology>();
  t->Id = NextTopologyId.fetch_add(1);
  t->Window_mm = slopeWindow_mm > 0.0 ? slopeWindow_mm : 1.0;
  const std::size_t n = skeleton.pointCount();
  t->PathOffset.reserve(skeleton.paths.size() + 1);
  t->PathOf.resize(n);
  t->Position.resize(n);
  t->Tangent.resize(n);
  t->Torsion.resize(n);
  t->Radius.resize(n);
  t->Stencil.resize(n);
  int g = 0;
  const double half = 0.5 * t->Window_mm;
  for (std::size_t p = 0; p < skeleton.paths.size(); ++p)
  {
    t->PathOffset.push_back(g);
    const auto& pts = skeleton.paths[p].points;
    const int m = static_cast<int>(pts.size());
    const bool closed = isClosedLoop(skeleton, static_cast<int>(p));
    for (int i = 0; i < m; ++i)
    {
      t->PathOf[g + i] = static_cast<int>(p);
      t->Position[g + i] = pts[i].position_World_mm;
      t->Tangent[g + i] = pts[i].tangent_World;
      t->Torsion[g + i] = pts[i].torsion_per_mm;
      t->Radius[g + i] = pts[i].radius_mm;
      const auto f1 = walk(pts, i, +1, closed, half);
      const auto b1 = walk(pts, i, -1, closed, half);
      const auto f2 = walk(pts, i, +1, closed, 2.0 * half);
      const auto b2 = walk(pts, i, -1, closed, 2.0 * half);
      StencilEntry& e = t->Stencil[g + i];
      e.loInner = g + b1.first;
      e.hiInner = g + f1.first;
      e.loOuter = g + b2.first;
      e.hiOuter = g + f2.first;
      const double s1 = f1.second + b1.second;
      const double s2 = f2.second + b2.second;
      const bool symmetric = std::fabs(f1.second - b1.second) <= 0.1 * s1 &&
                             std::fabs(f2.second - b2.second) <= 0.1 * s2 && s2 > 1.2 * s1;
      if (symmetric)
      {
        const double r2 = (s2 / s1) * (s2 / s1);
        e.innerWeight = r2 / ((r2 - 1.0) * s1);
        e.outerWeight = 1.0 / ((r2 - 1.0) * s2);
        e.plainWeight = 1.0 / s1;
      }
      else if (s1 > 0.0)
      {
        e.innerWeight = 1.0 / s1;
        e.plainWeight = 1.0 / s1;
      }
    }
    g += m;
  }
  t->PathOffset.push_back(g);
  // The tangent estimate is camera independent: computed once here, rotated per view.
  t->TangentEstimate.resize(n);
  t->PackedX.resize(n);
  t->PackedY.resize(n);
  t->PackedZ.resize(n);
  for (std::size_t i = 0; i < n; ++i)
  {
    const StencilEntry& e = t->Stencil[i];
    const Vec3& here = t->Position[i];
    const Vec3 inner = t->Position[e.hiInner] - t->Position[e.loInner];
    const Vec3 outer = t->Position[e.hiOuter] - t->Position[e.loOuter];
    // Richardson's correction, faded out where the curve is not smooth across the stencil (a
    // corner: see tangentEstimate()).
    double keep = e.outerWeight > 0.0 ? 1.0 : 0.0;
    if (keep > 0.0)
    {
      auto turn = [&here](const Vec3& lo, const Vec3& hi)
      {
        const Vec3 back = here - lo;
        const Vec3 ahead = hi - here;
        return std::atan2(back.cross(ahead).norm(), back.dot(ahead));
      };
      const double m = std::fabs(turn(t->Position[e.loOuter], t->Position[e.hiOuter]) -
                                 2.0 * turn(t->Position[e.loInner], t->Position[e.hiInner]));
      const double u = std::clamp(
        (m - kRichardsonFullBelow_rad) / (kRichardsonNoneAbove_rad - kRichardsonFullBelow_rad),
        0.0,
        1.0);
      keep = 1.0 - u * u * (3.0 - 2.0 * u); // smoothstep: the estimate stays continuous
    }
    t->TangentEstimate[i] =
      inner * e.plainWeight +
      (inner * (e.innerWeight - e.plainWeight) - outer * e.outerWeight) * keep;
    t->PackedX[i] = static_cast<float>(t->Position[i].x);
    t->PackedY[i] = static_cast<float>(t->Position[i].y);
    t->PackedZ[i] = static_cast<float>(t->Position[i].z);
  }

  std::vector<std::pair<int, int>> edges;
  for (const Junction& j : skeleton.junctions)
  {
    if (j.childPath < 0 || j.parentPath < 0)
    {
      continue;
    }
    const int a = t->PathOffset[j.childPath] + endPoint(skeleton, j);
    const int b = t->PathOffset[j.parentPath] + j.parentPoint;
    if (a != b)
    {
      edges.emplace_back(a, b);
      edges.emplace_back(b, a);
    }
  }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  t->JunctionBegin.assign(n + 1, 0);
  for (const auto& e : edges)
  {
    ++t->JunctionBegin[e.first + 1];
  }
  int maxExtra = 0;
  for (std::size_t i = 0; i < n; ++i)
  {
    maxExtra = std::max(maxExtra, t->JunctionBegin[i + 1]);
    t->JunctionBegin[i + 1] += t->JunctionBegin[i];
  }
  t->JunctionTarget.reserve(edges.size());
  for (const auto& e : edges)
  {
    t->JunctionTarget.push_back(e.second);
  }
  t->MaxDegree = 2 + maxExtra;

  // Arc coordinates along each path and the nearest bifurcation on it (forward and backward
  // sweeps).
  t->PathArc.assign(n, 0.0);
  t->Bifurcation.assign(n, 0);
  t->NearestBifurcationArc.assign(n, std::numeric_limits<double>::quiet_NaN());
  for (const Junction& j : skeleton.junctions)
  {
    if (j.childPath < 0 || j.parentPath < 0)
    {
      continue;
    }
    const int last = static_cast<int>(skeleton.paths[j.parentPath].points.size()) - 1;
    if (j.childPath == j.parentPath && (j.parentPoint == 0 || j.parentPoint == last))
    {
      continue; // a loop closing on its own end: no branch
    }
    t->Bifurcation[t->PathOffset[j.childPath] + endPoint(skeleton, j)] = 1;
    t->Bifurcation[t->PathOffset[j.parentPath] + j.parentPoint] = 1;
  }
  for (int p = 0; p < t->pathCount(); ++p)
  {
    const int begin = t->PathOffset[p];
    const int end = t->PathOffset[p + 1];
    for (int g = begin + 1; g < end; ++g)
    {
      t->PathArc[g] = t->PathArc[g - 1] + (t->Position[g] - t->Position[g - 1]).norm();
    }
    double before = std::numeric_limits<double>::quiet_NaN();
    for (int g = begin; g < end; ++g)
    {
      before = t->Bifurcation[g] ? t->PathArc[g] : before;
      t->NearestBifurcationArc[g] = before;
    }
    double after = std::numeric_limits<double>::quiet_NaN();
    for (int g = end - 1; g >= begin; --g)
    {
      after = t->Bifurcation[g] ? t->PathArc[g] : after;
      const double b = t->NearestBifurcationArc[g];
      if (std::isnan(b) || (!std::isnan(after) && after - t->PathArc[g] < t->PathArc[g] - b))
      {
        t->NearestBifurcationArc[g] = after;
      }
    }
  }
  return t;
}

double SceneTopology::bifurcationOffset_mm(int from, int to, double t) const
{
  const int n = this->pointCount();
  if (from < 0 || from >= n)
  {
    return std::numeric_limits<double>::quiet_NaN();
  }
  double s = this->PathArc[from];
  double mark = this->NearestBifurcationArc[from];
  if (to >= 0 && to < n && t > 0.0)
  {
    if (this->PathOf[to] != this->PathOf[from])
    {
      return 0.0; // on a junction edge: at the bifurcation
    }
    s += std::clamp(t, 0.0, 1.0) * (this->PathArc[to] - this->PathArc[from]);
    const double other = this->NearestBifurcationArc[to];
    if (std::isnan(mark) || (!std::isnan(other) && std::fabs(other - s) < std::fabs(mark - s)))
    {
      mark = other;
    }
  }
  return s - mark; // NaN when the path has no bifurcation
}

int SceneTopology::neighbours(int g, int* out, int capacity) const
{
  int count = 0;
  const int path = this->PathOf[g];
  if (g > this->PathOffset[path] && count < capacity)
  {
    out[count++] = g - 1;
  }
  if (g + 1 < this->PathOffset[path + 1] && count < capacity)
  {
    out[count++] = g + 1;
  }
  for (int k = this->JunctionBegin[g]; k < this->JunctionBegin[g + 1] && count < capacity; ++k)
  {
    out[count++] = this->JunctionTarget[k];
  }
  return count;
}

} // namespace vtouch

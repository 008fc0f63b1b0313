#include "vtouchPolyDataToQSkeleton.h"

#include "vtouchCurveGeometry.h"

#include "vtkCellArray.h"
#include "vtkCellArrayIterator.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <vector>

namespace vtouch
{
namespace
{
const char* const kTopologyArrays[] = { "PathHeadJunction",
  "PathTailJunction",
  "JunctionChildPath",
  "JunctionChildEnd",
  "JunctionParentPath",
  "JunctionParentPoint" };

vtkDataArray* pointArray(vtkPolyData* pd, const char* name, int components)
{
  vtkDataArray* a = pd->GetPointData()->GetArray(name);
  return (a && a->GetNumberOfComponents() == components &&
           a->GetNumberOfTuples() == pd->GetNumberOfPoints())
           ? a
           : nullptr;
}

/// Per-point optional arrays of the input.
struct PointArrays
{
  vtkDataArray* tangent;
  vtkDataArray* radius;
  vtkDataArray* curvature;
  vtkDataArray* torsion;
  vtkDataArray* label;
};

/// Reads one polyline into `path`; `closed` tells whether the cell repeats its first point.
bool readPath(vtkPolyData* pd,
  vtkIdType n,
  const vtkIdType* ids,
  const PointArrays& a,
  SkeletonPath& path,
  bool& closed,
  std::string& error)
{
  closed = n > 3 && ids[n - 1] == ids[0];
  const vtkIdType count = closed ? n - 1 : n;
  path.points.resize(static_cast<std::size_t>(count));
  std::vector<Vec3> positions(path.points.size());
  for (vtkIdType i = 0; i < count; ++i)
  {
    double x[3];
    pd->GetPoint(ids[i], x);
    if (!std::isfinite(x[0]) || !std::isfinite(x[1]) || !std::isfinite(x[2]))
    {
      std::ostringstream msg;
      msg << "point " << ids[i] << " of polyline " << path.id << " is not finite";
      error = msg.str();
      return false;
    }
    SkeletonPoint& q = path.points[static_cast<std::size_t>(i)];
    q.position_World_mm = { x[0], x[1], x[2] };
    positions[static_cast<std::size_t>(i)] = q.position_World_mm;
    if (a.tangent)
    {
      double t[3];
      a.tangent->GetTuple(ids[i], t);
      q.tangent_World = { t[0], t[1], t[2] };
    }
    q.radius_mm = a.radius ? a.radius->GetComponent(ids[i], 0) : 0.0;
    q.curvature_per_mm = a.curvature ? a.curvature->GetComponent(ids[i], 0) : 0.0;
    q.torsion_per_mm = a.torsion ? a.torsion->GetComponent(ids[i], 0) : 0.0;
    if (a.label)
    {
      const int l = static_cast<int>(a.label->GetComponent(ids[i], 0));
      q.label = (l == 1 || l == 2) ? static_cast<PointLabel>(l) : PointLabel::Ordinary;
    }
  }
  if (!a.tangent || !a.curvature || !a.torsion)
  {
    // Differentiate the polyline as given (positions kept: the windows only fit derivatives).
    CurveGeometryWindows windows;
    windows.position_mm = 0.0;
    const std::vector<CurveSample> g = computeCurveGeometry(positions, windows);
    for (std::size_t i = 0; i < g.size() && i < path.points.size(); ++i)
    {
      SkeletonPoint& q = path.points[i];
      q.tangent_World = a.tangent ? q.tangent_World : g[i].tangent;
      q.curvature_per_mm = a.curvature ? q.curvature_per_mm : g[i].curvature;
      q.torsion_per_mm = a.torsion ? q.torsion_per_mm : g[i].torsion;
    }
  }
  return true;
}

int addJunction(QSkeleton& s, int child, Junction::End end, int parent, int parentPoint)
{
  Junction j;
  j.childPath = child;
  j.childEnd = end;
  j.parentPath = parent;
  j.parentPoint = parentPoint;
  s.junctions.push_back(j);
  const int index = static_cast<int>(s.junctions.size()) - 1;
  (end == Junction::End::Head ? s.paths[child].head : s.paths[child].tail).junction = index;
  return index;
}

/// VesselCenterline's topology from field data; false (with `error`) when present but invalid,
/// `found` false when absent.
bool readTopology(vtkPolyData* pd, QSkeleton& s, bool& found, std::string& error)
{
  vtkDataArray* a[6];
  found = true;
  for (int k = 0; k < 6; ++k)
  {
    a[k] = pd->GetFieldData()->GetArray(kTopologyArrays[k]);
    found = found && a[k] != nullptr;
  }
  if (!found)
  {
    return true;
  }
  const vtkIdType paths = static_cast<vtkIdType>(s.paths.size());
  const vtkIdType junctions = a[2]->GetNumberOfTuples();
  if (a[0]->GetNumberOfTuples() != paths || a[1]->GetNumberOfTuples() != paths ||
      a[3]->GetNumberOfTuples() != junctions || a[4]->GetNumberOfTuples() != junctions ||
      a[5]->GetNumberOfTuples() != junctions)
  {
    error = "the topology field arrays do not match the number of polylines";
    return false;
  }
  s.junctions.resize(static_cast<std::size_t>(junctions));
  for (vtkIdType k = 0; k < junctions; ++k)
  {
    Junction& j = s.junctions[static_cast<std::size_t>(k)];
    j.childPath = static_cast<int>(a[2]->GetComponent(k, 0));
    j.childEnd = a[3]->GetComponent(k, 0) != 0.0 ? Junction::End::Tail : Junction::End::Head;
    j.parentPath = static_cast<int>(a[4]->GetComponent(k, 0));
    j.parentPoint = static_cast<int>(a[5]->GetComponent(k, 0));
  }
  for (vtkIdType p = 0; p < paths; ++p)
  {
    s.paths[static_cast<std::size_t>(p)].head.junction = static_cast<int>(a[0]->GetComponent(p, 0));
    s.paths[static_cast<std::size_t>(p)].tail.junction = static_cast<int>(a[1]->GetComponent(p, 0));
  }
  return true;
}

/// Largest distance from point `i` of `path` to its neighbours, mm (the local sample spacing).
double spacingAt(const SkeletonPath& path, std::size_t i)
{
  double h = 0.0;
  const Vec3& x = path.points[i].position_World_mm;
  if (i > 0)
  {
    h = std::max(h, (path.points[i - 1].position_World_mm - x).norm());
  }
  if (i + 1 < path.points.size())
  {
    h = std::max(h, (path.points[i + 1].position_World_mm - x).norm());
  }
  return h;
}

/// The point of another path nearest to `x`, if it lies within `tolerance` or within the local
/// sample spacing there (a branch may start between two samples of its parent).
bool nearestOnOtherPath(const QSkeleton& s,
  int self,
  const Vec3& x,
  double tolerance,
  int& path,
  int& point)
{
  double best = 1e300;
  path = point = -1;
  for (const SkeletonPath& other : s.paths)
  {
    if (other.id == self)
    {
      continue;
    }
    for (std::size_t i = 0; i < other.points.size(); ++i)
    {
      const double d = (other.points[i].position_World_mm - x).norm();
      if (d < best)
      {
        best = d;
        path = other.id;
        point = static_cast<int>(i);
      }
    }
  }
  if (path < 0)
  {
    return false;
  }
  const double reach = std::max(
    tolerance, spacingAt(s.paths[static_cast<std::size_t>(path)], static_cast<std::size_t>(point)));
  return best <= reach;
}

/// Joins free ends that touch another path (inputs without topology arrays).
void inferJunctions(QSkeleton& s, double tolerance)
{
  // Heads first: a branch starts on its parent (the generators' and VesselCenterline's
  // convention); a tail then finds the connection already made from the other side.
  for (const Junction::End end : { Junction::End::Head, Junction::End::Tail })
  {
    for (std::size_t p = 0; p < s.paths.size(); ++p)
    {
      SkeletonPath& path = s.paths[p];
      const bool head = end == Junction::End::Head;
      if ((head ? path.head : path.tail).junction >= 0)
      {
        continue;
      }
      const int self = head ? 0 : static_cast<int>(path.points.size()) - 1;
      int parent = -1, parentPoint = -1;
      if (!nearestOnOtherPath(s,
            path.id,
            path.points[static_cast<std::size_t>(self)].position_World_mm,
            tolerance,
            parent,
            parentPoint))
      {
        continue;
      }
      // Two coincident free ends are one connection: keep the one already recorded.
      const SkeletonPath& q = s.paths[static_cast<std::size_t>(parent)];
      const int qEnd = parentPoint == 0                                       ? q.head.junction
                       : parentPoint == static_cast<int>(q.points.size()) - 1 ? q.tail.junction
                                                                              : -1;
      if (qEnd >= 0 && s.junctions[static_cast<std::size_t>(qEnd)].parentPath == path.id &&
          s.junctions[static_cast<std::size_t>(qEnd)].parentPoint == self)
      {
        continue;
      }
      addJunction(s, path.id, end, parent, parentPoint);
    }
  }
}

/// Labels from the topology when the input has no BifurcationLabel array.
void deriveLabels(QSkeleton& s)
{
  for (SkeletonPath& path : s.paths)
  {
    if (path.head.junction < 0)
    {
      path.points.front().label = PointLabel::EndPoint;
    }
    if (path.tail.junction < 0)
    {
      path.points.back().label = PointLabel::EndPoint;
    }
  }
  for (const Junction& j : s.junctions)
  {
    if (j.childPath == j.parentPath)
    {
      continue; // a ring closing on itself has no bifurcation
    }
    SkeletonPath& child = s.paths[static_cast<std::size_t>(j.childPath)];
    (j.childEnd == Junction::End::Head ? child.points.front() : child.points.back()).label =
      PointLabel::Bifurcation;
    s.paths[static_cast<std::size_t>(j.parentPath)]
      .points[static_cast<std::size_t>(j.parentPoint)]
      .label = PointLabel::Bifurcation;
  }
}
} // namespace

bool PolyDataToQSkeleton::convert(vtkPolyData* centerline,
  QSkeleton& skeleton,
  std::string& error) const
{
  skeleton = QSkeleton{};
  if (!centerline)
  {
    error = "no centerline (the input is not a vtkPolyData)";
    return false;
  }
  vtkCellArray* lines = centerline->GetLines();
  if (centerline->GetNumberOfPoints() == 0 || !lines || lines->GetNumberOfCells() == 0)
  {
    error = "the centerline is empty (no points or no polylines)";
    return false;
  }
  const PointArrays arrays{ pointArray(centerline, "Tangent", 3),
    pointArray(centerline, "Radius", 1),
    pointArray(centerline, "Curvature", 1),
    pointArray(centerline, "Torsion", 1),
    pointArray(centerline, "BifurcationLabel", 1) };
  std::vector<bool> closed;
  auto it = vtk::TakeSmartPointer(lines->NewIterator());
  for (it->GoToFirstCell(); !it->IsDoneWithTraversal(); it->GoToNextCell())
  {
    vtkIdType n = 0;
    const vtkIdType* ids = nullptr;
    it->GetCurrentCell(n, ids);
    SkeletonPath path;
    path.id = static_cast<int>(skeleton.paths.size());
    if (n < 2)
    {
      std::ostringstream msg;
      msg << "polyline " << path.id << " has " << n << " point(s); a path needs at least 2";
      error = msg.str();
      return false;
    }
    bool ring = false;
    if (!readPath(centerline, n, ids, arrays, path, ring, error))
    {
      return false;
    }
    skeleton.paths.push_back(std::move(path));
    closed.push_back(ring);
  }
  bool hasTopology = false;
  if (!readTopology(centerline, skeleton, hasTopology, error))
  {
    return false;
  }
  if (!hasTopology)
  {
    for (std::size_t p = 0; p < skeleton.paths.size(); ++p)
    {
      if (closed[p])
      {
        addJunction(skeleton, static_cast<int>(p), Junction::End::Tail, static_cast<int>(p), 0);
      }
    }
    inferJunctions(skeleton, this->junctionTolerance_mm);
  }
  if (!arrays.label)
  {
    deriveLabels(skeleton);
  }
  const std::string why = skeleton.validate();
  if (!why.empty())
  {
    error = "inconsistent centerline topology: " + why;
    skeleton = QSkeleton{};
    return false;
  }
  return true;
}

} // namespace vtouch

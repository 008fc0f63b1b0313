#include "vtouchQSkeletonToPolyData.h"

#include "vtkCellArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkUnsignedCharArray.h"

#include <vector>

namespace vtouch
{
void qSkeletonToPolyData(const QSkeleton& skeleton, vtkPolyData* output)
{
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  vtkNew<vtkCellArray> lines;
  vtkNew<vtkFloatArray> radius, tangent, curvature, torsion;
  vtkNew<vtkUnsignedCharArray> label;
  vtkNew<vtkIntArray> pathId, pointIndex;
  radius->SetName("Radius");
  tangent->SetName("Tangent");
  tangent->SetNumberOfComponents(3);
  curvature->SetName("Curvature");
  torsion->SetName("Torsion");
  label->SetName("BifurcationLabel");
  pathId->SetName("PathId");
  pointIndex->SetName("PointIndex");
  for (const SkeletonPath& path : skeleton.paths)
  {
    lines->InsertNextCell(static_cast<vtkIdType>(path.points.size()));
    for (std::size_t i = 0; i < path.points.size(); ++i)
    {
      const SkeletonPoint& q = path.points[i];
      lines->InsertCellPoint(points->InsertNextPoint(
        q.position_World_mm.x, q.position_World_mm.y, q.position_World_mm.z));
      radius->InsertNextValue(static_cast<float>(q.radius_mm));
      tangent->InsertNextTuple3(q.tangent_World.x, q.tangent_World.y, q.tangent_World.z);
      curvature->InsertNextValue(static_cast<float>(q.curvature_per_mm));
      torsion->InsertNextValue(static_cast<float>(q.torsion_per_mm));
      label->InsertNextValue(static_cast<unsigned char>(q.label));
      pathId->InsertNextValue(path.id);
      pointIndex->InsertNextValue(static_cast<int>(i));
    }
  }
  output->SetPoints(points);
  output->SetLines(lines);
  vtkPointData* pd = output->GetPointData();
  for (vtkDataArray* a :
    std::vector<vtkDataArray*>{ radius, tangent, curvature, torsion, label, pathId, pointIndex })
  {
    pd->AddArray(a);
  }
  const auto intArray = [](const char* name)
  {
    vtkNew<vtkIntArray> a;
    a->SetName(name);
    return a;
  };
  auto head = intArray("PathHeadJunction");
  auto tail = intArray("PathTailJunction");
  for (const SkeletonPath& path : skeleton.paths)
  {
    head->InsertNextValue(path.head.junction);
    tail->InsertNextValue(path.tail.junction);
  }
  auto child = intArray("JunctionChildPath");
  auto childEnd = intArray("JunctionChildEnd");
  auto parent = intArray("JunctionParentPath");
  auto parentPoint = intArray("JunctionParentPoint");
  for (const Junction& j : skeleton.junctions)
  {
    child->InsertNextValue(j.childPath);
    childEnd->InsertNextValue(j.childEnd == Junction::End::Tail ? 1 : 0);
    parent->InsertNextValue(j.parentPath);
    parentPoint->InsertNextValue(j.parentPoint);
  }
  vtkFieldData* fd = output->GetFieldData();
  for (vtkIntArray* a :
    { head.Get(), tail.Get(), child.Get(), childEnd.Get(), parent.Get(), parentPoint.Get() })
  {
    fd->AddArray(a);
  }
}
} // namespace vtouch

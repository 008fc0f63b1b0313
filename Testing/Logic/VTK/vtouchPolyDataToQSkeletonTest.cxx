// PolyDataToQSkeleton: the two centerline encodings of the plugin (VesselCenterline with its
// topology in field data, VesselPhantom's analytic polylines without) back to a QSkeleton.
#include "vtouchPolyDataToQSkeleton.h"
#include "vtouchQSkeletonToPolyData.h"

#include "vtouchPhantomGenerator.h"

#include "vtkCellArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkUnsignedCharArray.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

namespace vtouch
{
namespace
{

QSkeleton phantomSkeleton(PhantomShape shape)
{
  PhantomSpec spec;
  spec.shape = shape;
  PhantomGenerator phantom(spec);
  EXPECT_TRUE(phantom.ok()) << phantom.error();
  return phantom.centerline();
}

/// The encoding of vtkVesselTouchCenterlineFilter (one polyline per path, arrays, topology):
/// its own encoder, so that these tests are a round trip.
vtkNew<vtkPolyData> centerlineEncoding(const QSkeleton& s)
{
  vtkNew<vtkPolyData> out;
  qSkeletonToPolyData(s, out);
  return out;
}

/// The encoding of vtkVesselTouchPhantomSource port 1: polylines with Radius and Tangent only, a
/// ring closed by repeating its first point id, no topology.
vtkNew<vtkPolyData> phantomEncoding(const QSkeleton& s)
{
  vtkNew<vtkPolyData> out;
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  vtkNew<vtkDoubleArray> radius, tangent;
  radius->SetName("Radius");
  tangent->SetName("Tangent");
  tangent->SetNumberOfComponents(3);
  vtkNew<vtkCellArray> lines;
  for (const SkeletonPath& path : s.paths)
  {
    const bool closed =
      path.tail.junction >= 0 && s.junctions[path.tail.junction].parentPath == path.id;
    const vtkIdType n = static_cast<vtkIdType>(path.points.size());
    lines->InsertNextCell(closed ? n + 1 : n);
    const vtkIdType first = points->GetNumberOfPoints();
    for (const SkeletonPoint& p : path.points)
    {
      lines->InsertCellPoint(points->InsertNextPoint(
        p.position_World_mm.x, p.position_World_mm.y, p.position_World_mm.z));
      radius->InsertNextValue(p.radius_mm);
      tangent->InsertNextTuple3(p.tangent_World.x, p.tangent_World.y, p.tangent_World.z);
    }
    if (closed)
    {
      lines->InsertCellPoint(first);
    }
  }
  out->SetPoints(points);
  out->SetLines(lines);
  out->GetPointData()->AddArray(radius);
  out->GetPointData()->AddArray(tangent);
  return out;
}

void expectSameGeometry(const QSkeleton& expected, const QSkeleton& actual)
{
  ASSERT_EQ(actual.paths.size(), expected.paths.size());
  for (std::size_t p = 0; p < expected.paths.size(); ++p)
  {
    const SkeletonPath& e = expected.paths[p];
    const SkeletonPath& a = actual.paths[p];
    EXPECT_EQ(a.id, static_cast<int>(p));
    ASSERT_EQ(a.points.size(), e.points.size()) << "path " << p;
    for (std::size_t i = 0; i < e.points.size(); ++i)
    {
      EXPECT_NEAR(
        (a.points[i].position_World_mm - e.points[i].position_World_mm).norm(), 0.0, 1e-9);
      EXPECT_NEAR(a.points[i].radius_mm, e.points[i].radius_mm, 1e-5);
      EXPECT_NEAR(a.points[i].tangent_World.norm(), 1.0, 1e-5);
    }
  }
}

TEST(PolyDataToQSkeleton, NullOrEmptyInputFailsWithReason)
{
  PolyDataToQSkeleton converter;
  QSkeleton s;
  std::string error;
  EXPECT_FALSE(converter.convert(nullptr, s, error));
  EXPECT_NE(error.find("no centerline"), std::string::npos) << error;
  vtkNew<vtkPolyData> empty;
  error.clear();
  EXPECT_FALSE(converter.convert(empty, s, error));
  EXPECT_NE(error.find("empty"), std::string::npos) << error;
  // Points but no polyline (e.g. a vertex cloud).
  vtkNew<vtkPoints> points;
  points->InsertNextPoint(0, 0, 0);
  empty->SetPoints(points);
  EXPECT_FALSE(converter.convert(empty, s, error));
  EXPECT_TRUE(s.empty());
}

TEST(PolyDataToQSkeleton, CenterlineEncodingRoundTripsPathsJunctionsAndLabels)
{
  for (PhantomShape shape :
    { PhantomShape::YBifurcation, PhantomShape::Tree, PhantomShape::LoopNetwork })
  {
    const QSkeleton expected = phantomSkeleton(shape);
    vtkNew<vtkPolyData> poly = centerlineEncoding(expected);
    QSkeleton actual;
    std::string error;
    ASSERT_TRUE(PolyDataToQSkeleton().convert(poly, actual, error)) << error;
    SCOPED_TRACE(toString(shape));
    expectSameGeometry(expected, actual);
    EXPECT_EQ(actual.validate(), "");
    ASSERT_EQ(actual.junctions.size(), expected.junctions.size());
    for (std::size_t k = 0; k < expected.junctions.size(); ++k)
    {
      EXPECT_EQ(actual.junctions[k].childPath, expected.junctions[k].childPath);
      EXPECT_EQ(actual.junctions[k].childEnd, expected.junctions[k].childEnd);
      EXPECT_EQ(actual.junctions[k].parentPath, expected.junctions[k].parentPath);
      EXPECT_EQ(actual.junctions[k].parentPoint, expected.junctions[k].parentPoint);
    }
    for (std::size_t p = 0; p < expected.paths.size(); ++p)
    {
      EXPECT_EQ(actual.paths[p].head.junction, expected.paths[p].head.junction);
      EXPECT_EQ(actual.paths[p].tail.junction, expected.paths[p].tail.junction);
      for (std::size_t i = 0; i < expected.paths[p].points.size(); ++i)
      {
        EXPECT_EQ(actual.paths[p].points[i].label, expected.paths[p].points[i].label);
      }
    }
  }
}

TEST(PolyDataToQSkeleton, PhantomEncodingRecoversJunctionsRingsAndCurvature)
{
  // Without topology arrays the junctions are found geometrically: every junction of the
  // generator (branch starts, a ring closing on itself, spokes meeting a ring between samples).
  for (PhantomShape shape : { PhantomShape::YBifurcation,
         PhantomShape::Tree,
         PhantomShape::LoopNetwork,
         PhantomShape::Circle,
         PhantomShape::Helix })
  {
    const QSkeleton expected = phantomSkeleton(shape);
    vtkNew<vtkPolyData> poly = phantomEncoding(expected);
    QSkeleton actual;
    std::string error;
    ASSERT_TRUE(PolyDataToQSkeleton().convert(poly, actual, error)) << error;
    SCOPED_TRACE(toString(shape));
    expectSameGeometry(expected, actual);
    EXPECT_EQ(actual.validate(), "");
    ASSERT_EQ(actual.junctions.size(), expected.junctions.size());
    for (const Junction& e : expected.junctions)
    {
      const SkeletonPath& child = actual.paths[static_cast<std::size_t>(e.childPath)];
      const int k = e.childEnd == Junction::End::Head ? child.head.junction : child.tail.junction;
      ASSERT_GE(k, 0) << "path " << e.childPath << " lost its junction";
      const Junction& a = actual.junctions[static_cast<std::size_t>(k)];
      EXPECT_EQ(a.parentPath, e.parentPath);
      EXPECT_LE(std::abs(a.parentPoint - e.parentPoint), 1) << "path " << e.childPath;
    }
  }
  // The helix's curvature and torsion come back from the polyline (constant along the coil).
  const QSkeleton helix = phantomSkeleton(PhantomShape::Helix);
  QSkeleton actual;
  std::string error;
  ASSERT_TRUE(PolyDataToQSkeleton().convert(phantomEncoding(helix), actual, error)) << error;
  const auto& pts = actual.paths[0].points;
  const SkeletonPoint& mid = pts[pts.size() / 2];
  const SkeletonPoint& ref = helix.paths[0].points[pts.size() / 2];
  EXPECT_NEAR(mid.curvature_per_mm, ref.curvature_per_mm, 0.05 * std::fabs(ref.curvature_per_mm));
  EXPECT_NEAR(mid.torsion_per_mm, ref.torsion_per_mm, 0.05 * std::fabs(ref.torsion_per_mm));
  EXPECT_EQ(pts.front().label, PointLabel::EndPoint);
  EXPECT_EQ(pts.back().label, PointLabel::EndPoint);
}

TEST(PolyDataToQSkeleton, BadGeometryOrTopologyFailsWithReason)
{
  const QSkeleton y = phantomSkeleton(PhantomShape::YBifurcation);
  PolyDataToQSkeleton converter;
  QSkeleton s;
  std::string error;
  {
    vtkNew<vtkPolyData> poly = centerlineEncoding(y);
    poly->GetPoints()->SetPoint(3, std::numeric_limits<double>::quiet_NaN(), 0, 0);
    EXPECT_FALSE(converter.convert(poly, s, error));
    EXPECT_NE(error.find("not finite"), std::string::npos) << error;
  }
  {
    vtkNew<vtkPolyData> poly = centerlineEncoding(y);
    auto* parentPoint =
      vtkIntArray::SafeDownCast(poly->GetFieldData()->GetArray("JunctionParentPoint"));
    parentPoint->SetValue(0, 100000);
    EXPECT_FALSE(converter.convert(poly, s, error));
    EXPECT_NE(error.find("topology"), std::string::npos) << error;
    EXPECT_TRUE(s.empty());
  }
  {
    vtkNew<vtkPolyData> poly = centerlineEncoding(y);
    poly->GetFieldData()->GetArray("PathHeadJunction")->SetNumberOfTuples(1);
    EXPECT_FALSE(converter.convert(poly, s, error));
    EXPECT_NE(error.find("topology"), std::string::npos) << error;
  }
  {
    vtkNew<vtkPolyData> poly;
    vtkNew<vtkPoints> points;
    points->InsertNextPoint(0, 0, 0);
    vtkNew<vtkCellArray> lines;
    lines->InsertNextCell(1);
    lines->InsertCellPoint(0);
    poly->SetPoints(points);
    poly->SetLines(lines);
    EXPECT_FALSE(converter.convert(poly, s, error));
    EXPECT_NE(error.find("at least 2"), std::string::npos) << error;
  }
}

} // namespace
} // namespace vtouch

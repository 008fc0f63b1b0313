#include "pqVesselTouchAgentActors.h"

#include "vtkActor.h"
#include "vtkActor2D.h"
#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkConeSource.h"
#include "vtkIdList.h"
#include "vtkMatrix4x4.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkPolyDataMapper2D.h"
#include "vtkPolyDataNormals.h"
#include "vtkProperty.h"
#include "vtkProperty2D.h"
#include "vtkRenderer.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <cmath>

namespace
{
constexpr int kConeFacets = 32;
constexpr double kPi = 3.14159265358979323846;
constexpr double kCursorRadius_px = 9.0;

void setColour(vtkProperty2D* property, const std::array<unsigned char, 3>& rgb)
{
  property->SetColor(rgb[0] / 255.0, rgb[1] / 255.0, rgb[2] / 255.0);
}
} // namespace

pqVesselTouchAgentActors::pqVesselTouchAgentActors()
{
  this->buildCone();
  this->buildCursor();
  this->buildArrow();
}

pqVesselTouchAgentActors::~pqVesselTouchAgentActors() = default;

void pqVesselTouchAgentActors::buildCone()
{
  // A unit-height cone along +Z centred on the origin (apex z = +0.5, base z = -0.5, base radius
  // 0.35), coloured per cell: blue base, red sides, a two-facet white stripe at +X for the roll.
  vtkNew<vtkConeSource> source;
  source->SetResolution(kConeFacets);
  source->SetHeight(1.0);
  source->SetRadius(0.35);
  source->SetCenter(0.0, 0.0, 0.0);
  source->SetDirection(0.0, 0.0, 1.0);
  source->CappingOn();
  source->Update();
  vtkPolyData* poly = source->GetOutput();
  vtkNew<vtkUnsignedCharArray> colours;
  colours->SetName("AgentColours");
  colours->SetNumberOfComponents(3);
  vtkNew<vtkIdList> ids;
  for (vtkIdType cell = 0; cell < poly->GetNumberOfCells(); ++cell)
  {
    poly->GetCellPoints(cell, ids);
    std::array<unsigned char, 3> rgb = SideRgb;
    if (ids->GetNumberOfIds() > 3)
    {
      rgb = BaseRgb;
    }
    else
    {
      double mid[2] = { 0.0, 0.0 };
      int baseCorners = 0;
      for (vtkIdType k = 0; k < ids->GetNumberOfIds(); ++k)
      {
        double p[3];
        poly->GetPoint(ids->GetId(k), p);
        if (p[2] < 0.0)
        {
          mid[0] += p[0];
          mid[1] += p[1];
          ++baseCorners;
        }
      }
      const double angle_deg = std::atan2(mid[1], mid[0]) * 180.0 / kPi;
      if (baseCorners > 0 && std::abs(angle_deg) < 360.0 / kConeFacets)
      {
        rgb = StripeRgb;
      }
    }
    colours->InsertNextTypedTuple(rgb.data());
  }
  poly->GetCellData()->SetScalars(colours);
  vtkNew<vtkPolyDataNormals> normals; // smooth sides, a flat base
  normals->SetInputData(poly);
  normals->SetFeatureAngle(45.0);
  normals->SplittingOn();
  normals->ComputeCellNormalsOff();
  normals->Update();
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputData(normals->GetOutput());
  mapper->SetScalarModeToUseCellData();
  mapper->SetColorModeToDirectScalars();
  this->Cone->SetMapper(mapper);
  this->Cone->PickableOff();
  this->Cone->SetUserMatrix(this->ConeMatrix);
  this->Cone->GetProperty()->SetAmbient(0.35);
  this->Cone->GetProperty()->SetDiffuse(0.65);
  this->Cone->GetProperty()->SetSpecular(0.1);
  this->Cone->VisibilityOff();
}

void pqVesselTouchAgentActors::buildCursor()
{
  // A ring with a centre cross, in pixels around (0, 0); the actor's position moves it.
  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> lines;
  constexpr int segments = 24;
  for (int i = 0; i < segments; ++i)
  {
    const double a = 2.0 * kPi * i / segments;
    points->InsertNextPoint(kCursorRadius_px * std::cos(a), kCursorRadius_px * std::sin(a), 0.0);
  }
  lines->InsertNextCell(segments + 1);
  for (int i = 0; i <= segments; ++i)
  {
    lines->InsertCellPoint(i % segments);
  }
  const double arm = 0.5 * kCursorRadius_px;
  const double cross[4][3] = { { -arm, 0, 0 }, { arm, 0, 0 }, { 0, -arm, 0 }, { 0, arm, 0 } };
  for (int i = 0; i < 4; i += 2)
  {
    const vtkIdType a = points->InsertNextPoint(cross[i]);
    const vtkIdType b = points->InsertNextPoint(cross[i + 1]);
    const vtkIdType segment[2] = { a, b };
    lines->InsertNextCell(2, segment);
  }
  vtkNew<vtkPolyData> poly;
  poly->SetPoints(points);
  poly->SetLines(lines);
  vtkNew<vtkPolyDataMapper2D> mapper;
  mapper->SetInputData(poly);
  this->Cursor->SetMapper(mapper);
  this->Cursor->PickableOff();
  setColour(this->Cursor->GetProperty(), CursorRgb);
  this->Cursor->GetProperty()->SetLineWidth(2.0);
  this->Cursor->VisibilityOff();
}

void pqVesselTouchAgentActors::buildArrow()
{
  // Shaft 0-1, head 1-2 and 1-3; the points are rewritten per frame.
  for (int i = 0; i < 4; ++i)
  {
    this->ArrowPoints->InsertNextPoint(0.0, 0.0, 0.0);
  }
  vtkNew<vtkCellArray> lines;
  const vtkIdType segments[3][2] = { { 0, 1 }, { 1, 2 }, { 1, 3 } };
  for (const auto& segment : segments)
  {
    lines->InsertNextCell(2, segment);
  }
  this->ArrowPolyData->SetPoints(this->ArrowPoints);
  this->ArrowPolyData->SetLines(lines);
  vtkNew<vtkPolyDataMapper2D> mapper;
  mapper->SetInputData(this->ArrowPolyData);
  this->Arrow->SetMapper(mapper);
  this->Arrow->PickableOff();
  setColour(this->Arrow->GetProperty(), ArrowRgb);
  this->Arrow->GetProperty()->SetLineWidth(3.0);
  this->Arrow->VisibilityOff();
}

void pqVesselTouchAgentActors::addTo(vtkRenderer* renderer)
{
  renderer->AddActor(this->Cone);
  renderer->AddActor2D(this->Cursor);
  renderer->AddActor2D(this->Arrow);
}

void pqVesselTouchAgentActors::removeFrom(vtkRenderer* renderer)
{
  renderer->RemoveActor(this->Cone);
  renderer->RemoveActor2D(this->Cursor);
  renderer->RemoveActor2D(this->Arrow);
}

void pqVesselTouchAgentActors::setConeMatrix(const std::array<double, 16>& matrix)
{
  this->ConeMatrix->DeepCopy(matrix.data());
}

void pqVesselTouchAgentActors::setConeVisible(bool visible)
{
  this->Cone->SetVisibility(visible);
}

void pqVesselTouchAgentActors::setCursor(bool visible, double x_px, double y_px)
{
  this->Cursor->SetVisibility(visible);
  if (visible)
  {
    this->Cursor->SetPosition(x_px, y_px);
  }
}

void pqVesselTouchAgentActors::setForceArrow(bool visible,
  const double from_px[2],
  const double to_px[2])
{
  const double dx = to_px[0] - from_px[0];
  const double dy = to_px[1] - from_px[1];
  const double length = std::hypot(dx, dy);
  if (!visible || !(length >= 2.0))
  {
    this->Arrow->VisibilityOff();
    return;
  }
  // A head of a third of the length (at most 12 px), its barbs 25 degrees off the shaft.
  const double head = std::min(12.0, length / 3.0);
  const double ux = dx / length;
  const double uy = dy / length;
  const double c = std::cos(25.0 * kPi / 180.0);
  const double s = std::sin(25.0 * kPi / 180.0);
  this->ArrowPoints->SetPoint(0, from_px[0], from_px[1], 0.0);
  this->ArrowPoints->SetPoint(1, to_px[0], to_px[1], 0.0);
  this->ArrowPoints->SetPoint(
    2, to_px[0] - head * (c * ux - s * uy), to_px[1] - head * (s * ux + c * uy), 0.0);
  this->ArrowPoints->SetPoint(
    3, to_px[0] - head * (c * ux + s * uy), to_px[1] - head * (-s * ux + c * uy), 0.0);
  this->ArrowPoints->Modified();
  this->Arrow->VisibilityOn();
}

void pqVesselTouchAgentActors::hideForSelection()
{
  if (this->Hidden)
  {
    return;
  }
  this->SavedVisibility = { { this->Cone->GetVisibility() != 0,
    this->Cursor->GetVisibility() != 0,
    this->Arrow->GetVisibility() != 0 } };
  this->Cone->VisibilityOff();
  this->Cursor->VisibilityOff();
  this->Arrow->VisibilityOff();
  this->Hidden = true;
}

void pqVesselTouchAgentActors::restoreVisibility()
{
  if (!this->Hidden)
  {
    return;
  }
  this->Cone->SetVisibility(this->SavedVisibility[0]);
  this->Cursor->SetVisibility(this->SavedVisibility[1]);
  this->Arrow->SetVisibility(this->SavedVisibility[2]);
  this->Hidden = false;
}

#include "pqVesselTouchCenterlineOverlay.h"

#include "pqDataRepresentation.h"
#include "pqOutputPort.h"
#include "pqPipelineSource.h"
#include "pqRenderView.h"

#include "vtkActor.h"
#include "vtkAlgorithm.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSMRenderViewProxy.h"
#include "vtkSMSourceProxy.h"

namespace
{
/// Orange: far from any grey of the MIP, from the agent's blue cone and its green force arrow.
constexpr double kColour[3] = { 1.0, 0.55, 0.0 };
constexpr float kLineWidth_px = 3.0F;
/// The seed's marker: cyan, apart from the centerlines' orange and the grey MIP.
constexpr double kSeedColour[3] = { 0.0, 0.9, 1.0 };
/// Preview's candidate region: magenta, apart from every colour above and the agent's red, blue
/// and green; translucent, so the MIP's vessels show through it.
constexpr double kRegionColour[3] = { 1.0, 0.0, 0.85 };
constexpr double kRegionOpacity = 0.55;
} // namespace

pqVesselTouchCenterlineOverlay::pqVesselTouchCenterlineOverlay(QObject* parentObject)
  : QObject(parentObject)
{
  this->Overlay->SetInteractive(0);
  this->Overlay->SetPreserveColorBuffer(1); // the scene below stays
  this->Overlay->SetPreserveDepthBuffer(0); // and does not hide the lines
  this->Mapper->SetInputData(this->Lines);
  this->Mapper->ScalarVisibilityOff();
  this->Actor->SetMapper(this->Mapper);
  vtkProperty* property = this->Actor->GetProperty();
  property->SetColor(kColour[0], kColour[1], kColour[2]);
  property->SetLineWidth(kLineWidth_px);
  property->SetRenderLinesAsTubes(true);
  property->SetLighting(false);
  this->Overlay->AddActor(this->Actor);
  this->SeedSphere->SetThetaResolution(24);
  this->SeedSphere->SetPhiResolution(12);
  this->SeedMapper->SetInputConnection(this->SeedSphere->GetOutputPort());
  this->SeedActor->SetMapper(this->SeedMapper);
  this->SeedActor->GetProperty()->SetColor(kSeedColour[0], kSeedColour[1], kSeedColour[2]);
  this->SeedActor->GetProperty()->SetLighting(false); // one flat colour, like the lines
  this->SeedActor->SetVisibility(false);
  this->Overlay->AddActor(this->SeedActor);
  this->RegionMapper->SetInputData(this->Region);
  this->RegionMapper->ScalarVisibilityOff();
  this->RegionActor->SetMapper(this->RegionMapper);
  vtkProperty* region = this->RegionActor->GetProperty();
  region->SetColor(kRegionColour[0], kRegionColour[1], kRegionColour[2]);
  region->SetOpacity(kRegionOpacity);
  region->SetAmbient(0.6); // mostly flat, with enough shading to read the shape
  region->SetDiffuse(0.4);
  this->RegionActor->SetVisibility(false);
  this->Overlay->AddActor(this->RegionActor);
}

pqVesselTouchCenterlineOverlay::~pqVesselTouchCenterlineOverlay()
{
  this->detach();
}

bool pqVesselTouchCenterlineOverlay::attach(pqView* view)
{
  auto* renderView = qobject_cast<pqRenderView*>(view);
  vtkSMRenderViewProxy* proxy = renderView ? renderView->getRenderViewProxy() : nullptr;
  vtkRenderer* scene = proxy ? proxy->GetRenderer() : nullptr;
  vtkRenderWindow* window = proxy ? proxy->GetRenderWindow() : nullptr;
  if (view == this->View && window == this->Window && this->Window)
  {
    return true;
  }
  this->detach();
  if (!scene || !window)
  {
    return false;
  }
  this->View = view;
  this->Window = window;
  this->Layer = window->GetNumberOfLayers();
  window->SetNumberOfLayers(this->Layer + 1);
  this->Overlay->SetLayer(this->Layer);
  this->Overlay->SetActiveCamera(scene->GetActiveCamera());
  window->AddRenderer(this->Overlay);
  return true;
}

void pqVesselTouchCenterlineOverlay::detach()
{
  if (this->Window)
  {
    this->Window->RemoveRenderer(this->Overlay);
    if (this->Window->GetNumberOfLayers() == this->Layer + 1)
    {
      this->Window->SetNumberOfLayers(this->Layer);
    }
  }
  this->Window = nullptr;
  this->View = nullptr;
  this->Layer = -1;
}

void pqVesselTouchCenterlineOverlay::show(pqPipelineSource* centerline, pqView* view, bool visible)
{
  if (this->Centerline != centerline)
  {
    if (this->Centerline)
    {
      QObject::disconnect(this->Centerline, nullptr, this, nullptr);
    }
    this->Centerline = centerline;
  }
  auto* proxy = centerline ? vtkSMSourceProxy::SafeDownCast(centerline->getProxy()) : nullptr;
  auto* algorithm = proxy ? vtkAlgorithm::SafeDownCast(proxy->GetClientSideObject()) : nullptr;
  auto* output = algorithm ? vtkPolyData::SafeDownCast(algorithm->GetOutputDataObject(0)) : nullptr;
  if (output && visible)
  {
    this->Lines->ShallowCopy(output);
  }
  else
  {
    this->Lines->Initialize();
  }
  this->Lines->Modified();
  if (view && this->attach(view) && centerline)
  {
    // The Pipeline Browser's eye on the filter shows and hides the overlay too.
    if (pqDataRepresentation* repr = centerline->getRepresentation(0, view))
    {
      QObject::connect(repr,
        &pqDataRepresentation::visibilityChanged,
        this,
        &pqVesselTouchCenterlineOverlay::followRepresentation,
        Qt::UniqueConnection);
    }
  }
  this->followRepresentation();
}

void pqVesselTouchCenterlineOverlay::followRepresentation()
{
  pqDataRepresentation* repr =
    this->Centerline && this->View ? this->Centerline->getRepresentation(0, this->View) : nullptr;
  this->Actor->SetVisibility(repr && repr->isVisible() && this->Lines->GetNumberOfCells() > 0);
  if (this->View)
  {
    this->View->render();
  }
}

bool pqVesselTouchCenterlineOverlay::isShowing() const
{
  return this->Window && this->Actor->GetVisibility() && this->Lines->GetNumberOfCells() > 0;
}

void pqVesselTouchCenterlineOverlay::showSeed(pqView* view, const double* seed_mm, double radius_mm)
{
  if (seed_mm)
  {
    this->SeedSphere->SetCenter(seed_mm[0], seed_mm[1], seed_mm[2]);
    this->SeedSphere->SetRadius(radius_mm);
  }
  this->SeedActor->SetVisibility(seed_mm != nullptr);
  if (view && this->attach(view))
  {
    view->render();
  }
}

bool pqVesselTouchCenterlineOverlay::isShowingSeed() const
{
  return this->Window && this->SeedActor->GetVisibility();
}

void pqVesselTouchCenterlineOverlay::showRegion(pqView* view, vtkPolyData* surface)
{
  if (surface)
  {
    this->Region->ShallowCopy(surface);
  }
  else
  {
    this->Region->Initialize();
  }
  this->Region->Modified();
  this->RegionActor->SetVisibility(this->Region->GetNumberOfCells() > 0);
  if (view && this->attach(view))
  {
    view->render();
  }
  else if (this->View)
  {
    this->View->render();
  }
}

bool pqVesselTouchCenterlineOverlay::isShowingRegion() const
{
  return this->Window && this->RegionActor->GetVisibility();
}

#include "pqVesselTouchAgentOverlay.h"

#include "pqVesselTouchAgentActors.h"

#include "vtkCamera.h"
#include "vtkCommand.h"
#include "vtkImageData.h"
#include "vtkPointData.h"
#include "vtkProp.h"
#include "vtkPropCollection.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkRendererCollection.h"
#include "vtkTexture.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <vector>

pqVesselTouchAgentOverlay::pqVesselTouchAgentOverlay(pqVesselTouchAgentActors& actors)
  : Actors(actors)
{
  this->Overlay->SetPreserveColorBuffer(1); // normal frames: draw the agent over ParaView's image
  this->Overlay->SetPreserveDepthBuffer(0); // the agent is always on top of the MIP
  this->Overlay->InteractiveOff();          // picking and camera interaction stay with ParaView
  this->Texture->InterpolateOff();
  this->Texture->SetInputData(this->Image);
  this->Actors.addTo(this->Overlay);
  this->StartObserver = this->Overlay->AddObserver(
    vtkCommand::StartEvent, this, &pqVesselTouchAgentOverlay::onOverlayStart);
  this->EndObserver = this->Overlay->AddObserver(
    vtkCommand::EndEvent, this, &pqVesselTouchAgentOverlay::onOverlayEnd);
}

pqVesselTouchAgentOverlay::~pqVesselTouchAgentOverlay()
{
  this->detach();
  this->Overlay->RemoveObserver(this->StartObserver);
  this->Overlay->RemoveObserver(this->EndObserver);
  this->Actors.removeFrom(this->Overlay);
}

bool pqVesselTouchAgentOverlay::attach(vtkRenderWindow* window, vtkRenderer* scene)
{
  this->detach();
  if (!window || !scene)
  {
    return false;
  }
  this->Window = window;
  this->Scene = scene;
  this->Layer = window->GetNumberOfLayers();
  window->SetNumberOfLayers(this->Layer + 1);
  this->Overlay->SetLayer(this->Layer);
  this->Overlay->SetActiveCamera(scene->GetActiveCamera());
  window->AddRenderer(this->Overlay);
  this->Valid = false;
  return true;
}

void pqVesselTouchAgentOverlay::detach()
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
  this->Scene = nullptr;
  this->Layer = -1;
  this->Valid = false;
}

pqVesselTouchAgentOverlay::Stamp pqVesselTouchAgentOverlay::sceneStamp() const
{
  // What the captured image depends on: the camera (object and MTime, which ParaView's camera
  // properties and the interactor both move), the window size, and the last change of anything a
  // visible prop of the scene draws (mapper, input, property, transfer functions).
  vtkCamera* camera = this->Scene->GetActiveCamera();
  vtkMTimeType redraw = 0;
  vtkPropCollection* props = this->Scene->GetViewProps();
  vtkCollectionSimpleIterator it;
  props->InitTraversal(it);
  while (vtkProp* prop = props->GetNextProp(it))
  {
    if (prop->GetVisibility())
    {
      redraw = std::max(redraw, prop->GetRedrawMTime());
    }
  }
  const int* size = this->Window->GetSize();
  return { { static_cast<unsigned long long>(camera->GetMTime()),
    static_cast<unsigned long long>(reinterpret_cast<std::uintptr_t>(camera)),
    static_cast<unsigned long long>(size[0]),
    static_cast<unsigned long long>(size[1]),
    static_cast<unsigned long long>(redraw) } };
}

bool pqVesselTouchAgentOverlay::isCacheValid() const
{
  return this->Window && this->Scene && this->Valid && this->sceneStamp() == this->Captured;
}

void pqVesselTouchAgentOverlay::onOverlayStart()
{
  if (this->InCachedFrame || !this->Scene || !this->Window)
  {
    return; // an agent-only frame: the background is the cached texture
  }
  vtkCamera* camera = this->Scene->GetActiveCamera();
  if (this->Overlay->GetActiveCamera() != camera)
  {
    this->Overlay->SetActiveCamera(camera); // ParaView swapped its camera
  }
  if (this->Scene->GetSelector())
  {
    // A hardware-selection pass: the buffer holds ids, not an image to keep, and the agent must
    // not write colours over them.
    this->Actors.hideForSelection();
    return;
  }
  const int* size = this->Window->GetSize();
  if (size[0] <= 0 || size[1] <= 0)
  {
    return;
  }
  this->Window->GetRGBACharPixelData(0, 0, size[0] - 1, size[1] - 1, 0, this->Pixels);
  this->Image->SetDimensions(size[0], size[1], 1);
  this->Image->GetPointData()->SetScalars(this->Pixels);
  this->Image->Modified();
  ++this->Captures;
  this->LastSceneRender_ms = 1000.0 * this->Scene->GetLastRenderTimeInSeconds();
  this->Captured = this->sceneStamp();
  this->Valid = true;
}

void pqVesselTouchAgentOverlay::onOverlayEnd()
{
  this->Actors.restoreVisibility();
}

void pqVesselTouchAgentOverlay::renderCached()
{
  if (!this->Window)
  {
    return;
  }
  std::vector<vtkRenderer*> others;
  vtkRendererCollection* renderers = this->Window->GetRenderers();
  vtkCollectionSimpleIterator it;
  renderers->InitTraversal(it);
  while (vtkRenderer* renderer = renderers->GetNextRenderer(it))
  {
    if (renderer != this->Overlay.GetPointer() && renderer->GetDraw())
    {
      others.push_back(renderer);
      renderer->DrawOff();
    }
  }
  const auto start = std::chrono::steady_clock::now();
  this->InCachedFrame = true;
  this->Overlay->SetPreserveColorBuffer(0);
  this->Overlay->SetBackgroundTexture(this->Texture);
  this->Overlay->TexturedBackgroundOn();
  this->Window->Render();
  this->Overlay->TexturedBackgroundOff();
  this->Overlay->SetPreserveColorBuffer(1);
  this->InCachedFrame = false;
  for (vtkRenderer* renderer : others)
  {
    renderer->DrawOn();
  }
  ++this->CachedFrames;
  this->CachedSeconds +=
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

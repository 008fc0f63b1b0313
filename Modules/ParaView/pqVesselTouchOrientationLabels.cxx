#include "pqVesselTouchOrientationLabels.h"

#include "pqDataRepresentation.h"
#include "pqPipelineSource.h"
#include "pqRenderView.h"

#include "vtkCallbackCommand.h"
#include "vtkCamera.h"
#include "vtkCommand.h"
#include "vtkMath.h"
#include "vtkNew.h"
#include "vtkRenderer.h"
#include "vtkSMProperty.h"
#include "vtkSMPropertyHelper.h"
#include "vtkSMProxy.h"
#include "vtkSMRenderViewProxy.h"
#include "vtkTextActor.h"
#include "vtkTextProperty.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace
{
// A world axis counts in an edge's letters when it carries at least this share of the direction
// (|component| of the unit vector): 0.25 ~ 14.5 degrees off the screen plane's edge direction.
constexpr double kLetterComponent = 0.25;
constexpr int kFontSize_px = 20;
constexpr double kMargin_viewport = 0.015;
}

struct pqVesselTouchOrientationLabels::Internals
{
  std::array<vtkNew<vtkTextActor>, 4> Actors;
  vtkNew<vtkCallbackCommand> BeforeRender;
  vtkRenderer* Renderer = nullptr;
  unsigned long Observer = 0;
};

pqVesselTouchOrientationLabels::pqVesselTouchOrientationLabels(pqRenderView* view)
  : QObject(view)
  , Internal(new Internals)
  , View(view)
{
  this->setObjectName("VesselTouchOrientationLabels");
  // Edge -> anchor in normalized viewport coordinates and text justification.
  const double anchors[4][2] = { { 0.5, 1.0 - kMargin_viewport },
    { 0.5, kMargin_viewport },
    { kMargin_viewport, 0.5 },
    { 1.0 - kMargin_viewport, 0.5 } };
  for (int edge = 0; edge < 4; ++edge)
  {
    vtkTextActor* actor = this->Internal->Actors[edge];
    actor->GetPositionCoordinate()->SetCoordinateSystemToNormalizedViewport();
    actor->SetPosition(anchors[edge][0], anchors[edge][1]);
    vtkTextProperty* property = actor->GetTextProperty();
    property->SetFontSize(kFontSize_px);
    property->SetBold(true);
    property->SetColor(1.0, 0.85, 0.2); // amber: readable over the grey MIP and the black
    property->SetJustification(edge == Left    ? VTK_TEXT_LEFT
                               : edge == Right ? VTK_TEXT_RIGHT
                                               : VTK_TEXT_CENTERED);
    property->SetVerticalJustification(edge == Top      ? VTK_TEXT_TOP
                                       : edge == Bottom ? VTK_TEXT_BOTTOM
                                                        : VTK_TEXT_CENTERED);
    actor->SetVisibility(false);
    actor->PickableOff();
  }
  this->Internal->Renderer = view->getRenderViewProxy()->GetRenderer();
  if (this->Internal->Renderer)
  {
    for (auto& actor : this->Internal->Actors)
    {
      this->Internal->Renderer->AddActor2D(actor);
    }
    this->Internal->BeforeRender->SetClientData(this);
    this->Internal->BeforeRender->SetCallback([](vtkObject*, unsigned long, void* self, void*)
      { static_cast<pqVesselTouchOrientationLabels*>(self)->update(); });
    this->Internal->Observer =
      this->Internal->Renderer->AddObserver(vtkCommand::StartEvent, this->Internal->BeforeRender);
  }
}

pqVesselTouchOrientationLabels::~pqVesselTouchOrientationLabels()
{
  if (this->Internal->Renderer && this->View)
  {
    this->Internal->Renderer->RemoveObserver(this->Internal->Observer);
    for (auto& actor : this->Internal->Actors)
    {
      this->Internal->Renderer->RemoveActor2D(actor);
    }
  }
}

pqVesselTouchOrientationLabels* pqVesselTouchOrientationLabels::show(pqPipelineSource* source,
  pqRenderView* view)
{
  if (!source || !view)
  {
    return nullptr;
  }
  auto* labels =
    view->findChild<pqVesselTouchOrientationLabels*>(QString(), Qt::FindDirectChildrenOnly);
  if (!labels)
  {
    labels = new pqVesselTouchOrientationLabels(view);
  }
  labels->Source = source;
  vtkSMProperty* frame = source->getProxy()->GetProperty("OutputFrame");
  labels->Ras = frame && vtkSMPropertyHelper(frame).GetAsInt() == 1;
  labels->update();
  return labels;
}

QString pqVesselTouchOrientationLabels::letters(const double direction_World[3], bool ras)
{
  // World axis -> (letter toward +axis, letter toward -axis).
  static const char* const lps[3][2] = { { "L", "R" }, { "P", "A" }, { "S", "I" } };
  static const char* const rasLetters[3][2] = { { "R", "L" }, { "A", "P" }, { "S", "I" } };
  std::array<int, 3> axes = { 0, 1, 2 };
  std::sort(axes.begin(),
    axes.end(),
    [direction_World](int a, int b)
    { return std::abs(direction_World[a]) > std::abs(direction_World[b]); });
  QString text;
  for (int axis : axes)
  {
    const double component = direction_World[axis];
    if (std::abs(component) >= kLetterComponent)
    {
      const int end = component > 0.0 ? 0 : 1;
      text += QLatin1String(ras ? rasLetters[axis][end] : lps[axis][end]);
    }
  }
  return text;
}

QString pqVesselTouchOrientationLabels::text(Edge edge) const
{
  vtkTextActor* actor = this->Internal->Actors[edge];
  return actor->GetVisibility() && actor->GetInput() ? QString(actor->GetInput()) : QString();
}

void pqVesselTouchOrientationLabels::update()
{
  pqDataRepresentation* representation =
    (this->Source && this->View) ? this->Source->getRepresentation(this->View) : nullptr;
  const bool shown = representation && representation->isVisible() && this->Internal->Renderer;
  if (!shown)
  {
    for (auto& actor : this->Internal->Actors)
    {
      actor->SetVisibility(false);
    }
    return;
  }
  vtkCamera* camera = this->Internal->Renderer->GetActiveCamera();
  double up[3];
  double forward[3];
  camera->GetViewUp(up);
  camera->GetDirectionOfProjection(forward);
  // The screen's up is the view up made orthogonal to the direction of projection.
  double along = vtkMath::Dot(up, forward);
  for (int i = 0; i < 3; ++i)
  {
    up[i] -= along * forward[i];
  }
  vtkMath::Normalize(up);
  double right[3];
  vtkMath::Cross(forward, up, right);
  vtkMath::Normalize(right);
  const double* directions[4] = { up, nullptr, nullptr, right };
  double down[3] = { -up[0], -up[1], -up[2] };
  double left[3] = { -right[0], -right[1], -right[2] };
  directions[Bottom] = down;
  directions[Left] = left;
  for (int edge = 0; edge < 4; ++edge)
  {
    const QByteArray text = letters(directions[edge], this->Ras).toLatin1();
    vtkTextActor* actor = this->Internal->Actors[edge];
    if (!actor->GetInput() || text != actor->GetInput())
    {
      actor->SetInput(text.constData());
    }
    actor->SetVisibility(!text.isEmpty());
  }
}

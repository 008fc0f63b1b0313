#include "pqVesselTouchSeedPicker.h"

#include "pqVesselTouchRemoteRayProbe.h"

#include "vtouchRayMaximum.h"

#include "pqPipelineSource.h"
#include "pqRenderView.h"

#include "vtkAlgorithm.h"
#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkPointData.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSMRenderViewProxy.h"
#include "vtkSMSourceProxy.h"

#include <QEvent>
#include <QMouseEvent>
#include <QWidget>

namespace
{
/// A click that moved more than this many pixels between press and release is a drag.
constexpr int kClickTolerance_px = 4;
} // namespace

pqVesselTouchSeedPicker::pqVesselTouchSeedPicker(QObject* parentObject)
  : QObject(parentObject)
{
}

pqVesselTouchSeedPicker::~pqVesselTouchSeedPicker()
{
  this->disarm();
}

void pqVesselTouchSeedPicker::arm(pqRenderView* view, pqPipelineSource* volume)
{
  this->disarm();
  if (!view || !view->widget())
  {
    Q_EMIT this->pickFailed(tr("Pick seed: no render view is active."));
    return;
  }
  this->View = view;
  this->Volume = volume;
  this->WatchedWidget = view->widget();
  this->WatchedWidget->installEventFilter(this);
}

void pqVesselTouchSeedPicker::disarm()
{
  if (this->WatchedWidget)
  {
    this->WatchedWidget->removeEventFilter(this);
  }
  this->WatchedWidget = nullptr;
}

bool pqVesselTouchSeedPicker::isArmed() const
{
  return this->WatchedWidget != nullptr;
}

bool pqVesselTouchSeedPicker::eventFilter(QObject* watched, QEvent* event)
{
  if (watched != this->WatchedWidget)
  {
    return this->QObject::eventFilter(watched, event);
  }
  if (event->type() == QEvent::MouseButtonPress)
  {
    auto* mouse = static_cast<QMouseEvent*>(event);
    if (mouse->button() == Qt::LeftButton)
    {
      this->PressPosition = mouse->pos();
      return true; // the camera stays where the user aimed
    }
  }
  else if (event->type() == QEvent::MouseButtonRelease)
  {
    auto* mouse = static_cast<QMouseEvent*>(event);
    if (mouse->button() == Qt::LeftButton)
    {
      if ((mouse->pos() - this->PressPosition).manhattanLength() <= kClickTolerance_px)
      {
        QPointer<pqRenderView> view = this->View;
        QPointer<pqPipelineSource> volume = this->Volume;
        this->disarm();
        this->pickAt(view, volume, mouse->pos());
      }
      return true;
    }
  }
  else if (event->type() == QEvent::MouseMove &&
           (static_cast<QMouseEvent*>(event)->buttons() & Qt::LeftButton))
  {
    return true;
  }
  return this->QObject::eventFilter(watched, event);
}

bool pqVesselTouchSeedPicker::clickRay(pqRenderView* view,
  const QPoint& position,
  std::array<double, 3>& near_mm,
  std::array<double, 3>& far_mm)
{
  vtkSMRenderViewProxy* viewProxy = view ? view->getRenderViewProxy() : nullptr;
  vtkRenderer* renderer = viewProxy ? viewProxy->GetRenderer() : nullptr;
  QWidget* widget = view ? view->widget() : nullptr;
  if (!renderer || !widget || widget->height() <= 0)
  {
    return false;
  }
  // Qt: logical pixels from the top-left; VTK display: device pixels from the bottom-left.
  const double ratio = widget->devicePixelRatioF();
  const int* size = renderer->GetRenderWindow()->GetSize();
  const double x = position.x() * ratio;
  const double y =
    (size && size[1] > 0 ? size[1] : widget->height() * ratio) - position.y() * ratio - 1;
  std::array<double, 3>* ends[2] = { &near_mm, &far_mm };
  for (int e = 0; e < 2; ++e)
  {
    renderer->SetDisplayPoint(x, y, e == 0 ? 0.0 : 1.0);
    renderer->DisplayToWorld();
    const double* w = renderer->GetWorldPoint();
    if (w[3] == 0.0)
    {
      return false;
    }
    for (int i = 0; i < 3; ++i)
    {
      (*ends[e])[i] = w[i] / w[3];
    }
  }
  return true;
}

bool pqVesselTouchSeedPicker::pickAt(pqRenderView* view,
  pqPipelineSource* volume,
  const QPoint& position)
{
  auto* proxy = volume ? vtkSMSourceProxy::SafeDownCast(volume->getProxy()) : nullptr;
  auto* algorithm = proxy ? vtkAlgorithm::SafeDownCast(proxy->GetClientSideObject()) : nullptr;
  if (!volume)
  {
    Q_EMIT this->pickFailed(tr("Pick seed: choose a volume first."));
    return false;
  }
  if (!algorithm)
  {
    // Connected to a separate pvserver: the voxels are on its ranks; probe the ray there.
    std::array<double, 3> near_mm{};
    std::array<double, 3> far_mm{};
    if (!clickRay(view, position, near_mm, far_mm))
    {
      Q_EMIT this->pickFailed(tr("Pick seed: no render view to pick in."));
      return false;
    }
    const pqVesselTouchRemoteRayProbe::Result remote =
      pqVesselTouchRemoteRayProbe::find(volume, near_mm.data(), far_mm.data());
    if (!remote.found)
    {
      Q_EMIT this->pickFailed(remote.error);
      return false;
    }
    Q_EMIT this->seedPicked(remote.seed_mm[0], remote.seed_mm[1], remote.seed_mm[2], remote.value);
    return true;
  }
  proxy->UpdatePipeline();
  vtkImageData* image = vtkImageData::SafeDownCast(algorithm->GetOutputDataObject(0));
  vtkDataArray* scalars = image ? image->GetPointData()->GetScalars() : nullptr;
  if (!scalars)
  {
    Q_EMIT this->pickFailed(tr("Pick seed: the volume has no image scalars."));
    return false;
  }
  std::array<double, 3> near_mm{};
  std::array<double, 3> far_mm{};
  if (!clickRay(view, position, near_mm, far_mm))
  {
    Q_EMIT this->pickFailed(tr("Pick seed: no render view to pick in."));
    return false;
  }
  std::array<double, 3> start_Index{};
  std::array<double, 3> end_Index{};
  image->TransformPhysicalPointToContinuousIndex(near_mm.data(), start_Index.data());
  image->TransformPhysicalPointToContinuousIndex(far_mm.data(), end_Index.data());
  const int* extent = image->GetExtent();
  std::array<int, 3> dimensions{};
  for (int i = 0; i < 3; ++i)
  {
    start_Index[i] -= extent[2 * i];
    end_Index[i] -= extent[2 * i];
    dimensions[i] = extent[2 * i + 1] - extent[2 * i] + 1;
  }
  const auto sample = [&](int i, int j, int k)
  {
    const int ijk[3] = { i + extent[0], j + extent[2], k + extent[4] };
    return scalars->GetComponent(image->ComputePointId(const_cast<int*>(ijk)), 0);
  };
  const vtouch::RayMaximumResult best =
    vtouch::RayMaximum::find(dimensions, start_Index, end_Index, sample);
  if (!best.found)
  {
    Q_EMIT this->pickFailed(tr("Pick seed: the click's ray misses the volume."));
    return false;
  }
  double seed_mm[3];
  image->TransformIndexToPhysicalPoint(
    best.index[0] + extent[0], best.index[1] + extent[2], best.index[2] + extent[4], seed_mm);
  Q_EMIT this->seedPicked(seed_mm[0], seed_mm[1], seed_mm[2], best.value);
  return true;
}

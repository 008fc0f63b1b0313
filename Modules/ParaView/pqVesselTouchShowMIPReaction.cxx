#include "pqVesselTouchShowMIPReaction.h"

#include "pqVesselTouchVolumeCheck.h"

#include "pqActiveObjects.h"
#include "pqOutputPort.h"
#include "pqPipelineSource.h"
#include "pqRenderView.h"
#include "pqView.h"

#include "vtkDataObject.h"
#include "vtkDataSetAttributes.h"
#include "vtkNew.h"
#include "vtkPVArrayInformation.h"
#include "vtkPVDataInformation.h"
#include "vtkPVDataSetAttributesInformation.h"
#include "vtkSMPVRepresentationProxy.h"
#include "vtkSMParaViewPipelineControllerWithRendering.h"
#include "vtkSMPropertyHelper.h"
#include "vtkSMSourceProxy.h"
#include "vtkSMTransferFunctionProxy.h"
#include "vtkSMViewProxy.h"

#include <QtDebug>

pqVesselTouchShowMIPReaction::pqVesselTouchShowMIPReaction(QAction* parentObject)
  : Superclass(parentObject)
{
  QObject::connect(&pqActiveObjects::instance(),
    &pqActiveObjects::sourceChanged,
    this,
    &pqVesselTouchShowMIPReaction::updateEnableState);
  QObject::connect(&pqActiveObjects::instance(),
    &pqActiveObjects::viewChanged,
    this,
    &pqVesselTouchShowMIPReaction::updateEnableState);
  this->updateEnableState();
}

void pqVesselTouchShowMIPReaction::updateEnableState()
{
  pqPipelineSource* source = pqActiveObjects::instance().activeSource();
  pqView* view = pqActiveObjects::instance().activeView();
  if (source != this->Watched)
  {
    // The active source's data may arrive (Apply) or change after it became active.
    if (this->Watched)
    {
      QObject::disconnect(this->Watched, nullptr, this, nullptr);
    }
    this->Watched = source;
    if (source)
    {
      QObject::connect(source,
        QOverload<pqPipelineSource*>::of(&pqPipelineSource::dataUpdated),
        this,
        &pqVesselTouchShowMIPReaction::updateEnableState);
    }
  }
  // A 2D image (a PNG, one slice) is refused here: its "MIP" means nothing and renders slowly.
  const QString problem = source ? pqVesselTouchVolumeCheck::problem(source) : QString();
  const bool renderView = qobject_cast<pqRenderView*>(view) != nullptr;
  QAction* action = this->parentAction();
  action->setEnabled(source && renderView && problem.isEmpty());
  QString tip = tr("Show the active 3D volume as a maximum-intensity projection");
  if (!source)
  {
    tip += tr(" (select a volume in the Pipeline Browser)");
  }
  else if (!problem.isEmpty())
  {
    tip += QStringLiteral(": ") + problem;
  }
  else if (!renderView)
  {
    tip += tr(" (make a render view active)");
  }
  action->setToolTip(tip);
}

void pqVesselTouchShowMIPReaction::onTriggered()
{
  showAsMIP(pqActiveObjects::instance().activeSource(), pqActiveObjects::instance().activeView());
}

bool pqVesselTouchShowMIPReaction::showAsMIP(pqPipelineSource* source, pqView* view)
{
  if (!source || !qobject_cast<pqRenderView*>(view))
  {
    qWarning("VesselTouch: Show as MIP needs an active source and an active render view.");
    return false;
  }
  source->getSourceProxy()->UpdatePipeline();
  const QString problem = pqVesselTouchVolumeCheck::problem(source);
  if (!problem.isEmpty())
  {
    qWarning().noquote() << "VesselTouch: Show as MIP:" << problem;
    return false;
  }
  vtkPVDataInformation* info = source->getOutputPort(0)->getDataInformation();
  vtkPVArrayInformation* scalars =
    info->GetPointDataInformation()->GetAttributeInformation(vtkDataSetAttributes::SCALARS);

  vtkNew<vtkSMParaViewPipelineControllerWithRendering> controller;
  vtkSMProxy* repr = controller->Show(source->getSourceProxy(), 0, view->getViewProxy());
  if (!repr)
  {
    qWarning("VesselTouch: the view cannot show this source.");
    return false;
  }
  vtkSMRepresentationProxy::SetRepresentationType(repr, "Volume");
  // ParaView names only Composite/Isosurface/Slice; maximum intensity is blend mode 1.
  vtkSMPropertyHelper(repr, "BlendMode").Set(1);
  vtkSMPVRepresentationProxy::SetScalarColoring(repr, scalars->GetName(), vtkDataObject::POINT);
  vtkSMPVRepresentationProxy::RescaleTransferFunctionToDataRange(repr, false, true);
  vtkSMProxy* lut = vtkSMPropertyHelper(repr, "LookupTable", true).GetAsProxy();
  if (lut)
  {
    vtkSMTransferFunctionProxy::ApplyPreset(lut, "Grayscale", false);
    double range[2] = { 0.0, 1.0 };
    scalars->GetComponentRange(0, range);
    vtkSMProxy* opacity = vtkSMPropertyHelper(lut, "ScalarOpacityFunction", true).GetAsProxy();
    if (opacity)
    {
      // A linear ramp: the brightest voxel along each ray shows as its own grey level.
      const double points[8] = { range[0], 0.0, 0.5, 0.0, range[1], 1.0, 0.5, 0.0 };
      vtkSMPropertyHelper(opacity, "Points").Set(points, 8);
      opacity->UpdateVTKObjects();
    }
    lut->UpdateVTKObjects();
  }
  repr->UpdateVTKObjects();
  view->resetDisplay();
  view->render();
  return true;
}

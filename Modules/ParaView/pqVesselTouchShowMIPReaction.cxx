#include "pqVesselTouchShowMIPReaction.h"

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
  this->parentAction()->setEnabled(source && qobject_cast<pqRenderView*>(view));
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
  vtkPVDataInformation* info = source->getOutputPort(0)->getDataInformation();
  if (!info || info->GetDataSetType() != VTK_IMAGE_DATA || info->GetNumberOfPoints() == 0)
  {
    qWarning() << "VesselTouch: Show as MIP needs a non-empty image (vtkImageData); "
               << source->getSMName() << "is not one.";
    return false;
  }
  vtkPVArrayInformation* scalars =
    info->GetPointDataInformation()->GetAttributeInformation(vtkDataSetAttributes::SCALARS);
  if (!scalars || !scalars->GetName())
  {
    qWarning() << "VesselTouch: Show as MIP needs point scalars on" << source->getSMName();
    return false;
  }

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

#include "pqVesselTouchShowMIPReaction.h"

#include "pqVesselTouchBlendModeNames.h"
#include "pqVesselTouchOrientationLabels.h"
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
#include "vtkSMProperty.h"
#include "vtkSMPropertyHelper.h"
#include "vtkSMSourceProxy.h"
#include "vtkSMTransferFunctionProxy.h"
#include "vtkSMViewProxy.h"

#include <QtDebug>

#include <algorithm>

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

void pqVesselTouchShowMIPReaction::setRadiologicalCamera(pqPipelineSource* source,
  vtkSMProxy* viewProxy)
{
  // Only patient images (VesselTouch's readers, OutputFrame LPS = 0 or RAS = 1) have a patient
  // orientation; a phantom keeps ParaView's default view.
  vtkSMProperty* frame = source->getProxy()->GetProperty("OutputFrame");
  if (!frame)
  {
    return;
  }
  const bool ras = vtkSMPropertyHelper(frame).GetAsInt() == 1;
  // The radiological axial view: seen from the feet (looking toward +z, superior), anterior up,
  // the patient's left on the screen's right. LPS: +x is left, so up = -y (anterior); RAS: +x is
  // right, up = +y. The camera's right (direction x up) is then +x (LPS) or -x (RAS).
  vtkPVDataInformation* info = source->getOutputPort(0)->getDataInformation();
  double bounds[6];
  info->GetBounds(bounds);
  double centre[3];
  double size = 0.0;
  for (int i = 0; i < 3; ++i)
  {
    centre[i] = 0.5 * (bounds[2 * i] + bounds[2 * i + 1]);
    size = std::max(size, bounds[2 * i + 1] - bounds[2 * i]);
  }
  const double position[3] = { centre[0], centre[1], centre[2] - 3.0 * std::max(size, 1.0) };
  const double up[3] = { 0.0, ras ? 1.0 : -1.0, 0.0 };
  vtkSMPropertyHelper(viewProxy, "CameraFocalPoint").Set(centre, 3);
  vtkSMPropertyHelper(viewProxy, "CameraPosition").Set(position, 3);
  vtkSMPropertyHelper(viewProxy, "CameraViewUp").Set(up, 3);
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
  // Copies: showing and colouring update the pipeline, which replaces the data information.
  const QByteArray scalarName(scalars->GetName());
  double range[2] = { 0.0, 1.0 };
  scalars->GetComponentRange(0, range);

  vtkNew<vtkSMParaViewPipelineControllerWithRendering> controller;
  vtkSMProxy* repr = controller->Show(source->getSourceProxy(), 0, view->getViewProxy());
  if (!repr)
  {
    qWarning("VesselTouch: the view cannot show this source.");
    return false;
  }
  vtkSMRepresentationProxy::SetRepresentationType(repr, "Volume");
  // ParaView names only Composite/Isosurface/Slice; maximum intensity is blend mode 1, named in the
  // Properties panel's list so the panel shows "Maximum Intensity" rather than "Composite".
  pqVesselTouchBlendModeNames::nameMaximumIntensity(repr);
  vtkSMPropertyHelper(repr, "BlendMode").Set(pqVesselTouchBlendModeNames::MaximumIntensity);
  vtkSMPVRepresentationProxy::SetScalarColoring(repr, scalarName.constData(), vtkDataObject::POINT);
  vtkSMPVRepresentationProxy::RescaleTransferFunctionToDataRange(repr, false, true);
  vtkSMProxy* lut = vtkSMPropertyHelper(repr, "LookupTable", true).GetAsProxy();
  if (lut)
  {
    vtkSMTransferFunctionProxy::ApplyPreset(lut, "Grayscale", false);
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
  // A MIP is read on black, from the first frame (not only once tracing starts).
  vtkSMProxy* viewProxy = view->getProxy();
  const double black[3] = { 0.0, 0.0, 0.0 };
  vtkSMPropertyHelper(viewProxy, "UseColorPaletteForBackground", /*quiet=*/true).Set(0);
  vtkSMPropertyHelper(viewProxy, "Background").Set(black, 3);
  setRadiologicalCamera(source, viewProxy);
  if (source->getProxy()->GetProperty("OutputFrame"))
  {
    // Patient images get L/R/A/P/S/I letters at the view's edges (a view annotation).
    pqVesselTouchOrientationLabels::show(source, qobject_cast<pqRenderView*>(view));
  }
  viewProxy->UpdateVTKObjects();
  view->resetDisplay();
  view->render();
  return true;
}

#include "pqVesselTouchCenterlineExtraction.h"

#include "pqVesselTouchCenterlineOverlay.h"
#include "pqVesselTouchVolumeCheck.h"

#include "pqApplicationCore.h"
#include "pqObjectBuilder.h"
#include "pqOutputPort.h"
#include "pqPipelineSource.h"
#include "pqProgressManager.h"
#include "pqView.h"

#include "vtkAlgorithm.h"
#include "vtkDataArray.h"
#include "vtkDataObject.h"
#include "vtkFieldData.h"
#include "vtkNew.h"
#include "vtkPVDataInformation.h"
#include "vtkSMPVRepresentationProxy.h"
#include "vtkSMParaViewPipelineControllerWithRendering.h"
#include "vtkSMPropertyHelper.h"
#include "vtkSMSourceProxy.h"
#include "vtkSMViewProxy.h"
#include "vtkStringArray.h"

namespace
{
/// The centerlines' colour: orange, far from any grey of the MIP (and from the agent's green
/// force arrow and blue cone).
constexpr double kCenterlineColour[3] = { 1.0, 0.55, 0.0 };
/// Line width of the centerlines drawn as tubes, pixels.
constexpr double kCenterlineWidth_px = 3.0;

/// The filter's client-side output (builtin session), null otherwise.
vtkDataObject* clientOutput(pqPipelineSource* filter)
{
  auto* proxy = filter ? vtkSMSourceProxy::SafeDownCast(filter->getProxy()) : nullptr;
  auto* algorithm = proxy ? vtkAlgorithm::SafeDownCast(proxy->GetClientSideObject()) : nullptr;
  return algorithm ? algorithm->GetOutputDataObject(0) : nullptr;
}
} // namespace

pqVesselTouchCenterlineExtraction::pqVesselTouchCenterlineExtraction(QObject* parentObject)
  : QObject(parentObject)
  , Overlay(new pqVesselTouchCenterlineOverlay(this))
{
}

pqVesselTouchCenterlineExtraction::~pqVesselTouchCenterlineExtraction() = default;

pqPipelineSource* pqVesselTouchCenterlineExtraction::centerline() const
{
  return this->Centerline;
}

void pqVesselTouchCenterlineExtraction::setCenterline(pqPipelineSource* filter)
{
  this->Centerline = filter;
}

const pqVesselTouchExtractionResult& pqVesselTouchCenterlineExtraction::result() const
{
  return this->Result;
}

pqPipelineSource* pqVesselTouchCenterlineExtraction::filterFor(pqPipelineSource* volume)
{
  if (this->Centerline &&
      vtkSMPropertyHelper(this->Centerline->getProxy(), "Input").GetAsProxy() == volume->getProxy())
  {
    return this->Centerline;
  }
  this->Centerline = pqApplicationCore::instance()->getObjectBuilder()->createFilter(
    "filters", "VesselCenterline", volume);
  return this->Centerline;
}

void pqVesselTouchCenterlineExtraction::showInView(pqPipelineSource* centerline,
  pqView* view,
  bool visible)
{
  if (!centerline || !view)
  {
    return;
  }
  vtkNew<vtkSMParaViewPipelineControllerWithRendering> controller;
  vtkSMViewProxy* viewProxy = view->getViewProxy();
  auto* source = vtkSMSourceProxy::SafeDownCast(centerline->getProxy());
  if (!visible)
  {
    controller->Hide(source, 0, viewProxy);
  }
  else if (vtkSMProxy* repr = controller->Show(source, 0, viewProxy))
  {
    // The representation (the Pipeline Browser's eye, the Properties panel) is drawn under the
    // MIP's vessels; the overlay draws the same lines on top.
    vtkSMPVRepresentationProxy::SetScalarColoring(repr, nullptr, vtkDataObject::POINT);
    vtkSMPropertyHelper(repr, "AmbientColor").Set(kCenterlineColour, 3);
    vtkSMPropertyHelper(repr, "DiffuseColor").Set(kCenterlineColour, 3);
    vtkSMPropertyHelper(repr, "LineWidth").Set(kCenterlineWidth_px);
    vtkSMPropertyHelper(repr, "RenderLinesAsTubes", /*quiet=*/true).Set(1);
    repr->UpdateVTKObjects();
  }
  this->Overlay->show(centerline, view, visible);
}

bool pqVesselTouchCenterlineExtraction::isShowingCenterline() const
{
  return this->Overlay->isShowing();
}

pqPipelineSource* pqVesselTouchCenterlineExtraction::extract(pqPipelineSource* volume,
  const double seed_mm[3],
  bool automatic,
  double lowerThreshold,
  double upperThreshold,
  pqView* view)
{
  this->Result = pqVesselTouchExtractionResult();
  const QString problem = pqVesselTouchVolumeCheck::problem(volume);
  if (!problem.isEmpty())
  {
    Q_EMIT this->failed(problem);
    return nullptr;
  }
  pqPipelineSource* filter = this->filterFor(volume);
  if (!filter)
  {
    Q_EMIT this->failed(tr("The VesselCenterline filter is not available."));
    return nullptr;
  }
  vtkSMProxy* proxy = filter->getProxy();
  vtkSMPropertyHelper(proxy, "UseSeedPoint").Set(1);
  vtkSMPropertyHelper(proxy, "SeedPoint").Set(seed_mm, 3);
  const bool hasAutomatic = proxy->GetProperty("AutomaticIntensityRange") != nullptr;
  if (hasAutomatic)
  {
    vtkSMPropertyHelper(proxy, "AutomaticIntensityRange").Set(automatic ? 1 : 0);
  }
  if (!automatic || !hasAutomatic)
  {
    vtkSMPropertyHelper(proxy, "LowerThreshold").Set(lowerThreshold);
    vtkSMPropertyHelper(proxy, "UpperThreshold").Set(upperThreshold);
  }
  proxy->UpdateVTKObjects();

  pqProgressManager* progressManager = pqApplicationCore::instance()->getProgressManager();
  QMetaObject::Connection connection;
  if (progressManager)
  {
    connection = QObject::connect(progressManager,
      &pqProgressManager::progress,
      this,
      [this](const QString&, int percent) { Q_EMIT this->progress(percent); });
  }
  Q_EMIT this->progress(0);
  vtkSMSourceProxy::SafeDownCast(proxy)->UpdatePipeline();
  QObject::disconnect(connection);
  filter->setModifiedState(pqProxy::UNMODIFIED);

  this->readResult(filter);
  // The view follows: the new centerlines at once, or nothing stale where none were found.
  this->showInView(filter, view, this->Result.paths > 0);
  if (this->Result.paths <= 0)
  {
    Q_EMIT this->failed(
      !this->Result.message.isEmpty()
        ? this->Result.message
        : tr("No centerline at this seed and intensity range: is the seed inside a vessel, and "
             "the lower bound below the vessel's intensity?"));
    return filter;
  }
  Q_EMIT this->progress(100);
  Q_EMIT this->finished(filter, this->Result.paths);
  return filter;
}

const pqVesselTouchExtractionResult& pqVesselTouchCenterlineExtraction::readResult(
  pqPipelineSource* filter)
{
  this->Result = pqVesselTouchExtractionResult();
  vtkPVDataInformation* info = filter ? filter->getOutputPort(0)->getDataInformation() : nullptr;
  this->Result.paths = info ? static_cast<int>(info->GetNumberOfCells()) : 0;
  if (vtkDataObject* output = clientOutput(filter))
  {
    vtkFieldData* fields = output->GetFieldData();
    vtkDataArray* used = fields ? fields->GetArray("IntensityRangeUsed") : nullptr;
    if (used && used->GetNumberOfTuples() * used->GetNumberOfComponents() >= 2)
    {
      this->Result.rangeKnown = true;
      this->Result.rangeUsed[0] = used->GetComponent(0, 0);
      this->Result.rangeUsed[1] =
        used->GetNumberOfComponents() >= 2 ? used->GetComponent(0, 1) : used->GetComponent(1, 0);
    }
    vtkDataArray* automaticUsed = fields ? fields->GetArray("IntensityRangeAutomatic") : nullptr;
    this->Result.rangeAutomatic = automaticUsed && automaticUsed->GetNumberOfTuples() > 0 &&
                                  automaticUsed->GetComponent(0, 0) != 0.0;
    auto* message = fields
                      ? vtkStringArray::SafeDownCast(fields->GetAbstractArray("ExtractionMessage"))
                      : nullptr;
    if (message && message->GetNumberOfValues() > 0)
    {
      this->Result.message = QString::fromStdString(message->GetValue(0));
    }
  }
  return this->Result;
}

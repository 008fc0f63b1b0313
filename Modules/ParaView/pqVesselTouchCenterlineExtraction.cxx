#include "pqVesselTouchCenterlineExtraction.h"

#include "pqApplicationCore.h"
#include "pqObjectBuilder.h"
#include "pqOutputPort.h"
#include "pqPipelineSource.h"
#include "pqProgressManager.h"

#include "vtkPVDataInformation.h"
#include "vtkSMPropertyHelper.h"
#include "vtkSMSourceProxy.h"

pqVesselTouchCenterlineExtraction::pqVesselTouchCenterlineExtraction(QObject* parentObject)
  : QObject(parentObject)
{
}

pqVesselTouchCenterlineExtraction::~pqVesselTouchCenterlineExtraction() = default;

pqPipelineSource* pqVesselTouchCenterlineExtraction::centerline() const
{
  return this->Centerline;
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

pqPipelineSource* pqVesselTouchCenterlineExtraction::extract(pqPipelineSource* volume,
  const double seed_mm[3],
  double lowerThreshold,
  double upperThreshold)
{
  if (!volume)
  {
    Q_EMIT this->failed(tr("Extract centerlines: choose a volume first."));
    return nullptr;
  }
  pqPipelineSource* filter = this->filterFor(volume);
  if (!filter)
  {
    Q_EMIT this->failed(tr("Extract centerlines: the VesselCenterline filter is not available."));
    return nullptr;
  }
  vtkSMProxy* proxy = filter->getProxy();
  vtkSMPropertyHelper(proxy, "UseSeedPoint").Set(1);
  vtkSMPropertyHelper(proxy, "SeedPoint").Set(seed_mm, 3);
  vtkSMPropertyHelper(proxy, "LowerThreshold").Set(lowerThreshold);
  vtkSMPropertyHelper(proxy, "UpperThreshold").Set(upperThreshold);
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
  Q_EMIT this->progress(100);

  vtkPVDataInformation* info = filter->getOutputPort(0)->getDataInformation();
  const int paths = info ? static_cast<int>(info->GetNumberOfCells()) : 0;
  if (paths <= 0)
  {
    Q_EMIT this->failed(tr("Extract centerlines: no centerline at this seed and threshold (is the "
                           "seed inside a vessel and the lower threshold below its intensity?)."));
    return filter;
  }
  Q_EMIT this->finished(filter, paths);
  return filter;
}

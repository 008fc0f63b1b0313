#include "pqVesselTouchRegionPreview.h"

#include "pqVesselTouchShadingNote.h"

#include "pqVesselTouchCenterlineOverlay.h"
#include "pqVesselTouchVolumeJob.h"

#include "pqApplicationCore.h"
#include "pqPipelineSource.h"
#include "pqServerManagerModel.h"
#include "pqView.h"

#include "vtkDataArray.h"
#include "vtkDataObject.h"
#include "vtkFieldData.h"
#include "vtkFlyingEdges3D.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkStringArray.h"
#include "vtkUnsignedCharArray.h"
#include "vtkVesselTouchCandidateRegionFilter.h"

pqVesselTouchRegionPreview::pqVesselTouchRegionPreview(pqVesselTouchCenterlineOverlay* overlay,
  QObject* parentObject)
  : QObject(parentObject)
  , Overlay(overlay)
{
  // The preview belongs to its volume: it goes with it.
  QObject::connect(pqApplicationCore::instance()->getServerManagerModel(),
    &pqServerManagerModel::preSourceRemoved,
    this,
    [this](pqPipelineSource* source)
    {
      if (source == this->Volume)
      {
        this->hide();
      }
    });
}

pqVesselTouchRegionPreview::~pqVesselTouchRegionPreview() = default;

QString pqVesselTouchRegionPreview::unavailableReason(pqPipelineSource* volume)
{
  return pqVesselTouchVolumeJob::localImage(volume)
           ? QString()
           : tr("Preview needs the volume's voxels in this process: it is not available when "
                "the data is on a remote server.");
}

bool pqVesselTouchRegionPreview::isRunning() const
{
  return this->Job != nullptr;
}

bool pqVesselTouchRegionPreview::isShown() const
{
  return this->Overlay->isShowingRegion();
}

bool pqVesselTouchRegionPreview::show(pqPipelineSource* volume,
  const double seed_mm[3],
  bool automatic,
  double lower,
  double upper,
  pqView* view)
{
  this->hide();
  if (!unavailableReason(volume).isEmpty())
  {
    return false;
  }
  this->Volume = volume;
  this->View = view;
  // The region exactly as VesselCandidateRegion computes it, then its surface (on the thread
  // too: an isosurface of the 0/1 mask at 0.5, in the volume's world frame).
  vtkNew<vtkVesselTouchCandidateRegionFilter> region;
  region->SetUseSeedPoint(true);
  region->SetSeedPoint(seed_mm[0], seed_mm[1], seed_mm[2]);
  region->SetAutomaticIntensityRange(automatic);
  region->SetLowerThreshold(lower);
  region->SetUpperThreshold(upper);
  vtkNew<vtkFlyingEdges3D> surface;
  surface->SetInputConnection(region->GetOutputPort());
  surface->SetValue(0, 0.5);
  surface->ComputeNormalsOn();
  surface->ComputeScalarsOff();
  auto* job = new pqVesselTouchVolumeJob(volume, region, surface, this);
  region->SetCancelFlag(job->cancelFlag());
  QObject::connect(
    job, &pqVesselTouchVolumeJob::progress, this, &pqVesselTouchRegionPreview::progress);
  QObject::connect(
    job, &pqVesselTouchVolumeJob::finished, this, [this, job]() { this->onJobFinished(job); });
  this->Job = job;
  Q_EMIT this->progress(0);
  return job->start();
}

void pqVesselTouchRegionPreview::hide()
{
  if (this->Job)
  {
    this->Job->cancel(); // it ends at its next check point; nothing of it is shown
    this->Job = nullptr;
  }
  this->Result = pqVesselTouchPreviewResult();
  if (this->Overlay->isShowingRegion())
  {
    this->Overlay->showRegion(this->View, nullptr);
  }
}

void pqVesselTouchRegionPreview::onJobFinished(pqVesselTouchVolumeJob* job)
{
  job->deleteLater();
  if (job != this->Job)
  {
    return;
  }
  this->Job = nullptr;
  auto* region = vtkVesselTouchCandidateRegionFilter::SafeDownCast(job->head());
  if (job->wasCancelled() || !job->volume() || !region || region->GetLastRunCancelled())
  {
    Q_EMIT this->cancelled(job->volume() ? job->cancelReason() : tr("The volume was deleted."));
    return;
  }
  pqVesselTouchPreviewResult result;
  result.rangeUsed[0] = region->GetIntensityRangeUsed()[0];
  result.rangeUsed[1] = region->GetIntensityRangeUsed()[1];
  result.rangeAutomatic = region->GetAutomaticIntensityRange();
  result.message = QString::fromUtf8(region->GetExtractionMessage());
  auto* mask = vtkImageData::SafeDownCast(region->GetOutputDataObject(0));
  result.shading = pqVesselTouchShadingNote(mask ? mask->GetFieldData() : nullptr);
  auto* vessel =
    mask ? vtkUnsignedCharArray::SafeDownCast(mask->GetPointData()->GetScalars()) : nullptr;
  for (vtkIdType i = 0, n = vessel ? vessel->GetNumberOfValues() : 0; i < n; ++i)
  {
    result.voxels += vessel->GetValue(i) != 0 ? 1 : 0;
  }
  this->Result = result;
  if (result.voxels == 0)
  {
    Q_EMIT this->failed(!result.message.isEmpty()
                          ? result.message
                          : tr("No candidate vessel region at this seed and intensity range."));
    return;
  }
  this->Overlay->showRegion(
    this->View, vtkPolyData::SafeDownCast(job->tail()->GetOutputDataObject(0)));
  Q_EMIT this->shown();
}

#include "pqVesselTouchCenterlineExtraction.h"

#include "pqVesselTouchShadingNote.h"

#include "pqVesselTouchCenterlineOverlay.h"
#include "pqVesselTouchRemoteCancel.h"
#include "pqVesselTouchRemoteUpdateEvents.h"
#include "pqVesselTouchVolumeCheck.h"
#include "pqVesselTouchVolumeJob.h"

#include "pqApplicationCore.h"
#include "pqObjectBuilder.h"
#include "pqOutputPort.h"
#include "pqPipelineSource.h"
#include "pqProgressManager.h"
#include "pqServer.h"
#include "pqServerResource.h"
#include "pqView.h"

#include "vtkAlgorithm.h"
#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkDataObject.h"
#include "vtkFieldData.h"
#include "vtkNew.h"
#include "vtkPVDataInformation.h"
#include "vtkPVProgressHandler.h"
#include "vtkPolyData.h"
#include "vtkSMPVRepresentationProxy.h"
#include "vtkSMParaViewPipelineControllerWithRendering.h"
#include "vtkSMPropertyHelper.h"
#include "vtkSMSession.h"
#include "vtkSMSourceProxy.h"
#include "vtkSMViewProxy.h"
#include "vtkStringArray.h"
#include "vtkVesselTouchCenterlineFilter.h"

#include <QCoreApplication>

#include <algorithm>

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

bool pqVesselTouchCenterlineExtraction::Request::sameAs(const Request& other) const
{
  return this->volume == other.volume &&
         std::equal(this->seed_mm, this->seed_mm + 3, other.seed_mm) &&
         this->automatic == other.automatic &&
         (this->automatic || (this->lower == other.lower && this->upper == other.upper));
}

pqVesselTouchCenterlineExtraction::Request pqVesselTouchCenterlineExtraction::Request::of(
  pqPipelineSource* volume,
  const double seed_mm[3],
  bool automatic,
  double lowerThreshold,
  double upperThreshold,
  pqView* view)
{
  Request request;
  request.volume = volume;
  std::copy(seed_mm, seed_mm + 3, request.seed_mm);
  request.automatic = automatic;
  request.lower = lowerThreshold;
  request.upper = upperThreshold;
  request.view = view;
  return request;
}

pqPipelineSource* pqVesselTouchCenterlineExtraction::extract(pqPipelineSource* volume,
  const double seed_mm[3],
  bool automatic,
  double lowerThreshold,
  double upperThreshold,
  pqView* view)
{
  const Request request =
    Request::of(volume, seed_mm, automatic, lowerThreshold, upperThreshold, view);
  this->Clock.start();
  return this->run(request, nullptr, std::string());
}

bool pqVesselTouchCenterlineExtraction::isRunning() const
{
  return this->Job != nullptr || this->Remote != nullptr;
}

void pqVesselTouchCenterlineExtraction::setRemoteUpdateEvents(
  pqVesselTouchRemoteUpdateEvents* events)
{
  this->RemoteEvents = events;
}

void pqVesselTouchCenterlineExtraction::cancel(const QString& reason)
{
  if (this->Job)
  {
    this->Job->cancel(reason);
  }
  if (this->Remote)
  {
    this->Remote->cancel(); // at once when the port is known, else at the next progress report
  }
}

bool pqVesselTouchCenterlineExtraction::start(pqPipelineSource* volume,
  const double seed_mm[3],
  bool automatic,
  double lowerThreshold,
  double upperThreshold,
  pqView* view)
{
  const Request request =
    Request::of(volume, seed_mm, automatic, lowerThreshold, upperThreshold, view);
  if (this->Job && request.sameAs(this->Running))
  {
    return true; // the same extraction is under way: let it finish
  }
  if (this->Job)
  {
    this->Job->cancel(); // superseded: it ends soon, its result is dropped
    this->Job = nullptr;
  }
  this->Clock.start();
  this->Result = pqVesselTouchExtractionResult();
  const QString problem = pqVesselTouchVolumeCheck::problem(volume);
  if (!problem.isEmpty() || !pqVesselTouchVolumeJob::localImage(volume))
  {
    // Remote data (or none): the pipeline's filter, synchronously, as in ParaView.
    this->run(request, nullptr, std::string());
    return false;
  }
  // A private copy of the filter, with the parameters the volume's filter proxy has (the
  // defaults for a volume without one) and the request's seed and range.
  vtkNew<vtkVesselTouchCenterlineFilter> copy;
  const bool sameVolume =
    this->Centerline &&
    vtkSMPropertyHelper(this->Centerline->getProxy(), "Input").GetAsProxy() == volume->getProxy();
  if (sameVolume)
  {
    copy->CopyParameters(vtkVesselTouchCenterlineFilter::SafeDownCast(
      this->Centerline->getProxy()->GetClientSideObject()));
  }
  copy->SetUseSeedPoint(true);
  copy->SetSeedPoint(request.seed_mm[0], request.seed_mm[1], request.seed_mm[2]);
  copy->SetAutomaticIntensityRange(automatic);
  if (!automatic)
  {
    copy->SetLowerThreshold(lowerThreshold);
    copy->SetUpperThreshold(upperThreshold);
  }
  auto* job = new pqVesselTouchVolumeJob(volume, copy, copy, this);
  copy->SetCancelFlag(job->cancelFlag());
  QObject::connect(
    job, &pqVesselTouchVolumeJob::progress, this, &pqVesselTouchCenterlineExtraction::progress);
  QObject::connect(
    job, &pqVesselTouchVolumeJob::finished, this, [this, job]() { this->onJobFinished(job); });
  this->Job = job;
  this->Running = request;
  Q_EMIT this->progress(0);
  if (!job->start())
  {
    this->Job = nullptr; // the volume's data went away since the check above
    job->deleteLater();
    this->run(request, nullptr, std::string());
    return false;
  }
  return true;
}

void pqVesselTouchCenterlineExtraction::onJobFinished(pqVesselTouchVolumeJob* job)
{
  job->deleteLater();
  if (job != this->Job)
  {
    return; // superseded by a later start(): dropped
  }
  this->Job = nullptr;
  auto* copy = vtkVesselTouchCenterlineFilter::SafeDownCast(job->head());
  if (job->wasCancelled() || !job->volume() || !copy || copy->GetLastRunCancelled())
  {
    Q_EMIT this->cancelled(job->volume() ? job->cancelReason() : tr("The volume was deleted."));
    return;
  }
  Request request = this->Running;
  this->run(request, copy->GetOutput(), copy->GetLastRunKey());
}

pqPipelineSource* pqVesselTouchCenterlineExtraction::run(const Request& request,
  vtkPolyData* precomputed,
  const std::string& key)
{
  this->Result = pqVesselTouchExtractionResult();
  pqPipelineSource* volume = request.volume;
  pqView* view = request.view;
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
  this->Previous = Parameters::of(filter);
  vtkSMPropertyHelper(proxy, "UseSeedPoint").Set(1);
  vtkSMPropertyHelper(proxy, "SeedPoint").Set(request.seed_mm, 3);
  const bool hasAutomatic = proxy->GetProperty("AutomaticIntensityRange") != nullptr;
  if (hasAutomatic)
  {
    vtkSMPropertyHelper(proxy, "AutomaticIntensityRange").Set(request.automatic ? 1 : 0);
  }
  if (!request.automatic || !hasAutomatic)
  {
    vtkSMPropertyHelper(proxy, "LowerThreshold").Set(request.lower);
    vtkSMPropertyHelper(proxy, "UpperThreshold").Set(request.upper);
  }
  proxy->UpdateVTKObjects();
  auto* local = vtkVesselTouchCenterlineFilter::SafeDownCast(proxy->GetClientSideObject());
  if (precomputed && local)
  {
    // The update below returns the background run's output if nothing changed since.
    local->SetPrecomputedOutput(precomputed, key.c_str());
  }

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
  const bool remoteCancelled = this->updateRemotely(filter);
  QObject::disconnect(connection);
  filter->setModifiedState(pqProxy::UNMODIFIED);
  if (remoteCancelled)
  {
    this->restorePrevious(filter, view);
    Q_EMIT this->cancelled(QString());
    return filter;
  }
  this->Completed = filter;

  this->readResult(filter);
  this->Result.background = local && local->GetLastRunPrecomputed();
  this->Result.seconds = static_cast<double>(this->Clock.elapsed()) / 1000.0;
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

bool pqVesselTouchCenterlineExtraction::updateRemotely(pqPipelineSource* filter)
{
  auto* source = vtkSMSourceProxy::SafeDownCast(filter->getProxy());
  pqServer* server = filter->getServer();
  if (!server || !server->isRemote() || !source->GetProperty("RemoteCancelToken") || this->Remote)
  {
    source->UpdatePipeline(); // built in (or a nested call): ParaView's update
    return false;
  }
  this->Remote = std::make_unique<pqVesselTouchRemoteCancel>(server->getResource().host(), source);
  vtkPVProgressHandler* handler = server->session()->GetProgressHandler();
  vtkNew<vtkCallbackCommand> observer;
  observer->SetClientData(this);
  observer->SetCallback([](vtkObject* caller, unsigned long, void* self, void*)
    { static_cast<pqVesselTouchCenterlineExtraction*>(self)->onRemoteProgress(caller); });
  const unsigned long tag = handler->AddObserver(vtkCommand::ProgressEvent, observer);
  Q_EMIT this->remoteRunStarted();
  // What ParaView posted before the run (its panels' queued updates, which may push properties
  // to the server) runs now, as the event loop would have run it: inside the update the server
  // must be sent nothing (pqVesselTouchRemoteUpdateEvents).
  QCoreApplication::sendPostedEvents();
  source->UpdatePipeline();
  handler->RemoveObserver(tag);
  const bool cancelled = this->Remote->acknowledged();
  if (this->Remote->wanted() && !cancelled)
  {
    qWarning("VesselTouch: the Cancel did not reach the server (%s); the run went on to its end.",
      qUtf8Printable(this->Remote->error()));
  }
  this->Remote.reset();
  return cancelled;
}

void pqVesselTouchCenterlineExtraction::onRemoteProgress(vtkObject* caller)
{
  auto* handler = vtkPVProgressHandler::SafeDownCast(caller);
  if (!handler || !this->Remote)
  {
    return;
  }
  const QString text =
    QString::fromUtf8(handler->GetLastProgressText() ? handler->GetLastProgressText() : "");
  const int percent = handler->GetLastProgress();
  this->Remote->observeProgressText(text); // sends a Cancel asked before the port was known
  Q_EMIT this->progress(percent);
  Q_EMIT this->remoteProgress(percent, text);
  if (this->RemoteEvents && !this->Remote->wanted())
  {
    this->RemoteEvents->processEvents(); // the Cancel's click, if any, calls cancel() in there
  }
}

pqVesselTouchCenterlineExtraction::Parameters pqVesselTouchCenterlineExtraction::Parameters::of(
  pqPipelineSource* filter)
{
  Parameters p;
  p.filter = filter;
  vtkSMProxy* proxy = filter->getProxy();
  vtkSMPropertyHelper(proxy, "SeedPoint").Get(p.seed_mm, 3);
  p.useSeed = vtkSMPropertyHelper(proxy, "UseSeedPoint").GetAsInt();
  p.automatic = proxy->GetProperty("AutomaticIntensityRange")
                  ? vtkSMPropertyHelper(proxy, "AutomaticIntensityRange").GetAsInt()
                  : 0;
  p.lower = vtkSMPropertyHelper(proxy, "LowerThreshold").GetAsDouble();
  p.upper = vtkSMPropertyHelper(proxy, "UpperThreshold").GetAsDouble();
  return p;
}

void pqVesselTouchCenterlineExtraction::Parameters::applyTo(pqPipelineSource* target) const
{
  vtkSMProxy* proxy = target->getProxy();
  vtkSMPropertyHelper(proxy, "SeedPoint").Set(this->seed_mm, 3);
  vtkSMPropertyHelper(proxy, "UseSeedPoint").Set(this->useSeed);
  if (proxy->GetProperty("AutomaticIntensityRange"))
  {
    vtkSMPropertyHelper(proxy, "AutomaticIntensityRange").Set(this->automatic);
  }
  vtkSMPropertyHelper(proxy, "LowerThreshold").Set(this->lower);
  vtkSMPropertyHelper(proxy, "UpperThreshold").Set(this->upper);
  proxy->UpdateVTKObjects();
}

void pqVesselTouchCenterlineExtraction::restorePrevious(pqPipelineSource* filter, pqView* view)
{
  if (this->Completed != filter || this->Previous.filter != filter)
  {
    // No earlier run of this filter to go back to: it stays cancelled (an empty output).
    this->Completed = nullptr;
    this->Result = pqVesselTouchExtractionResult();
    this->showInView(filter, view, false);
    return;
  }
  // Every rank returns the output it kept from before the cancelled run (no computing:
  // vtkVesselTouchCenterlineFilter's kept output, keyed on these parameters).
  this->Previous.applyTo(filter);
  vtkSMSourceProxy::SafeDownCast(filter->getProxy())->UpdatePipeline();
  filter->setModifiedState(pqProxy::UNMODIFIED);
  this->readResult(filter);
  this->showInView(filter, view, this->Result.paths > 0);
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
    this->Result.shading = pqVesselTouchShadingNote(fields);
  }
  return this->Result;
}

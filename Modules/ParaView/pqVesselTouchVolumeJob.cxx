#include "pqVesselTouchVolumeJob.h"

#include "pqApplicationCore.h"
#include "pqPipelineSource.h"
#include "pqServerManagerModel.h"

#include "vtkAlgorithm.h"
#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkExecutive.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkSMSourceProxy.h"

#include <sstream>
#include <system_error>

namespace
{
/// How often the GUI thread looks at the job's progress and end, ms.
constexpr int kPollPeriod_ms = 50;

struct MessageSink
{
  std::mutex* mutex;
  std::string* text;
};

/// ErrorEvent / WarningEvent of the job's objects (on the job's thread): kept for the GUI.
void collectMessage(vtkObject*, unsigned long, void* clientData, void* callData)
{
  auto* sink = static_cast<MessageSink*>(clientData);
  const std::lock_guard<std::mutex> lock(*sink->mutex);
  if (!sink->text->empty())
  {
    sink->text->push_back('\n');
  }
  sink->text->append(callData ? static_cast<const char*>(callData) : "");
}

/// ProgressEvent of the head filter (on the job's thread): the fraction as permille.
void storeProgress(vtkObject*, unsigned long, void* clientData, void* callData)
{
  if (callData)
  {
    const double fraction = *static_cast<const double*>(callData);
    static_cast<std::atomic<int>*>(clientData)->store(static_cast<int>(1000.0 * fraction));
  }
}
} // namespace

vtkImageData* pqVesselTouchVolumeJob::localImage(pqPipelineSource* volume)
{
  auto* proxy = volume ? vtkSMSourceProxy::SafeDownCast(volume->getProxy()) : nullptr;
  auto* algorithm = proxy ? vtkAlgorithm::SafeDownCast(proxy->GetClientSideObject()) : nullptr;
  return algorithm ? vtkImageData::SafeDownCast(algorithm->GetOutputDataObject(0)) : nullptr;
}

pqVesselTouchVolumeJob::pqVesselTouchVolumeJob(pqPipelineSource* volume,
  vtkAlgorithm* head,
  vtkAlgorithm* tail,
  QObject* parentObject)
  : QObject(parentObject)
  , Volume(volume)
  , Head(head)
  , Tail(tail ? tail : head)
{
  this->Poll.setInterval(kPollPeriod_ms);
  QObject::connect(&this->Poll, &QTimer::timeout, this, &pqVesselTouchVolumeJob::poll);
}

pqVesselTouchVolumeJob::~pqVesselTouchVolumeJob()
{
  this->CancelFlag = true;
  if (this->Thread.joinable())
  {
    this->Thread.join(); // prompt: the head stops at its next check point
  }
}

std::string pqVesselTouchVolumeJob::voxelsSignature() const
{
  vtkImageData* image = localImage(this->Volume);
  vtkPointData* points = image ? image->GetPointData() : nullptr;
  if (!points)
  {
    return std::string();
  }
  std::ostringstream signature;
  signature << static_cast<const void*>(image) << " " << static_cast<const void*>(points) << " "
            << static_cast<const void*>(points->GetScalars()) << " " << points->GetMTime();
  return signature.str();
}

bool pqVesselTouchVolumeJob::start()
{
  vtkImageData* image = localImage(this->Volume);
  if (!image || !this->Head || this->Thread.joinable() || this->Finished)
  {
    return false;
  }
  // The thread's own image: the voxels' array is shared (read only), everything else is its own.
  this->Input = vtkSmartPointer<vtkImageData>::New();
  this->Input->ShallowCopy(image);
  this->Head->SetInputDataObject(0, this->Input);
  this->StartSignature = this->voxelsSignature();

  // Messages and progress, observed on the thread that runs the filters.
  auto* sink = new MessageSink{ &this->ErrorMutex, &this->Errors };
  vtkNew<vtkCallbackCommand> messages;
  messages->SetCallback(collectMessage);
  messages->SetClientData(sink);
  messages->SetClientDataDeleteCallback([](void* data) { delete static_cast<MessageSink*>(data); });
  for (vtkAlgorithm* algorithm : { this->Head.GetPointer(), this->Tail.GetPointer() })
  {
    for (vtkObject* object :
      { static_cast<vtkObject*>(algorithm), static_cast<vtkObject*>(algorithm->GetExecutive()) })
    {
      object->AddObserver(vtkCommand::ErrorEvent, messages);
      object->AddObserver(vtkCommand::WarningEvent, messages);
    }
  }
  vtkNew<vtkCallbackCommand> progress;
  progress->SetCallback(storeProgress);
  progress->SetClientData(&this->Permille);
  this->Head->AddObserver(vtkCommand::ProgressEvent, progress);

  // The volume going away or re-executing makes the result useless: stop early.
  QObject::connect(this->Volume,
    QOverload<pqPipelineSource*>::of(&pqPipelineSource::dataUpdated),
    this,
    &pqVesselTouchVolumeJob::onVolumeDataUpdated);
  QObject::connect(pqApplicationCore::instance()->getServerManagerModel(),
    &pqServerManagerModel::preSourceRemoved,
    this,
    [this](pqPipelineSource* source)
    {
      if (source == this->Volume)
      {
        this->cancel(tr("The volume was deleted."));
      }
    });
  try
  {
    this->Thread = std::thread([this]() { this->run(); });
  }
  catch (const std::system_error&)
  {
    this->run(); // no thread to be had: run here (the GUI waits, as ParaView's own filters do)
  }
  this->Poll.start();
  return true;
}

void pqVesselTouchVolumeJob::run()
{
  try
  {
    this->Tail->Update();
  }
  catch (const std::exception& e) // std::bad_alloc from a filter
  {
    const std::lock_guard<std::mutex> lock(this->ErrorMutex);
    this->Errors += e.what();
  }
  this->Done = true;
}

void pqVesselTouchVolumeJob::cancel(const QString& reason)
{
  if (!this->CancelFlag.exchange(true))
  {
    this->CancelReason = reason;
  }
}

void pqVesselTouchVolumeJob::onVolumeDataUpdated()
{
  if (this->voxelsSignature() != this->StartSignature)
  {
    this->cancel(tr("The volume changed while this ran: run it again."));
  }
}

void pqVesselTouchVolumeJob::poll()
{
  const int percent = this->percent();
  if (percent != this->LastPercent && !this->Done)
  {
    this->LastPercent = percent;
    Q_EMIT this->progress(percent);
  }
  if (!this->Done || this->Finished)
  {
    return;
  }
  if (this->Thread.joinable())
  {
    this->Thread.join(); // it has returned: immediate
  }
  this->Poll.stop();
  this->Finished = true;
  {
    const std::lock_guard<std::mutex> lock(this->ErrorMutex);
    this->ErrorText = QString::fromStdString(this->Errors);
  }
  Q_EMIT this->finished();
}

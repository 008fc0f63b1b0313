#include "pqVesselTouchSessionBinding.h"

#include "pqActiveObjects.h"
#include "pqApplicationCore.h"
#include "pqObjectBuilder.h"
#include "pqPipelineSource.h"
#include "pqRenderView.h"
#include "pqServer.h"
#include "pqServerManagerModel.h"

#include "vtkCamera.h"
#include "vtkCommand.h"
#include "vtkEventQtSlotConnect.h"
#include "vtkSMParaViewPipelineController.h"
#include "vtkSMPropertyHelper.h"
#include "vtkSMRenderViewProxy.h"
#include "vtkSMSessionProxyManager.h"
#include "vtkSMSourceProxy.h"
#include "vtkSmartPointer.h"
#include "vtkAlgorithm.h"
#include "vtkNew.h"
#include "vtkPolyData.h"
#include "vtkSMStringVectorProperty.h"
#include "vtkXMLPolyDataWriter.h"

#include <QTimer>

const char* pqVesselTouchSessionBinding::registrationName()
{
  return "VesselTouchSession";
}

pqVesselTouchSessionBinding::pqVesselTouchSessionBinding(QObject* parentObject)
  : QObject(parentObject)
{
  pqServerManagerModel* model = pqApplicationCore::instance()->getServerManagerModel();
  QObject::connect(
    model, &pqServerManagerModel::sourceAdded, this, &pqVesselTouchSessionBinding::onSourceAdded);
  QObject::connect(model,
    &pqServerManagerModel::preSourceRemoved,
    this,
    &pqVesselTouchSessionBinding::onSourceRemoved);
  // A proxy renamed to "VesselTouchSession" (or away from it) changes the binding too.
  QObject::connect(model,
    &pqServerManagerModel::nameChanged,
    this,
    [this](pqServerManagerModelItem* item)
    {
      auto* source = qobject_cast<pqPipelineSource*>(item);
      if (source == this->Source && !isSession(source))
      {
        this->onSourceRemoved(source);
      }
      else if (source && !this->Source)
      {
        this->onSourceAdded(source);
      }
    });
  // The newest session when there are several (a state loaded before the panel existed).
  pqPipelineSource* newest = nullptr;
  for (pqPipelineSource* source : model->findItems<pqPipelineSource*>())
  {
    newest = isSession(source) ? source : newest;
  }
  if (newest)
  {
    this->adopt(newest);
  }
}

pqVesselTouchSessionBinding::~pqVesselTouchSessionBinding() = default;

bool pqVesselTouchSessionBinding::isSession(pqPipelineSource* source)
{
  return source && source->getProxy() && source->getSMName() == QLatin1String(registrationName()) &&
         QLatin1String(source->getProxy()->GetXMLName()) ==
           QLatin1String("VesselTouchHapticSession");
}

vtkSMProxy* pqVesselTouchSessionBinding::proxy() const
{
  return this->Source ? this->Source->getProxy() : nullptr;
}

pqPipelineSource* pqVesselTouchSessionBinding::source() const
{
  return this->Source;
}

void pqVesselTouchSessionBinding::onSourceAdded(pqPipelineSource* source)
{
  if (!isSession(source) || source == this->Source)
  {
    return;
  }
  // A second "VesselTouchSession": a state file loaded into a running ParaView (ParaView adds the
  // state's proxies beside the existing ones) or a script registering a new one. The newest is THE
  // session: the old one stops at once (its loop zeroes the force), the panel and the view follow
  // the new one, and the old one is deleted once the event that registered the new one is over
  // (not from inside the state loader's registration), so exactly one session stays registered.
  QPointer<pqPipelineSource> old = this->Source;
  if (old && old->getProxy())
  {
    old->getProxy()->InvokeCommand("Stop");
  }
  this->adopt(source);
  if (old)
  {
    QTimer::singleShot(0,
      this,
      [old]()
      {
        if (old && old->getProxy())
        {
          pqApplicationCore::instance()->getObjectBuilder()->destroy(old);
        }
      });
  }
}

void pqVesselTouchSessionBinding::onSourceRemoved(pqPipelineSource* source)
{
  if (source && source == this->Source)
  {
    this->adopt(nullptr);
  }
}

void pqVesselTouchSessionBinding::adopt(pqPipelineSource* source)
{
  this->Connector->Disconnect();
  this->Source = source;
  if (source)
  {
    this->Connector->Connect(source->getProxy(),
      vtkCommand::PropertyModifiedEvent,
      this,
      SLOT(onPropertyModified(vtkObject*, unsigned long, void*, void*)));
  }
  Q_EMIT this->sessionProxyChanged(this->proxy());
}

void pqVesselTouchSessionBinding::onPropertyModified(vtkObject*,
  unsigned long,
  void*,
  void* callData)
{
  // callData names the property; information properties (the 10 Hz status) are not edits.
  const QString name = callData ? QString::fromUtf8(static_cast<const char*>(callData)) : QString();
  if (this->Pushing || this->Pending || name.endsWith(QLatin1String("Info")))
  {
    return;
  }
  this->Pending = true;
  QTimer::singleShot(0, this, &pqVesselTouchSessionBinding::emitPropertiesModified);
}

void pqVesselTouchSessionBinding::emitPropertiesModified()
{
  this->Pending = false;
  Q_EMIT this->propertiesModified();
}

vtkSMProxy* pqVesselTouchSessionBinding::ensureSession()
{
  if (this->Source)
  {
    return this->proxy();
  }
  pqServer* server = pqActiveObjects::instance().activeServer();
  if (!server)
  {
    return nullptr;
  }
  vtkSMSessionProxyManager* pxm = server->proxyManager();
  vtkSmartPointer<vtkSMProxy> session;
  session.TakeReference(pxm->NewProxy("filters", "VesselTouchHapticSession"));
  if (!session)
  {
    return nullptr;
  }
  vtkNew<vtkSMParaViewPipelineController> controller;
  controller->PreInitializeProxy(session);
  session->UpdateVTKObjects();
  controller->PostInitializeProxy(session);
  // Registering makes pqServerManagerModel announce it: onSourceAdded() adopts it.
  controller->RegisterPipelineProxy(session, registrationName());
  return this->proxy();
}

void pqVesselTouchSessionBinding::setCenterline(vtkSMProxy* centerline, unsigned int port)
{
  vtkSMProxy* session = this->ensureSession();
  if (!session)
  {
    return;
  }
  pqServer* server = pqActiveObjects::instance().activeServer();
  vtkSMProxy* input = this->Delivery.deliver(server, centerline, port);
  if (input && pqVesselTouchCenterlineDelivery::isRemote(server))
  {
    // The delivery's mover is plumbing, not a registered pipeline source: it goes on
    // DeliveredCenterline, never on Input (pqPipelineFilter reports an unregistered proxy on an
    // Input in the Output Messages window, which then opens over the view).
    this->writeProperties(
      [&](vtkSMProxy* proxy) { vtkSMPropertyHelper(proxy, "DeliveredCenterline").Set(input); });
    return;
  }
  this->writeProperties(
    [&](vtkSMProxy* proxy) { vtkSMPropertyHelper(proxy, "Input").Set(input, port); });
}

bool pqVesselTouchSessionBinding::hasCenterline() const
{
  vtkSMProxy* session = this->proxy();
  return session &&
    (vtkSMPropertyHelper(session, "Input", /*quiet=*/true).GetAsProxy() ||
      vtkSMPropertyHelper(session, "DeliveredCenterline", /*quiet=*/true).GetAsProxy());
}

void pqVesselTouchSessionBinding::copyCamera(pqRenderView* view)
{
  vtkSMProxy* session = this->proxy();
  vtkSMRenderViewProxy* viewProxy = view ? view->getRenderViewProxy() : nullptr;
  vtkCamera* camera = viewProxy ? viewProxy->GetActiveCamera() : nullptr;
  if (!session || !camera)
  {
    return;
  }
  this->writeProperties(
    [&](vtkSMProxy*)
    {
      vtkSMPropertyHelper(session, "CameraPosition").Set(camera->GetPosition(), 3);
      vtkSMPropertyHelper(session, "CameraFocalPoint").Set(camera->GetFocalPoint(), 3);
      vtkSMPropertyHelper(session, "CameraViewUp").Set(camera->GetViewUp(), 3);
      vtkSMPropertyHelper(session, "CameraParallelProjection")
        .Set(camera->GetParallelProjection() ? 1 : 0);
      vtkSMPropertyHelper(session, "CameraParallelScale").Set(camera->GetParallelScale());
      vtkSMPropertyHelper(session, "CameraViewAngle").Set(camera->GetViewAngle());
      int size[2] = { 0, 0 };
      vtkSMPropertyHelper(viewProxy, "ViewSize").Get(size, 2);
      if (size[0] > 0 && size[1] > 0)
      {
        vtkSMPropertyHelper(session, "ViewportSize").Set(size, 2);
      }
    });
}

bool pqVesselTouchSessionBinding::start()
{
  vtkSMProxy* session = this->ensureSession();
  if (!session)
  {
    return false;
  }
  session->InvokeCommand("Start");
  session->UpdatePropertyInformation();
  return vtkSMPropertyHelper(session, "SessionStatusInfo").GetAsInt(0) != 0;
}

void pqVesselTouchSessionBinding::stop()
{
  if (vtkSMProxy* session = this->proxy())
  {
    session->InvokeCommand("Stop");
  }
}

void pqVesselTouchSessionBinding::reportConnectionLost(const QString& message)
{
  this->writeProperties(
    [&](vtkSMProxy* proxy)
    {
      auto* property =
        vtkSMStringVectorProperty::SafeDownCast(proxy->GetProperty("ConnectionLostMessage"));
      if (property)
      {
        property->SetNumberOfElements(1);
        property->SetElement(0, message.toUtf8().constData());
      }
    });
}

bool pqVesselTouchSessionBinding::saveSkeleton(const QString& fileName) const
{
  vtkSMProxy* session = this->proxy();
  auto* algorithm = session ? vtkAlgorithm::SafeDownCast(session->GetClientSideObject()) : nullptr;
  vtkPolyData* skeleton = algorithm && algorithm->GetNumberOfInputConnections(0) > 0
                            ? vtkPolyData::SafeDownCast(algorithm->GetInputDataObject(0, 0))
                            : nullptr;
  if (!skeleton || skeleton->GetNumberOfPoints() == 0)
  {
    return false;
  }
  vtkNew<vtkXMLPolyDataWriter> writer;
  writer->SetFileName(fileName.toUtf8().constData());
  writer->SetInputData(skeleton);
  return writer->Write() == 1;
}

void pqVesselTouchSessionBinding::writeProperties(const std::function<void(vtkSMProxy*)>& write)
{
  vtkSMProxy* session = this->proxy();
  if (!session)
  {
    return;
  }
  this->Pushing = true;
  write(session);
  session->UpdateVTKObjects();
  this->Pushing = false;
  this->Source->setModifiedState(pqProxy::UNMODIFIED);
}

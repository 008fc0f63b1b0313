#include "pqVesselTouchServerCheck.h"

#include "pqVesselTouchCenterlineDelivery.h"

#include "pqActiveObjects.h"
#include "pqApplicationCore.h"
#include "pqPluginManager.h"
#include "pqServer.h"
#include "pqServerManagerModel.h"
#include "pqServerResource.h"
#include "vtkPVPluginsInformation.h"
#include "vtkPVSessionBase.h"
#include "vtkClientSocket.h"
#include "vtkMultiProcessController.h"
#include "vtkSMSession.h"
#include "vtkSMSessionClient.h"
#include "vtkSocketCommunicator.h"
#include "vtkSMPluginManager.h"
#include "vtkSMProxyManager.h"

#include <QPointer>
#include <QTimer>

#include <poll.h>

namespace
{
/// The plugin's name as the plugin information reports it (paraview.plugin: NAME).
constexpr const char* kPluginName = "VesselTouch";
/// Above pqServer's observer (priority 0): VTK calls higher priorities first (project rule: the
/// force must be zero before ParaView's modal dialog and _exit).
constexpr float kBeforeParaViewPriority = 10.0f;
/// Socket poll period, ms (project rule: well under a human reaction time).
constexpr int kPollPeriod_ms = 20;

/// The descriptor of `session`'s socket to the data server, -1 built in.
int dataServerSocket(vtkSMSession* session)
{
  auto* client = vtkSMSessionClient::SafeDownCast(session);
  vtkMultiProcessController* controller =
    client ? client->GetController(vtkPVSession::DATA_SERVER) : nullptr;
  auto* communicator =
    controller ? vtkSocketCommunicator::SafeDownCast(controller->GetCommunicator()) : nullptr;
  vtkSocket* socket = communicator ? communicator->GetSocket() : nullptr;
  return socket ? socket->GetSocketDescriptor() : -1;
}
}

pqVesselTouchServerCheck::pqVesselTouchServerCheck(QObject* parentObject)
  : QObject(parentObject)
{
  // In the GUI this object watches the connection on the main thread: vesseltouch's Python
  // watch thread stays off (vesseltouch/connection_watch.py, GUI_WATCHES_ENV).
  qputenv("VESSELTOUCH_CONNECTION_WATCHED_IN_GUI", "1");
  pqApplicationCore* core = pqApplicationCore::instance();
  pqServerManagerModel* model = core->getServerManagerModel();
  // preServerAdded: before pqCrashRecoveryBehavior connects to the new server (serverAdded).
  QObject::connect(
    model, &pqServerManagerModel::preServerAdded, this, &pqVesselTouchServerCheck::watch);
  for (pqServer* server : model->findItems<pqServer*>())
  {
    this->watch(server); // the panel came after the connection (a plugin loaded later)
  }
  this->Poll = new QTimer(this);
  this->Poll->setInterval(kPollPeriod_ms);
  QObject::connect(this->Poll, &QTimer::timeout, this, &pqVesselTouchServerCheck::pollSockets);
  QObject::connect(&pqActiveObjects::instance(),
    &pqActiveObjects::serverChanged,
    this,
    &pqVesselTouchServerCheck::recheck);
  QObject::connect(core->getPluginManager(),
    &pqPluginManager::pluginsUpdated,
    this,
    &pqVesselTouchServerCheck::recheck);
  this->recheck();
}

pqVesselTouchServerCheck::~pqVesselTouchServerCheck()
{
  for (const Watched& watched : this->Sessions)
  {
    if (watched.Session)
    {
      watched.Session->RemoveObserver(watched.Tag);
    }
  }
}

QString pqVesselTouchServerCheck::serverName(pqServer* server)
{
  return server ? server->getResource().toURI() : QString();
}

QString pqVesselTouchServerCheck::problemFor(pqServer* server)
{
  if (!server || !pqVesselTouchCenterlineDelivery::isRemote(server) || !server->session())
  {
    return QString();
  }
  vtkSMPluginManager* plugins = vtkSMProxyManager::GetProxyManager()->GetPluginManager();
  vtkPVPluginsInformation* info = plugins->GetRemoteInformation(server->session());
  for (unsigned int i = 0; info && i < info->GetNumberOfPlugins(); ++i)
  {
    const char* name = info->GetPluginName(i);
    if (name && QString::fromUtf8(name) == QLatin1String(kPluginName) && info->GetPluginLoaded(i))
    {
      return QString();
    }
  }
  return tr("The pvserver %1 has not loaded the VesselTouch plugin, so Extract cannot run "
            "VesselCenterline there. Load it on the server: Tools > Manage Plugins, Remote "
            "Plugins, Load New... and choose the same VesselTouch.so as the client's (or, in the "
            "Python shell, LoadPlugin(path, remote=True)).")
    .arg(serverName(server));
}

void pqVesselTouchServerCheck::recheck()
{
  const QString problem = problemFor(pqActiveObjects::instance().activeServer());
  if (problem != this->Problem)
  {
    this->Problem = problem;
    Q_EMIT this->problemChanged(problem);
  }
}

void pqVesselTouchServerCheck::watch(pqServer* server)
{
  if (!server)
  {
    return;
  }
  if (vtkObject* session = server->session())
  {
    Watched watched;
    watched.Server = server;
    watched.Session = session;
    watched.Socket = dataServerSocket(server->session());
    watched.Tag = session->AddObserver(vtkPVSessionBase::ConnectionLost,
      this,
      &pqVesselTouchServerCheck::onSessionConnectionLost,
      kBeforeParaViewPriority);
    this->Sessions.push_back(watched);
    if (watched.Socket >= 0)
    {
      this->Poll->start();
    }
  }
  // The server's plugin list is known once its session is up: check again then.
  QTimer::singleShot(0, this, &pqVesselTouchServerCheck::recheck);
}

void pqVesselTouchServerCheck::pollSockets()
{
  bool any = false;
  for (Watched& watched : this->Sessions)
  {
    if (watched.Socket < 0)
    {
      continue;
    }
    // The server gone (closed, or Disconnect closed this socket): stop watching it.
    if (!watched.Server || !watched.Session ||
        dataServerSocket(watched.Server->session()) != watched.Socket)
    {
      watched.Socket = -1;
      continue;
    }
    pollfd entry{ watched.Socket, POLLRDHUP, 0 };
    if (::poll(&entry, 1, 0) > 0 && (entry.revents & (POLLRDHUP | POLLHUP | POLLERR)) != 0)
    {
      watched.Socket = -1;
      this->onSessionConnectionLost(watched.Session, vtkPVSessionBase::ConnectionLost, nullptr);
      continue;
    }
    any = true;
  }
  if (!any)
  {
    this->Poll->stop();
  }
}

void pqVesselTouchServerCheck::onSessionConnectionLost(vtkObject* session, unsigned long, void*)
{
  for (Watched& watched : this->Sessions)
  {
    if (watched.Session == session && watched.Tag != 0)
    {
      session->RemoveObserver(watched.Tag); // once: the socket reports every failed call
      watched.Tag = 0;
      watched.Socket = -1;
      Q_EMIT this->connectionLost(serverName(watched.Server));
      return;
    }
  }
}

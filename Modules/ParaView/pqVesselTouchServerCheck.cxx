#include "pqVesselTouchServerCheck.h"

#include "pqVesselTouchCenterlineDelivery.h"

#include "pqActiveObjects.h"
#include "pqApplicationCore.h"
#include "pqPluginManager.h"
#include "pqServer.h"
#include "pqServerManagerModel.h"
#include "pqServerResource.h"
#include "vtkPVPluginsInformation.h"
#include "vtkSMPluginManager.h"
#include "vtkSMProxyManager.h"

#include <QPointer>
#include <QTimer>

namespace
{
/// The plugin's name as the plugin information reports it (paraview.plugin: NAME).
constexpr const char* kPluginName = "VesselTouch";
}

pqVesselTouchServerCheck::pqVesselTouchServerCheck(QObject* parentObject)
  : QObject(parentObject)
{
  pqApplicationCore* core = pqApplicationCore::instance();
  pqServerManagerModel* model = core->getServerManagerModel();
  // preServerAdded: before pqCrashRecoveryBehavior connects to the new server (serverAdded).
  QObject::connect(
    model, &pqServerManagerModel::preServerAdded, this, &pqVesselTouchServerCheck::watch);
  for (pqServer* server : model->findItems<pqServer*>())
  {
    this->watch(server); // the panel came after the connection (a plugin loaded later)
  }
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

pqVesselTouchServerCheck::~pqVesselTouchServerCheck() = default;

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
  QPointer<pqServer> guarded(server);
  QObject::connect(server,
    &pqServer::serverSideDisconnected,
    this,
    [this, guarded]() { Q_EMIT this->connectionLost(serverName(guarded)); });
  // The server's plugin list is known once its session is up: check again then.
  QTimer::singleShot(0, this, &pqVesselTouchServerCheck::recheck);
}

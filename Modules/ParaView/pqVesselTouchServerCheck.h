// The server the panel works on, watched for issue 19's faults (item 6).
//
// - A pvserver without the VesselTouch plugin: VesselCenterline (and the other server-side
//   filters) cannot be created there, so problem() says what is missing and how to fix it, and
//   the panel disables Extract with that reason instead of failing a proxy creation. Re-checked
//   when the active server changes and when plugins load (pqPluginManager::pluginsUpdated).
// - The pvserver lost: connectionLost() the moment pqServer says so (serverSideDisconnected:
//   pqServer watches its socket for server notifications, and vtkSMSessionClient turns the
//   socket's error into vtkPVSessionBase::ConnectionLost). Measured here: pqServer learns it at
//   its next heartbeat (a send that fails), tens of seconds later, and ParaView's
//   pqCrashRecoveryBehavior answers with a modal dialog, then ends the application (_exit). So
//   this class polls the data-server socket for the peer's hang-up on the main thread every
//   20 ms (POLLRDHUP, reading nothing: ParaView's messages are left alone; the period is a
//   project rule, well under a reaction time), and observes the session's ConnectionLost event at
//   a higher priority than pqServer's: the panel zeroes the force and saves the skeleton before
//   ParaView's dialog. The
//   haptic thread never touches the network; detection is the GUI's.
#ifndef pqVesselTouchServerCheck_h
#define pqVesselTouchServerCheck_h

#include <QObject>
#include <QPointer>
#include <QString>

#include "vtkWeakPointer.h"

#include <vector>

class pqServer;
class QTimer;
class vtkObject;

class pqVesselTouchServerCheck : public QObject
{
  Q_OBJECT
public:
  explicit pqVesselTouchServerCheck(QObject* parent = nullptr);
  ~pqVesselTouchServerCheck() override;

  /// Why VesselTouch's server-side filters are unavailable on the active server, with the fix;
  /// "" when they are available (built in, or the server loaded the plugin).
  QString problem() const { return this->Problem; }
  /// The same for `server` ("" for null or built in).
  static QString problemFor(pqServer* server);
  /// The server's name as the user knows it (its resource, e.g. "cs://127.0.0.1:11111").
  static QString serverName(pqServer* server);

Q_SIGNALS:
  /// problem() changed ("" when the server is fine again).
  void problemChanged(const QString& problem);
  /// The connection to `server` (its name) was lost.
  void connectionLost(const QString& server);

private Q_SLOTS:
  void recheck();
  void watch(pqServer* server);
  void pollSockets();

private:
  void onSessionConnectionLost(vtkObject* session, unsigned long event, void* data);

  struct Watched
  {
    QPointer<pqServer> Server;
    vtkWeakPointer<vtkObject> Session;
    unsigned long Tag = 0;
    int Socket = -1; ///< the client's socket to the data server (-1: none, or lost)
  };
  std::vector<Watched> Sessions;
  QTimer* Poll = nullptr;
  QString Problem;
  Q_DISABLE_COPY(pqVesselTouchServerCheck)
};

#endif

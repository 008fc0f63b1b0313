// The panel's side of a Cancel on a pvserver (issue 19 item 1, issue 16 item 6; the Python side is
// vesseltouch.RemoteCancel): while the server's ranks run VesselCenterline the client's connection
// waits for the update's reply, so the cancel goes over the side channel the filter's first rank
// opens (vtouch::RemoteCancelListener, Docs/CLIENT-SERVER.md "Cancel on a pvserver"): the filter's
// RemoteCancelToken (one random string per proxy, set here once), the port named in the progress
// text ("VesselCenterline: cancel port N") and the host the client connected the session to.
// Sending is blocking with time-outs (QTcpSocket's waitFor*: no event loop needed, since it runs
// while the client is inside the update).
#ifndef pqVesselTouchRemoteCancel_h
#define pqVesselTouchRemoteCancel_h

#include <QString>

class vtkSMProxy;

class pqVesselTouchRemoteCancel
{
public:
  /// `host`: the pvserver's host (pqServerResource::host()). `proxy`: the VesselCenterline proxy;
  /// its RemoteCancelToken is set (pushed to the server) if empty.
  pqVesselTouchRemoteCancel(const QString& host, vtkSMProxy* proxy);

  /// Reads the port from one progress text of the server (ignored when it names none).
  void observeProgressText(const QString& text);
  /// Asks for the cancel: sent at once when the port is known, else at the next progress text
  /// that names it. Returns whether the server answered "cancelling" (so far).
  bool cancel();
  /// The user asked for a cancel (cancel() was called).
  bool wanted() const { return this->Wanted; }
  /// The server acknowledged the cancel ("cancelling").
  bool acknowledged() const { return this->Answer == QLatin1String("cancelling"); }
  /// Why a cancel could not be delivered ("" when it was or none was sent).
  const QString& error() const { return this->Error; }
  int port() const { return this->Port; }
  const QString& token() const { return this->Token; }

  /// Project rule (as remote_cancel.py's SEND_TIMEOUT_S): the connection and the answer may take
  /// this long; a server on a LAN answers in milliseconds, and a cancel that cannot be delivered
  /// must not freeze the client for longer.
  static constexpr int SendTimeout_ms = 5000;

private:
  void send();

  QString Host;
  QString Token;
  int Port = 0;
  bool Wanted = false;
  bool Sent = false;
  QString Answer;
  QString Error;
};

#endif

#include "pqVesselTouchRemoteCancel.h"

#include "vtkSMPropertyHelper.h"
#include "vtkSMProxy.h"

#include <QRandomGenerator>
#include <QRegularExpression>
#include <QTcpSocket>

namespace
{
/// A random token of 32 hex digits (as remote_cancel.py's secrets.token_hex(16)).
QString newToken()
{
  QString token;
  for (int i = 0; i < 4; ++i)
  {
    token += QString("%1").arg(QRandomGenerator::system()->generate(), 8, 16, QLatin1Char('0'));
  }
  return token;
}
} // namespace

pqVesselTouchRemoteCancel::pqVesselTouchRemoteCancel(const QString& host, vtkSMProxy* proxy)
  : Host(host)
{
  if (!proxy || !proxy->GetProperty("RemoteCancelToken"))
  {
    this->Error = QStringLiteral("the server's VesselCenterline has no RemoteCancelToken");
    return;
  }
  vtkSMPropertyHelper helper(proxy, "RemoteCancelToken");
  const char* existing = helper.GetAsString();
  this->Token = existing ? QString::fromUtf8(existing) : QString();
  if (this->Token.isEmpty())
  {
    // One token per proxy (as Python's): not a parameter of the output.
    this->Token = newToken();
    helper.Set(this->Token.toUtf8().constData());
    proxy->UpdateVTKObjects();
  }
}

void pqVesselTouchRemoteCancel::observeProgressText(const QString& text)
{
  static const QRegularExpression portText(QStringLiteral("VesselCenterline: cancel port (\\d+)"));
  const QRegularExpressionMatch match = portText.match(text);
  if (match.hasMatch())
  {
    this->Port = match.captured(1).toInt();
  }
  if (this->Wanted && this->Port > 0 && !this->Sent)
  {
    this->send();
  }
}

bool pqVesselTouchRemoteCancel::cancel()
{
  this->Wanted = true;
  if (this->Port > 0 && !this->Sent)
  {
    this->send();
  }
  return this->acknowledged();
}

void pqVesselTouchRemoteCancel::send()
{
  this->Sent = true;
  if (this->Token.isEmpty() || this->Host.isEmpty())
  {
    this->Error = this->Error.isEmpty() ? QStringLiteral("no server to cancel on") : this->Error;
    return;
  }
  QTcpSocket socket;
  socket.connectToHost(this->Host, static_cast<quint16>(this->Port));
  if (!socket.waitForConnected(SendTimeout_ms))
  {
    this->Error = QStringLiteral("the cancel could not reach %1:%2: %3")
                    .arg(this->Host)
                    .arg(this->Port)
                    .arg(socket.errorString());
    return;
  }
  socket.write((this->Token + QLatin1Char('\n')).toUtf8());
  if (!socket.waitForBytesWritten(SendTimeout_ms))
  {
    this->Error = QStringLiteral("the cancel was not sent: %1").arg(socket.errorString());
    return;
  }
  while (!socket.canReadLine() && socket.waitForReadyRead(SendTimeout_ms))
  {
  }
  this->Answer = QString::fromUtf8(socket.readLine()).trimmed();
  if (!this->acknowledged())
  {
    this->Error = QStringLiteral("the server answered %1").arg(this->Answer);
  }
}

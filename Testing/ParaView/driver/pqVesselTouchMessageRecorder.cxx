#include "pqVesselTouchMessageRecorder.h"

#include "pqCoreUtilities.h"
#include "pqOutputWidget.h"

#include <QDockWidget>
#include <QMutex>
#include <QMutexLocker>
#include <QWidget>
#include <QtGlobal>

namespace
{
/// Kept messages: enough for a test's window of interest, bounded for a long GUI session.
constexpr int kKeptMessages = 200;

QMutex gMutex;
QStringList gMessages;
QStringList gDisplayed;
QtMessageHandler gPrevious = nullptr;
bool gInstalled = false;

void keep(QStringList& list, const QString& entry)
{
  list.append(entry);
  while (list.size() > kKeptMessages)
  {
    list.removeFirst();
  }
}

pqOutputWidget* outputWidget()
{
  QWidget* window = pqCoreUtilities::mainWidget();
  return window ? window->findChild<pqOutputWidget*>() : nullptr;
}

void record(QtMsgType type, const QMessageLogContext& context, const QString& text)
{
  const char* kind = type == QtWarningMsg ? "warning"
    : type == QtCriticalMsg               ? "critical"
    : type == QtFatalMsg                  ? "fatal"
                                          : nullptr;
  if (kind)
  {
    QMutexLocker lock(&gMutex);
    keep(gMessages, QStringLiteral("%1: %2").arg(QLatin1String(kind), text));
  }
  if (gPrevious)
  {
    gPrevious(type, context, text);
  }
}
} // namespace

void pqVesselTouchMessageRecorder::install()
{
  if (gInstalled)
  {
    return;
  }
  gInstalled = true;
  gPrevious = qInstallMessageHandler(record);
  if (pqOutputWidget* output = outputWidget())
  {
    QObject::connect(output, &pqOutputWidget::messageDisplayed, output,
      [](const QString& message, int)
      {
        QMutexLocker lock(&gMutex);
        keep(gDisplayed, message.trimmed());
      });
  }
}

QStringList pqVesselTouchMessageRecorder::displayedMessages()
{
  QMutexLocker lock(&gMutex);
  return gDisplayed;
}

QStringList pqVesselTouchMessageRecorder::messages()
{
  QMutexLocker lock(&gMutex);
  return gMessages;
}

bool pqVesselTouchMessageRecorder::outputMessagesVisible()
{
  pqOutputWidget* output = outputWidget();
  for (QWidget* w = output; w; w = w->parentWidget())
  {
    if (qobject_cast<QDockWidget*>(w))
    {
      return w->isVisible();
    }
  }
  return output && output->isVisible();
}

#include "pqVesselTouchTestHooks.h"

#include "pqVesselTouchPanelSelfTest.h"
#include "pqVesselTouchTestDriver.h"

#include "pqVesselTouchAgentDisplay.h"
#include "pqVesselTouchDockPanel.h"
#include "pqVesselTouchSessionBinding.h"
#include "pqVesselTouchShowAgentAction.h"

#include "qVesselTouchInfoWidget.h"

#include "pqCoreUtilities.h"

#include <QAction>
#include <QApplication>
#include <QJsonDocument>
#include <QJsonObject>
#include <QSaveFile>
#include <QTimer>
#include <QWidget>
#include <QtDebug>

namespace
{
/// How often the hooks look for the panel and the toolbar, ms, and for how long (60 s).
constexpr int kAttachPeriod_ms = 100;
constexpr int kMaxAttachAttempts = 600;
/// The panel report's period, ms.
constexpr int kPanelReportPeriod_ms = 250;
/// Drawn frames between two agent reports (about twice a second at the display's 60 Hz).
constexpr int kFramesPerAgentReport = 30;

/// Replaces `path` in one step (rename(2)): a reader never finds it missing or half written.
void writeJson(const QString& path, const QJsonObject& object)
{
  QSaveFile file(path);
  if (file.open(QIODevice::WriteOnly | QIODevice::Truncate))
  {
    file.write(QJsonDocument(object).toJson());
    file.commit();
  }
}

template<typename T>
T* findAnywhere()
{
  for (QWidget* top : QApplication::topLevelWidgets())
  {
    if (auto* found = qobject_cast<T*>(top))
    {
      return found;
    }
    if (auto* found = top->findChild<T*>())
    {
      return found;
    }
  }
  return nullptr;
}

bool flagSet(const char* name)
{
  return qEnvironmentVariableIntValue(name) == 1;
}
} // namespace

pqVesselTouchTestHooks::pqVesselTouchTestHooks(QObject* parentObject)
  : QObject(parentObject)
{
}

pqVesselTouchTestHooks::~pqVesselTouchTestHooks() = default;

void pqVesselTouchTestHooks::startup()
{
  QTimer::singleShot(0, this, &pqVesselTouchTestHooks::attach);
}

void pqVesselTouchTestHooks::attach()
{
  this->Panel = findAnywhere<pqVesselTouchDockPanel>();
  this->AgentAction = findAnywhere<pqVesselTouchShowAgentAction>();
  if (!this->Panel || !this->AgentAction)
  {
    if (++this->Attempts < kMaxAttachAttempts)
    {
      QTimer::singleShot(kAttachPeriod_ms, this, &pqVesselTouchTestHooks::attach);
    }
    else
    {
      qWarning() << "VesselTouchTestDriver: no VesselTouch panel or toolbar (is the VesselTouch "
                    "plugin loaded?)";
    }
    return;
  }
  this->install();
}

void pqVesselTouchTestHooks::install()
{
  pqVesselTouchDockPanel* panel = this->Panel;
  if (!qEnvironmentVariableIsEmpty("VESSELTOUCH_GUI_DRIVER"))
  {
    new pqVesselTouchTestDriver(panel, qEnvironmentVariable("VESSELTOUCH_GUI_DRIVER"));
  }
  if (!qEnvironmentVariableIsEmpty("VESSELTOUCH_GUI_SELFTEST"))
  {
    auto* selfTest =
      new pqVesselTouchPanelSelfTest(panel, qEnvironmentVariable("VESSELTOUCH_GUI_SELFTEST"));
    selfTest->start();
  }
  if (!qEnvironmentVariableIsEmpty("VESSELTOUCH_GUI_REPORT"))
  {
    auto* timer = new QTimer(this);
    QObject::connect(timer, &QTimer::timeout, this, &pqVesselTouchTestHooks::writePanelReport);
    timer->start(kPanelReportPeriod_ms);
    this->writePanelReport();
  }
  if (!qEnvironmentVariableIsEmpty("VESSELTOUCH_AGENT_REPORT"))
  {
    QObject::connect(this->AgentAction->display(),
      &pqVesselTouchAgentDisplay::frameDrawn,
      this,
      &pqVesselTouchTestHooks::onAgentFrameDrawn);
  }
  if (flagSet("VESSELTOUCH_GUI_AGENT"))
  {
    this->AgentAction->setChecked(true);
  }
  if (flagSet("VESSELTOUCH_GUI_TRACE_MOUSE"))
  {
    QWidget* main = pqCoreUtilities::mainWidget();
    if (auto* trace = main ? main->findChild<QAction*>("actionVesselTouchTraceWithMouse") : nullptr)
    {
      trace->setChecked(true);
    }
  }
}

void pqVesselTouchTestHooks::writePanelReport()
{
  pqVesselTouchDockPanel* panel = this->Panel;
  const qVesselTouchInfoWidget* info =
    panel ? panel->findChild<qVesselTouchInfoWidget*>() : nullptr;
  if (!info)
  {
    return;
  }
  QJsonObject versions;
  for (const QString& component : info->versionComponents())
  {
    versions.insert(component, info->version(component));
  }
  QJsonObject report;
  report.insert("panel", panel->objectName());
  report.insert("title", panel->windowTitle());
  report.insert("visible", panel->isVisible());
  report.insert("dataset", info->datasetName());
  report.insert("summary", info->datasetSummary());
  report.insert("versions", versions);
  report.insert("session", panel->sessionBinding()->proxy() != nullptr);
  writeJson(qEnvironmentVariable("VESSELTOUCH_GUI_REPORT"), report);
}

void pqVesselTouchTestHooks::onAgentFrameDrawn()
{
  if (!this->AgentAction || ++this->FramesSinceAgentReport < kFramesPerAgentReport)
  {
    return;
  }
  this->FramesSinceAgentReport = 0;
  QJsonObject report = this->AgentAction->display()->diagnostics();
  // Numbered, so a test can wait for a report written after what it did.
  report.insert("sequence", static_cast<double>(++this->AgentReports));
  writeJson(qEnvironmentVariable("VESSELTOUCH_AGENT_REPORT"), report);
}

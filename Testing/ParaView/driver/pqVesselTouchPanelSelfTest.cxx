#include "pqVesselTouchPanelSelfTest.h"

#include "pqVesselTouchCenterlineWorkflow.h"
#include "pqVesselTouchDockPanel.h"
#include "pqVesselTouchSessionBinding.h"
#include "pqVesselTouchSessionStatus.h"
#include "pqVesselTouchAgentDisplay.h"
#include "pqVesselTouchShowAgentAction.h"

#include "qVesselTouchDeviceWidget.h"
#include "qVesselTouchForceLawWidget.h"
#include "qVesselTouchForceZonesWidget.h"
#include "qVesselTouchHapticZoomWidget.h"
#include "qVesselTouchLoopStatsWidget.h"
#include "qVesselTouchHapticParameterForm.h"

#include "pqActiveObjects.h"
#include "pqCoreUtilities.h"
#include "pqApplicationCore.h"
#include "pqObjectBuilder.h"
#include "pqOutputPort.h"
#include "pqPipelineSource.h"
#include "pqRenderView.h"
#include "pqServerManagerModel.h"
#include "pqSettings.h"

#include "vtkAlgorithm.h"
#include "vtkCell.h"
#include "vtkPVDataInformation.h"
#include "vtkPolyData.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSMRenderViewProxy.h"
#include "vtkSMPropertyHelper.h"
#include "vtkSMProxy.h"
#include "vtkVesselTouchHapticSession.h"
#include "vtouchHapticParameterTable.h"

#include <QCoreApplication>
#include <QFile>
#include <QJsonArray>
#include <QJsonDocument>
#include <QMouseEvent>
#include <QPushButton>
#include <QStringList>
#include <QTimer>
#include <QWidget>
#include <QtDebug>

#include <cmath>

namespace
{
constexpr int kPollPeriod_ms = 500;
constexpr int kMaxSceneAttempts = 300; // 150 s
constexpr int kRunTime_ms = 1500;
constexpr int kSettleTime_ms = 300;
} // namespace

pqVesselTouchPanelSelfTest::pqVesselTouchPanelSelfTest(pqVesselTouchDockPanel* panel,
  const QString& reportPath)
  : QObject(panel)
  , Panel(panel)
  , ReportPath(reportPath)
{
}

pqVesselTouchPanelSelfTest::~pqVesselTouchPanelSelfTest() = default;

void pqVesselTouchPanelSelfTest::start()
{
  QTimer::singleShot(kPollPeriod_ms, this, &pqVesselTouchPanelSelfTest::waitForScene);
}

void pqVesselTouchPanelSelfTest::fail(const QString& message)
{
  this->Report.insert("error", message);
  this->finish();
}

void pqVesselTouchPanelSelfTest::waitForScene()
{
  pqServerManagerModel* model = pqApplicationCore::instance()->getServerManagerModel();
  for (pqPipelineSource* source : model->findItems<pqPipelineSource*>())
  {
    vtkPVDataInformation* info = source->getOutputPort(0)->getDataInformation();
    if (QLatin1String(source->getProxy()->GetXMLName()) == QLatin1String("VesselPhantom") && info &&
        info->GetNumberOfPoints() > 0 && pqActiveObjects::instance().activeView())
    {
      this->Phantom = source;
    }
  }
  // The start-up script writes VESSELTOUCH_DONE_FLAG last: wait for it so that its own session
  // settings do not race with the self-test's.
  const QString doneFlag = qEnvironmentVariable("VESSELTOUCH_DONE_FLAG");
  const bool scriptDone = doneFlag.isEmpty() || QFile::exists(doneFlag);
  if (!this->Phantom || !scriptDone)
  {
    if (++this->Attempts > kMaxSceneAttempts)
    {
      this->fail(
        this->Phantom ? "the start-up script did not finish" : "no VesselPhantom appeared");
      return;
    }
    QTimer::singleShot(kPollPeriod_ms, this, &pqVesselTouchPanelSelfTest::waitForScene);
    return;
  }
  this->Report.insert("phantom", this->Phantom->getSMName());
  // Let the start-up script finish its render first.
  QTimer::singleShot(2000, this, &pqVesselTouchPanelSelfTest::deleteSession);
}

void pqVesselTouchPanelSelfTest::deleteSession()
{
  if (!this->Panel)
  {
    return;
  }
  pqVesselTouchSessionBinding* binding = this->Panel->sessionBinding();
  this->Report.insert("session_at_startup", binding->proxy() != nullptr);
  // The session as the panel's default values set it (a fresh user: no saved settings).
  this->Report.insert("values_at_startup", this->sessionValues());
  if (binding->source())
  {
    pqApplicationCore::instance()->getObjectBuilder()->destroy(binding->source());
  }
  this->Report.insert("session_after_delete", binding->proxy() != nullptr);
  QTimer::singleShot(kSettleTime_ms, this, &pqVesselTouchPanelSelfTest::setWidgets);
}

void pqVesselTouchPanelSelfTest::setWidgets()
{
  if (!this->Panel)
  {
    return;
  }
  pqVesselTouchDockPanel& panel = *this->Panel;
  panel.deviceWidget()->setCurrentDeviceId("simulated");
  panel.forceLawWidget()->setForceLaw(qVesselTouchForceLawWidget::ChangeOfHeight);
  qVesselTouchForceLawParameters law = panel.forceLawWidget()->parameters();
  law.cohGain_N = 0.7;
  law.haptic.cohLambda_mm = 0.02;
  panel.forceLawWidget()->setParameters(law);
  panel.zoomWidget()->setRatio(2.5);
  panel.zonesWidget()->setThresholds(0.1, 0.6);
  // The Advanced section's tick options (issue 17).
  if (auto* tick = panel.findChild<qVesselTouchHapticParameterForm*>("tickOptionsWidget"))
  {
    vtouch::HapticParameters options = tick->parameters();
    options.tracerJunctionWindow_px = 12.0;
    options.proxyTickSpacing_mm = 2.0;
    options.proxyTangentSnap = true;
    options.idleDwell_s = 3.0;
    tick->setParameters(options);
  }
  this->Report.insert("zones_gain_N", panel.zonesWidget()->gain_N());
  QTimer::singleShot(kSettleTime_ms, this, &pqVesselTouchPanelSelfTest::pickAndExtract);
}

bool pqVesselTouchPanelSelfTest::centerlinePixel(double point_mm[3], QPoint& pixel) const
{
  auto* view = qobject_cast<pqRenderView*>(pqActiveObjects::instance().activeView());
  auto* algorithm = this->Phantom
                      ? vtkAlgorithm::SafeDownCast(this->Phantom->getProxy()->GetClientSideObject())
                      : nullptr;
  auto* lines = algorithm ? vtkPolyData::SafeDownCast(algorithm->GetOutputDataObject(1)) : nullptr;
  vtkRenderer* renderer = view ? view->getRenderViewProxy()->GetRenderer() : nullptr;
  if (!lines || lines->GetNumberOfCells() < 1 || !renderer || !view->widget())
  {
    return false;
  }
  vtkCell* vessel = lines->GetCell(0);
  lines->GetPoint(vessel->GetPointId(vessel->GetNumberOfPoints() / 2), point_mm);
  renderer->SetWorldPoint(point_mm[0], point_mm[1], point_mm[2], 1.0);
  renderer->WorldToDisplay();
  const double* display = renderer->GetDisplayPoint();
  const double ratio = view->widget()->devicePixelRatioF();
  const int height_px = renderer->GetRenderWindow()->GetSize()[1];
  pixel = QPoint(static_cast<int>(std::lround(display[0] / ratio)),
    static_cast<int>(std::lround((height_px - 1 - display[1]) / ratio)));
  return true;
}

void pqVesselTouchPanelSelfTest::pickAndExtract()
{
  if (!this->Panel)
  {
    return;
  }
  pqVesselTouchDockPanel& panel = *this->Panel;
  QJsonObject seed;
  double target_mm[3] = { 0.0, 0.0, 0.0 };
  QPoint pixel;
  if (this->centerlinePixel(target_mm, pixel))
  {
    seed.insert("target_mm", QJsonArray{ target_mm[0], target_mm[1], target_mm[2] });
    seed.insert("pixel", QJsonArray{ pixel.x(), pixel.y() });
    // What the user does: "Pick seed", then a click in the view (the armed one-shot filter).
    auto* button = panel.findChild<QPushButton*>("pickSeedButton");
    auto* view = qobject_cast<pqRenderView*>(pqActiveObjects::instance().activeView());
    if (button && view && view->widget())
    {
      button->setChecked(true);
      QMouseEvent press(
        QEvent::MouseButtonPress, QPointF(pixel), Qt::LeftButton, Qt::LeftButton, Qt::NoModifier);
      QCoreApplication::sendEvent(view->widget(), &press);
      QMouseEvent release(
        QEvent::MouseButtonRelease, QPointF(pixel), Qt::LeftButton, Qt::NoButton, Qt::NoModifier);
      QCoreApplication::sendEvent(view->widget(), &release);
      seed.insert("button_released", !button->isChecked());
    }
    double picked_mm[3];
    seed.insert("picked", panel.centerlineWorkflow()->seed(picked_mm));
    double seed_mm[3];
    if (panel.centerlineWorkflow()->seed(seed_mm))
    {
      seed.insert("position_mm", QJsonArray{ seed_mm[0], seed_mm[1], seed_mm[2] });
    }
  }
  else
  {
    seed.insert("error", "no analytic centerline or render view");
  }
  double bounds[6];
  this->Phantom->getOutputPort(0)->getDataInformation()->GetBounds(bounds);
  seed.insert("volume_bounds_mm",
    QJsonArray{ bounds[0], bounds[1], bounds[2], bounds[3], bounds[4], bounds[5] });
  seed.insert("panel_error", panel.errorText());
  seed.insert("thresholds",
    QJsonArray{
      panel.centerlineWorkflow()->lowerThreshold(), panel.centerlineWorkflow()->upperThreshold() });
  this->Report.insert("seed", seed);

  panel.centerlineWorkflow()->extract();
  this->reportExtraction();
}

void pqVesselTouchPanelSelfTest::reportExtraction()
{
  if (!this->Panel)
  {
    return;
  }
  pqVesselTouchDockPanel& panel = *this->Panel;
  if (panel.centerlineWorkflow()->isRunning())
  {
    QTimer::singleShot(kSettleTime_ms / 3, this, &pqVesselTouchPanelSelfTest::reportExtraction);
    return;
  }
  QJsonObject extraction;
  pqPipelineSource* centerline = panel.centerlineWorkflow()->centerline();
  extraction.insert("paths",
    centerline ? centerline->getOutputPort(0)->getDataInformation()->GetNumberOfCells() : 0);
  vtkSMProxy* session = panel.sessionBinding()->proxy();
  extraction.insert("session_created", session != nullptr);
  extraction.insert("session_input_is_extracted",
    session && centerline &&
      vtkSMPropertyHelper(session, "Input").GetAsProxy() == centerline->getProxy());
  extraction.insert("panel_error", panel.errorText());
  this->Report.insert("extraction", extraction);
  QTimer::singleShot(kSettleTime_ms, this, &pqVesselTouchPanelSelfTest::startSession);
}

void pqVesselTouchPanelSelfTest::startSession()
{
  if (!this->Panel)
  {
    return;
  }
  const bool started = this->Panel->startSession();
  this->Report.insert("start_returned", started);
  this->Report.insert("values_after_widgets", this->sessionValues());
  this->Report.insert("error_after_start", this->Panel->errorText());
  QTimer::singleShot(kRunTime_ms, this, &pqVesselTouchPanelSelfTest::changeWhileRunning);
}

void pqVesselTouchPanelSelfTest::changeWhileRunning()
{
  if (!this->Panel)
  {
    return;
  }
  this->Report.insert("status_running", this->status());
  const qVesselTouchLoopStats shown = this->Panel->loopStatsWidget()->stats();
  this->Report.insert("loop_widget_running", shown.running);
  this->Report.insert("loop_widget_ticks", static_cast<double>(shown.ticks));
  // The panel's running session switches the toolbar's agent display on (pqVesselTouchViewBinding).
  QWidget* mainWindow = pqCoreUtilities::mainWidget();
  auto* agent = mainWindow ? mainWindow->findChild<pqVesselTouchShowAgentAction*>() : nullptr;
  QJsonObject agentReport;
  agentReport.insert("action_found", agent != nullptr);
  if (agent)
  {
    pqVesselTouchAgentDisplay* display = agent->display();
    agentReport.insert("checked", agent->isChecked());
    agentReport.insert("enabled", display->isEnabled());
    agentReport.insert(
      "bound_to_session", display->session() == this->Panel->sessionBinding()->proxy());
    agentReport.insert(
      "frames", static_cast<double>(display->fullRenders() + display->cachedFrames()));
  }
  this->Report.insert("agent_display_running", agentReport);
  this->Panel->zoomWidget()->setRatio(1.5);
  this->Report.insert("values_changed_while_running", this->sessionValues());
  QTimer::singleShot(kSettleTime_ms, this, &pqVesselTouchPanelSelfTest::stopSession);
}

void pqVesselTouchPanelSelfTest::stopSession()
{
  if (!this->Panel)
  {
    return;
  }
  this->Panel->stopSession();
  QTimer::singleShot(kSettleTime_ms, this, &pqVesselTouchPanelSelfTest::editFromOutside);
}

void pqVesselTouchPanelSelfTest::editFromOutside()
{
  if (!this->Panel)
  {
    return;
  }
  this->Report.insert("status_stopped", this->status());
  // What the Python console does: set a property on the shared proxy.
  if (vtkSMProxy* session = this->Panel->sessionBinding()->proxy())
  {
    vtkSMPropertyHelper(session, "Zoom").Set(3.0);
    session->UpdateVTKObjects();
  }
  QTimer::singleShot(kSettleTime_ms, this, &pqVesselTouchPanelSelfTest::saveAndLoadState);
}

void pqVesselTouchPanelSelfTest::saveAndLoadState()
{
  if (!this->Panel)
  {
    return;
  }
  pqVesselTouchDockPanel& panel = *this->Panel;
  this->Report.insert("zoom_widget_after_outside_edit", panel.zoomWidget()->ratio());
  const QString state = this->ReportPath + ".pvsm";
  pqApplicationCore* core = pqApplicationCore::instance();
  this->Report.insert("state_saved", core->saveState(state));
  panel.zoomWidget()->setRatio(4.0); // the loaded state must bring 3 back
  this->Report.insert("zoom_widget_before_load", panel.zoomWidget()->ratio());
  core->loadState(state.toUtf8().constData(), pqActiveObjects::instance().activeServer());
  QTimer::singleShot(kSettleTime_ms,
    this,
    [this]()
    {
      if (!this->Panel)
      {
        return;
      }
      vtkSMProxy* session = this->Panel->sessionBinding()->proxy();
      this->Report.insert("session_after_load", session != nullptr);
      this->Report.insert("session_zoom_after_load",
        session ? vtkSMPropertyHelper(session, "Zoom").GetAsDouble() : 0.0);
      this->Report.insert("zoom_widget_after_load", this->Panel->zoomWidget()->ratio());
      this->Report.insert(
        "law_widget_after_load", static_cast<int>(this->Panel->forceLawWidget()->forceLaw()));
      if (pqSettings* settings = pqApplicationCore::instance()->settings())
      {
        QJsonObject saved;
        for (const char* key : { "ForceLaw",
               "CohGain_N",
               "ChangeOfHeightLambda",
               "Zoom",
               "ZoneZeroBelow",
               "ZoneSaturateAbove",
               "Device" })
        {
          saved.insert(
            key, QJsonValue::fromVariant(settings->value(QString("VesselTouch/") + key)));
        }
        this->Report.insert("settings", saved);
      }
      this->closePanelWhileRunning();
    });
}

void pqVesselTouchPanelSelfTest::closePanelWhileRunning()
{
  if (!this->Panel)
  {
    return;
  }
  this->Report.insert("restart_returned", this->Panel->startSession());
  QTimer::singleShot(kSettleTime_ms,
    this,
    [this]()
    {
      if (!this->Panel)
      {
        return;
      }
      this->Report.insert("status_before_close", this->status());
      this->Panel->close(); // the dock's close button
      this->Report.insert("status_after_close", this->status());
      this->Panel->show();
      this->finish();
    });
}

QJsonObject pqVesselTouchPanelSelfTest::sessionValues() const
{
  QJsonObject values;
  vtkSMProxy* session = this->Panel ? this->Panel->sessionBinding()->proxy() : nullptr;
  if (!session)
  {
    return values;
  }
  values.insert("DeviceType", vtkSMPropertyHelper(session, "DeviceType").GetAsInt());
  for (const vtouch::HapticParameterDescriptor& d : vtouch::kHapticParameterDescriptors)
  {
    values.insert(d.name, vtkSMPropertyHelper(session, d.name).GetAsDouble());
  }
  // What the running session really uses: the haptic parameters the C++ session holds, read
  // from the VTK object behind the proxy (builtin session).
  if (auto* vtk = vtkVesselTouchHapticSession::SafeDownCast(session->GetClientSideObject()))
  {
    QJsonObject object;
    const QStringList applied =
      QString::fromUtf8(vtk->GetAppliedHapticParameters()).split(' ', Qt::SkipEmptyParts);
    for (const QString& pair : applied)
    {
      const int at = pair.indexOf('=');
      object.insert(pair.left(at), pair.mid(at + 1).toDouble());
    }
    object.insert("DeviceType", vtk->GetDeviceType());
    values.insert("vtk_object", object);
  }
  values.insert("registration_name", QString(pqVesselTouchSessionBinding::registrationName()));
  return values;
}

QJsonObject pqVesselTouchPanelSelfTest::status() const
{
  vtkSMProxy* session = this->Panel ? this->Panel->sessionBinding()->proxy() : nullptr;
  const pqVesselTouchSessionStatus s = pqVesselTouchSessionStatus::read(session);
  QJsonObject status;
  status.insert("running", s.running);
  status.insert("fault", s.faultCode);
  status.insert("last_error", s.lastError);
  status.insert("ticks", static_cast<double>(s.loop.ticks));
  status.insert("achieved_rate_Hz", s.loop.achievedRate_Hz);
  status.insert("skeleton_paths", s.skeletonPaths);
  status.insert(
    "device_force_N", QJsonArray{ s.deviceForce_N[0], s.deviceForce_N[1], s.deviceForce_N[2] });
  status.insert("device_force_magnitude_N", s.deviceForceMagnitude_N());
  status.insert("summary", s.summary());
  return status;
}

void pqVesselTouchPanelSelfTest::finish()
{
  QFile file(this->ReportPath);
  if (!file.open(QIODevice::WriteOnly | QIODevice::Truncate))
  {
    qWarning() << "VesselTouch self-test: cannot write" << this->ReportPath;
    return;
  }
  this->Report.insert("done", true);
  file.write(QJsonDocument(this->Report).toJson());
}

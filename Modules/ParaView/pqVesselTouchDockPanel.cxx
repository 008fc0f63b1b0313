#include "pqVesselTouchDockPanel.h"
#include "ui_pqVesselTouchDockPanel.h"

#include "pqVesselTouchCenterlineWorkflow.h"
#include "pqVesselTouchDatasetSummary.h"
#include "pqVesselTouchPanelValues.h"
#include "pqVesselTouchSessionBinding.h"
#include "pqVesselTouchServerCheck.h"
#include "pqVesselTouchSessionStatus.h"
#include "pqVesselTouchViewBinding.h"

#include "qVesselTouchDeviceWidget.h"
#include "vtouchHidapiTransport.h"
#include "qVesselTouchForceLawWidget.h"
#include "qVesselTouchForceZonesWidget.h"
#include "qVesselTouchHapticZoomWidget.h"
#include "qVesselTouchInfoWidget.h"
#include "qVesselTouchLoopStatsWidget.h"
#include "qVesselTouchHapticParameterForm.h"

#include "pqActiveObjects.h"
#include "pqApplicationCore.h"
#include "pqCoreUtilities.h"
#include "pqOutputPort.h"
#include "pqPipelineSource.h"
#include "pqRenderView.h"
#include "pqSettings.h"

#include "vtkDataSetAttributes.h"
#include "vtkPVArrayInformation.h"
#include "vtkPVDataInformation.h"
#include "vtkPVDataSetAttributesInformation.h"
#include "vtkPVVersion.h"
#include "vtkPVXMLElement.h"
#include "vtkSMProperty.h"
#include "vtkSMPropertyHelper.h"
#include "vtkSMProxy.h"
#include "vtkSMProxyLocator.h"
#include "vtkVesselTouchVersion.h"

#include <QCloseEvent>
#include <QCoreApplication>
#include <QLabel>
#include <QMainWindow>
#include <QScrollArea>
#include <QSignalBlocker>
#include <QTimer>
#include <QDateTime>
#include <QDir>
#include <QtDebug>

#include <algorithm>

namespace
{
/// Status refresh period while a session exists, ms (~10 Hz).
constexpr int kStatusPeriod_ms = 100;
/// The panel's width when it first shows, pixels.
constexpr int kPanelWidth_px = 450;
/// The Advanced section's haptic parameters (issue 17's tick options): rows built from the
/// parameter table (label, unit, range, meaning), the force-law widget edits the laws' own.
const char* const kAdvancedParameters[] = { "TracerRule",
  "TracerMovementThreshold",
  "TracerJunctionWindow",
  "TracerJunctionMargin",
  "ContactDwell",
  "ContactApproachAtStart",
  "SlopeForceBudget",
  "ForceInterpolationPerAxis",
  "MaxForceRate",
  "ChangeOfHeightZMaxPerResolution",
  "ProxyTangentSnap",
  "ProxyNormalUnilateral",
  "ProxyThresholdFromData",
  "ProxyFriction",
  "ProxyTickSpacing",
  "ProxyTickForce",
  "ProxyTickAtBifurcations",
  "ProxyFieldForce",
  "IdleRadius",
  "IdleDwell",
  "IdleRamp" };

/// The "Help & Acknowledgement" section: the workflow in a few lines and the papers VesselTouch
/// implements.
QString helpText()
{
  return QCoreApplication::translate("pqVesselTouchDockPanel",
    "<p><b>Workflow.</b> Open a 3D angiogram (CTA, TOF-MRA), press <i>MIP</i> on the VesselTouch "
    "toolbar, <i>Pick seed</i> and click a vessel, <i>Extract</i>. Choose a device (the mouse "
    "works: <i>Trace with mouse</i>), <i>Start</i>, and feel the vessels: the agent (the cone) "
    "follows a vessel when you move along it; a click returns to exploring. Ctrl + left drag "
    "rotates the view while tracing. See Docs/USING.md.</p>"
    "<p><b>Acknowledgement.</b> VesselTouch implements:<br>"
    "D. Yi, V. Hayward, <i>Augmenting Computer Graphics with Haptics for the Visualization of "
    "Vessel Networks</i> (Q-skeleton, tracing, LDGF, force zones, haptic zoom);<br>"
    "M. Ikits, J. D. Brederson, C. D. Hansen, C. R. Johnson, <i>A Constraint-Based Technique "
    "for Haptic Volume Exploration</i> (constraint proxy);<br>"
    "V. Hayward, D. Yi, <i>Change of Height: An Approach to the Haptic Display of Shape and "
    "Texture Without Surface Normal</i> (change of height).</p>");
}
} // namespace

class pqVesselTouchDockPanel::pqInternals
{
public:
  Ui::pqVesselTouchDockPanel Ui;
  pqVesselTouchSessionBinding* Binding = nullptr;
  pqVesselTouchCenterlineWorkflow* Centerlines = nullptr;
  QTimer StatusTimer;
  QPointer<pqPipelineSource> Source;
  bool Revealed = false;
  bool Syncing = false;
  bool Running = false;
  /// The panel's own last error (a failed pick, no centerline...) and the session's (its last
  /// error or fault); the red line shows the session's first.
  QString PanelError;
  QVariantMap ShownDeviceCapabilities; // what the device section shows, to update on change only
  /// The open device's calibration as last given to the device section (same purpose).
  bool ShownHasCalibration = false;
  qVesselTouchDeviceCalibration ShownCalibration;
  QString SessionError;

  pqVesselTouchPanelValues fromWidgets() const
  {
    pqVesselTouchPanelValues v;
    v.law = this->Ui.forceLawWidget->parameters();
    vtouch::HapticParameters& haptic = v.law.haptic;
    haptic.forceLaw = static_cast<vtouch::ForceLawId>(this->Ui.forceLawWidget->forceLaw());
    haptic.zoom = this->Ui.zoomWidget->ratio();
    haptic.zoneZeroBelow = this->Ui.zonesWidget->zeroBelow();
    haptic.zoneSaturateAbove = this->Ui.zonesWidget->saturateAbove();
    v.deviceId = this->Ui.deviceWidget->currentDeviceId();
    // The Advanced section's rows (the tick's options of issue 17).
    this->Ui.tickOptionsWidget->writeTo(haptic);
    return v;
  }

  void toWidgets(const pqVesselTouchPanelValues& v, double zoneGain_N)
  {
    this->Syncing = true;
    if (v.forceLaw() >= 0 && v.forceLaw() < qVesselTouchForceLawWidget::kForceLawCount)
    {
      this->Ui.forceLawWidget->setForceLaw(v.forceLaw());
    }
    // The force-law widget keeps every haptic parameter (those without a widget ride along).
    this->Ui.forceLawWidget->setParameters(v.law);
    this->Ui.zoomWidget->setRatio(v.law.haptic.zoom);
    this->Ui.zonesWidget->setThresholds(v.law.haptic.zoneZeroBelow, v.law.haptic.zoneSaturateAbove);
    this->Ui.zonesWidget->setGain_N(v.activeGain_N(zoneGain_N));
    this->Ui.deviceWidget->setCurrentDeviceId(v.deviceId);
    this->Ui.tickOptionsWidget->setParameters(v.law.haptic);
    this->Ui.tickOptionsWidget->setForceLaw(static_cast<int>(this->Ui.forceLawWidget->forceLaw()));
    this->Syncing = false;
  }

  void saveSettings() const
  {
    if (pqSettings* settings = pqApplicationCore::instance()->settings())
    {
      this->fromWidgets().save(*settings);
    }
  }

  void writeSession()
  {
    const pqVesselTouchPanelValues values = this->fromWidgets();
    const double zoneGain_N = values.activeGain_N(this->Ui.zonesWidget->gain_N());
    this->Binding->writeProperties(
      [&](vtkSMProxy* session) { values.writeToProxy(session, zoneGain_N); });
  }
};

pqVesselTouchDockPanel::pqVesselTouchDockPanel(QWidget* parentObject)
  : QDockWidget(tr("VesselTouch"), parentObject)
  , Internals(new pqInternals)
{
  pqInternals& in = *this->Internals;
  auto* content = new QWidget(this);
  in.Ui.setupUi(content);
  in.Ui.infoWidget->setObjectName("VesselTouchInfo");
  in.Ui.infoWidget->setVersion("VesselTouch", vtkVesselTouchVersion::GetVesselTouchVersion());
  in.Ui.infoWidget->setVersion("ParaView", PARAVIEW_VERSION_FULL);
  in.Ui.infoWidget->setVersion("VTK", vtkVesselTouchVersion::GetVTKVersion());
  in.Ui.infoWidget->setVersion("ITK", vtkVesselTouchVersion::GetITKVersion());
  in.Ui.infoWidget->setVersion("hidapi", vtkVesselTouchVersion::GetHIDAPIVersion());
  in.Ui.stopButton->setEnabled(false);

  // One value, one field: the zones plot shows the force law's gain k, edited in the law.
  in.Ui.zonesWidget->setGainEditable(false);
  in.Ui.advancedGroup->setCollapsed(true);
  in.Ui.helpGroup->setCollapsed(true);
  in.Ui.helpText->setText(helpText());
  QObject::connect(in.Ui.resetDefaultsButton,
    &QPushButton::clicked,
    this,
    [this]()
    {
      pqInternals& internals = *this->Internals;
      pqVesselTouchPanelValues defaults;
      defaults.deviceId = internals.Ui.deviceWidget->currentDeviceId(); // not a force setting
      internals.toWidgets(
        defaults, defaults.activeGain_N(qVesselTouchForceLawParameters::defaultGain_N()));
      this->onWidgetsEdited();
    });

  auto* scroll = new QScrollArea(this);
  scroll->setObjectName("VesselTouchScroll");
  scroll->setWidgetResizable(true);
  // Wrapped labels follow the panel's width instead of setting it.
  for (QLabel* label : content->findChildren<QLabel*>())
  {
    if (label->wordWrap())
    {
      QSizePolicy policy = label->sizePolicy();
      policy.setHorizontalPolicy(QSizePolicy::Ignored);
      label->setSizePolicy(policy);
    }
  }
  // The panel fits its dock's width (no sideways scrolling, no cut-off left edge).
  scroll->setHorizontalScrollBarPolicy(Qt::ScrollBarAlwaysOff);
  scroll->setWidget(content);
  this->setWidget(scroll);

  in.Binding = new pqVesselTouchSessionBinding(this);
  in.Centerlines = new pqVesselTouchCenterlineWorkflow(in.Ui, this);

  in.StatusTimer.setInterval(kStatusPeriod_ms);
  QObject::connect(
    &in.StatusTimer, &QTimer::timeout, this, &pqVesselTouchDockPanel::updateSessionStatus);

  QStringList advanced;
  for (const char* name : kAdvancedParameters)
  {
    advanced << QString::fromLatin1(name);
  }
  in.Ui.tickOptionsWidget->setParameterNames(advanced);

  this->setUpDevices();
  pqVesselTouchPanelValues saved;
  if (pqSettings* settings = pqApplicationCore::instance()->settings())
  {
    saved.load(*settings);
  }
  in.toWidgets(saved, saved.activeGain_N(qVesselTouchForceLawParameters::defaultGain_N()));
  this->connectWidgets();

  QObject::connect(&pqActiveObjects::instance(),
    &pqActiveObjects::sourceChanged,
    this,
    &pqVesselTouchDockPanel::setActiveSource);
  QObject::connect(&pqActiveObjects::instance(),
    &pqActiveObjects::viewChanged,
    this,
    &pqVesselTouchDockPanel::activeViewChanged);
  QObject::connect(pqApplicationCore::instance(),
    &pqApplicationCore::stateLoaded,
    this,
    [this]() { QTimer::singleShot(0, this, &pqVesselTouchDockPanel::pullFromSession); });
  // Client/server faults (issue 19, item 6): a server without the plugin, a lost server.
  auto* serverCheck = new pqVesselTouchServerCheck(this);
  QObject::connect(serverCheck,
    &pqVesselTouchServerCheck::problemChanged,
    in.Centerlines,
    &pqVesselTouchCenterlineWorkflow::setServerProblem);
  in.Centerlines->setServerProblem(serverCheck->problem());
  QObject::connect(serverCheck,
    &pqVesselTouchServerCheck::connectionLost,
    this,
    &pqVesselTouchDockPanel::onConnectionLost);
  // The agent cone and the mouse in the render view follow this panel's session.
  new pqVesselTouchViewBinding(this);
  this->setActiveSource(pqActiveObjects::instance().activeSource());
  this->onSessionProxyChanged(in.Binding->proxy());

  // ParaView adds plugin docks hidden and restores its saved window state after start-up, so the
  // panel shows itself the first time a dataset becomes active (the user may close it afterwards
  // like any other panel).
  QTimer::singleShot(0, this, &pqVesselTouchDockPanel::revealOnce);
}

pqVesselTouchDockPanel::~pqVesselTouchDockPanel() = default;

void pqVesselTouchDockPanel::closeEvent(QCloseEvent* event)
{
  if (pqVesselTouchSessionStatus::read(this->Internals->Binding->proxy()).running)
  {
    this->stopSession();
  }
  QDockWidget::closeEvent(event);
}

void pqVesselTouchDockPanel::setUpDevices()
{
  QList<qVesselTouchDeviceEntry> devices{
    { "simulated", tr("Simulated handle"), "simulated" },
    { "pointer", tr("Mouse (pseudo-haptics)"), "pointer" },
    { "replay", tr("Replay a recording"), "replay" },
  };
  // Every joystick-like HID interface present now (force feedback devices present themselves as
  // joysticks, gamepads or multi-axis controllers, or with the PID usage page).
  vtouch::HidapiTransport hid;
  for (const vtouch::HidDeviceInfo& info : hid.enumerate())
  {
    const bool joystickLike =
      info.usagePage == 0x0F || info.usagePage == 0 ||
      (info.usagePage == 0x01 && (info.usage == 0x04 || info.usage == 0x05 || info.usage == 0x08));
    if (!joystickLike || info.path.empty())
    {
      continue;
    }
    const QString name = QString::fromStdString(info.manufacturer + " " + info.product).trimmed();
    devices.append({ QString("hid:%1").arg(QString::fromStdString(info.path)),
      tr("HID %1 (%2:%3)")
        .arg(name.isEmpty() ? QString::fromStdString(info.path) : name)
        .arg(info.vendorId, 4, 16, QChar('0'))
        .arg(info.productId, 4, 16, QChar('0')),
      "hid" });
  }
  // A HID device chosen in an earlier run stays listed under its path (it may be unplugged now:
  // Start then reports that it does not open).
  if (pqSettings* settings = pqApplicationCore::instance()->settings())
  {
    const QString saved = settings->value("VesselTouch/Device").toString();
    const bool listed = std::any_of(devices.begin(),
      devices.end(),
      [&saved](const qVesselTouchDeviceEntry& entry) { return entry.id == saved; });
    if (saved.startsWith(QLatin1String("hid:")) && !listed)
    {
      devices.append({ saved, tr("HID %1").arg(saved.mid(4)), "hid" });
    }
  }
  this->Internals->Ui.deviceWidget->setAvailableDevices(devices);
}

void pqVesselTouchDockPanel::connectWidgets()
{
  pqInternals& in = *this->Internals;
  QObject::connect(in.Ui.forceLawWidget,
    &qVesselTouchForceLawWidget::forceLawChanged,
    this,
    &pqVesselTouchDockPanel::onLawGainEdited);
  QObject::connect(in.Ui.forceLawWidget,
    &qVesselTouchForceLawWidget::parametersChanged,
    this,
    &pqVesselTouchDockPanel::onLawGainEdited);
  QObject::connect(in.Ui.zonesWidget,
    &qVesselTouchForceZonesWidget::gainChanged,
    this,
    &pqVesselTouchDockPanel::onZoneGainEdited);
  QObject::connect(in.Ui.zonesWidget,
    &qVesselTouchForceZonesWidget::thresholdsChanged,
    this,
    &pqVesselTouchDockPanel::onWidgetsEdited);
  QObject::connect(in.Ui.zoomWidget,
    &qVesselTouchHapticZoomWidget::ratioChanged,
    this,
    &pqVesselTouchDockPanel::onWidgetsEdited);
  QObject::connect(in.Ui.deviceWidget,
    &qVesselTouchDeviceWidget::deviceSelected,
    this,
    &pqVesselTouchDockPanel::onWidgetsEdited);
  QObject::connect(in.Ui.tickOptionsWidget,
    &qVesselTouchHapticParameterForm::parametersChanged,
    this,
    &pqVesselTouchDockPanel::onWidgetsEdited);
  // The Advanced rows that do not act on the chosen law are greyed out (the table says which).
  QObject::connect(in.Ui.forceLawWidget,
    &qVesselTouchForceLawWidget::forceLawChanged,
    in.Ui.tickOptionsWidget,
    &qVesselTouchHapticParameterForm::setForceLaw);

  QObject::connect(in.Binding,
    &pqVesselTouchSessionBinding::sessionProxyChanged,
    this,
    &pqVesselTouchDockPanel::onSessionProxyChanged);
  QObject::connect(in.Binding,
    &pqVesselTouchSessionBinding::propertiesModified,
    this,
    &pqVesselTouchDockPanel::pullFromSession);

  QObject::connect(
    in.Ui.startButton, &QPushButton::clicked, this, &pqVesselTouchDockPanel::startSession);
  QObject::connect(
    in.Ui.stopButton, &QPushButton::clicked, this, &pqVesselTouchDockPanel::stopSession);
  QObject::connect(in.Centerlines,
    &pqVesselTouchCenterlineWorkflow::centerlineReady,
    this,
    [this](pqPipelineSource* centerline, int paths)
    {
      this->Internals->Binding->setCenterline(centerline->getProxy(), 0);
      this->showError(QString());
      this->Internals->Ui.sessionStateLabel->setText(tr("Centerlines: %1 paths").arg(paths));
    });
}

// --- accessors ----------------------------------------------------------------------------
pqVesselTouchCenterlineWorkflow* pqVesselTouchDockPanel::centerlineWorkflow() const
{
  return this->Internals->Centerlines;
}
qVesselTouchForceLawWidget* pqVesselTouchDockPanel::forceLawWidget() const
{
  return this->Internals->Ui.forceLawWidget;
}
qVesselTouchHapticZoomWidget* pqVesselTouchDockPanel::zoomWidget() const
{
  return this->Internals->Ui.zoomWidget;
}
qVesselTouchForceZonesWidget* pqVesselTouchDockPanel::zonesWidget() const
{
  return this->Internals->Ui.zonesWidget;
}
qVesselTouchDeviceWidget* pqVesselTouchDockPanel::deviceWidget() const
{
  return this->Internals->Ui.deviceWidget;
}
qVesselTouchLoopStatsWidget* pqVesselTouchDockPanel::loopStatsWidget() const
{
  return this->Internals->Ui.loopStatsWidget;
}
pqVesselTouchSessionBinding* pqVesselTouchDockPanel::sessionBinding() const
{
  return this->Internals->Binding;
}
QString pqVesselTouchDockPanel::errorText() const
{
  return this->Internals->Ui.errorLabel->text();
}

// --- session ------------------------------------------------------------------------------
void pqVesselTouchDockPanel::onSessionProxyChanged(vtkSMProxy* session)
{
  pqInternals& in = *this->Internals;
  if (session)
  {
    // A fresh session (vesseltouch.logic(), or ours) takes the saved settings; one with values of
    // its own (a state file, Python) is shown as it is.
    if (pqVesselTouchPanelValues::proxyHasDefaults(session))
    {
      in.writeSession();
    }
    else
    {
      this->pullFromSession();
    }
    in.StatusTimer.start();
  }
  else
  {
    in.StatusTimer.stop();
  }
  this->updateSessionStatus();
  Q_EMIT this->sessionProxyChanged(session);
}

void pqVesselTouchDockPanel::pullFromSession()
{
  pqInternals& in = *this->Internals;
  vtkSMProxy* session = in.Binding->proxy();
  if (!session)
  {
    return;
  }
  pqVesselTouchPanelValues values = in.fromWidgets();
  const double zoneGain_N = values.readFromProxy(session);
  in.toWidgets(values, zoneGain_N);
  in.saveSettings();
}

void pqVesselTouchDockPanel::onWidgetsEdited()
{
  pqInternals& in = *this->Internals;
  if (in.Syncing)
  {
    return;
  }
  in.saveSettings();
  in.writeSession();
}

void pqVesselTouchDockPanel::onLawGainEdited()
{
  pqInternals& in = *this->Internals;
  if (!in.Syncing)
  {
    // The zones plot shows the current law's k.
    const QSignalBlocker blocker(in.Ui.zonesWidget);
    in.Ui.zonesWidget->setGain_N(in.fromWidgets().activeGain_N(in.Ui.zonesWidget->gain_N()));
  }
  this->onWidgetsEdited();
}

void pqVesselTouchDockPanel::onZoneGainEdited()
{
  pqInternals& in = *this->Internals;
  if (!in.Syncing)
  {
    pqVesselTouchPanelValues values = in.fromWidgets();
    values.setActiveGain_N(in.Ui.zonesWidget->gain_N());
    const QSignalBlocker blocker(in.Ui.forceLawWidget);
    in.Ui.forceLawWidget->setParameters(values.law);
  }
  this->onWidgetsEdited();
}

bool pqVesselTouchDockPanel::useDefaultCenterline()
{
  pqInternals& in = *this->Internals;
  vtkSMProxy* session = in.Binding->ensureSession();
  if (!session)
  {
    return false;
  }
  if (in.Binding->hasCenterline())
  {
    return true;
  }
  if (pqPipelineSource* centerline = in.Centerlines->centerline())
  {
    in.Binding->setCenterline(centerline->getProxy(), 0);
    return true;
  }
  pqPipelineSource* volume = in.Centerlines->currentVolume();
  if (volume && QLatin1String(volume->getProxy()->GetXMLName()) == QLatin1String("VesselPhantom"))
  {
    in.Binding->setCenterline(volume->getProxy(), 1); // the phantom's analytic centerline
    return true;
  }
  return false;
}

bool pqVesselTouchDockPanel::startSession()
{
  pqInternals& in = *this->Internals;
  if (!in.Binding->ensureSession())
  {
    this->showError(tr("Start: no server connection."));
    return false;
  }
  if (!this->useDefaultCenterline())
  {
    this->showError(tr("Start: extract the centerlines first (Pick seed, then Extract)."));
    return false;
  }
  in.writeSession();
  in.Binding->copyCamera(qobject_cast<pqRenderView*>(pqActiveObjects::instance().activeView()));
  const bool running = in.Binding->start();
  if (running)
  {
    this->showError(QString());
  }
  this->updateSessionStatus();
  return running;
}

void pqVesselTouchDockPanel::stopSession()
{
  this->Internals->Binding->stop();
  this->updateSessionStatus();
}

void pqVesselTouchDockPanel::updateSessionStatus()
{
  pqInternals& in = *this->Internals;
  vtkSMProxy* session = in.Binding->proxy();
  const pqVesselTouchSessionStatus status = pqVesselTouchSessionStatus::read(session);
  in.Ui.loopStatsWidget->setStats(status.loop);
  in.Ui.sessionStateLabel->setText(session ? status.summary() : tr("No session"));
  in.Ui.startButton->setEnabled(!status.running);
  in.Ui.stopButton->setEnabled(status.running);
  in.SessionError =
    status.faultCode != 0 ? tr("Fault: %1").arg(status.faultText) : status.lastError;
  this->showError(in.PanelError);
  in.Ui.deviceWidget->setStatusText(status.running ? tr("Open") : tr("Closed"));
  this->showDevice(status);
  if (status.running != in.Running)
  {
    in.Running = status.running;
    Q_EMIT this->runningChanged(status.running);
  }
}

void pqVesselTouchDockPanel::showDevice(const pqVesselTouchSessionStatus& status)
{
  pqInternals& in = *this->Internals;
  // A device fault names the device's trouble in the device section too (the red line says it
  // first); a lost pvserver is not the device's, and only the red line says it.
  in.Ui.deviceWidget->setFault(status.deviceFault() ? status.faultText : QString());
  if (!status.deviceOpen)
  {
    return; // keep showing the device last opened: its limits still bound the settings
  }
  // The calibration the open device applies, read-only; none for devices without raw axes.
  qVesselTouchDeviceWidget* device = in.Ui.deviceWidget;
  if (status.deviceHasCalibration != in.ShownHasCalibration ||
      status.deviceCalibration != in.ShownCalibration)
  {
    in.ShownHasCalibration = status.deviceHasCalibration;
    in.ShownCalibration = status.deviceCalibration;
    if (status.deviceHasCalibration)
    {
      device->setCalibration(status.deviceCalibration);
    }
    else
    {
      device->clearCalibration();
    }
  }
  const qVesselTouchDeviceCapabilities& caps = status.deviceCapabilities;
  if (in.ShownDeviceCapabilities == caps.toVariantMap())
  {
    return;
  }
  in.ShownDeviceCapabilities = caps.toVariantMap();
  device->setCapabilities(caps);
  // The proxy's coupler stiffness must stay renderable by this device (Ikits eq. 7: a stiffer
  // coupler than the device holds at its rate goes unstable); damping has no reported bound.
  in.Ui.forceLawWidget->setDeviceLimits(caps.maxStiffness_N_per_m, 0.0);
}

void pqVesselTouchDockPanel::onConnectionLost(const QString& server)
{
  pqInternals& in = *this->Internals;
  in.Binding->stop(); // zero force first: the rest may take a while
  const QString file =
    QDir(QDir::tempPath())
      .filePath(QStringLiteral("vesseltouch-skeleton-%1-%2.vtp")
                  .arg(QCoreApplication::applicationPid())
                  .arg(QDateTime::currentDateTime().toString(QStringLiteral("yyyyMMdd-hhmmss"))));
  const bool saved = in.Binding->saveSkeleton(file);
  const QString message =
    tr("The connection to the pvserver %1 was lost (the server died or the network went down): "
       "the force is zero and the haptic loop stopped. %2 ParaView closes after a lost server "
       "(it offers to save the state first); to go on, restart pvserver, File > Connect, load "
       "the plugin on the server and re-extract.")
      .arg(server,
        saved ? tr("The skeleton was saved to %1 (open it built in to trace it again).").arg(file)
              : tr("There was no skeleton to save."));
  in.Binding->reportConnectionLost(message);
  this->updateSessionStatus();
  in.Ui.errorLabel->repaint(); // ParaView's own reaction (a modal dialog, then _exit) follows
}

void pqVesselTouchDockPanel::showError(const QString& message)
{
  pqInternals& in = *this->Internals;
  in.PanelError = message;
  const QString shown = in.SessionError.isEmpty() ? in.PanelError : in.SessionError;
  in.Ui.errorLabel->setText(shown);
  in.Ui.errorLabel->setVisible(!shown.isEmpty());
}

// --- the active dataset and the GUI report --------------------------------------------------
void pqVesselTouchDockPanel::revealOnce()
{
  pqInternals& in = *this->Internals;
  if (in.Revealed)
  {
    return;
  }
  if (in.Source)
  {
    in.Revealed = true;
  }
  this->show();
  this->raise();
  // A module panel's width, not its widest label's: the render view keeps the room.
  if (auto* window = qobject_cast<QMainWindow*>(pqCoreUtilities::mainWidget()))
  {
    window->resizeDocks({ this }, { kPanelWidth_px }, Qt::Horizontal);
  }
}

void pqVesselTouchDockPanel::showEvent(QShowEvent* event)
{
  this->QDockWidget::showEvent(event);
}

void pqVesselTouchDockPanel::setActiveSource(pqPipelineSource* source)
{
  pqInternals& in = *this->Internals;
  if (in.Source)
  {
    QObject::disconnect(in.Source, nullptr, this, nullptr);
  }
  in.Source = source;
  if (source && !in.Revealed)
  {
    QTimer::singleShot(0, this, &pqVesselTouchDockPanel::revealOnce);
  }
  if (source)
  {
    QObject::connect(
      source, SIGNAL(dataUpdated(pqPipelineSource*)), this, SLOT(updateDatasetInformation()));
    QObject::connect(source,
      SIGNAL(nameChanged(pqServerManagerModelItem*)),
      this,
      SLOT(updateDatasetInformation()));
  }
  this->updateDatasetInformation();
}

void pqVesselTouchDockPanel::updateDatasetInformation()
{
  pqInternals& in = *this->Internals;
  qVesselTouchInfoWidget* info = in.Ui.infoWidget;
  if (!in.Source)
  {
    info->setDatasetName(QString());
    info->setDatasetSummary(QString());
    return;
  }
  info->setDatasetName(in.Source->getSMName());
  const QString summary = pqVesselTouchDatasetSummary::describe(in.Source);
  info->setDatasetSummary(summary);
}

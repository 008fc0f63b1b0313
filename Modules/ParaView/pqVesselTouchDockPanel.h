// The "VesselTouch" dock panel: the clinician's workflow on THE haptic session (the proxy
// registered as "VesselTouchSession", shared with vesseltouch.logic() in the Python console):
// choose the volume, pick a seed on the MIP, extract the centerlines, choose the device, start and
// stop, and tune force law, haptic zoom and force zones live. Layout:
// Resources/UI/pqVesselTouchDockPanel.ui. Widget values persist in the user's settings
// ("VesselTouch/..."); a loaded state file or Python edits re-sync the widgets from the proxy.
#ifndef pqVesselTouchDockPanel_h
#define pqVesselTouchDockPanel_h

#include <QDockWidget>
#include <QPointer>
#include <QScopedPointer>

class pqPipelineSource;
class pqView;
class pqVesselTouchCenterlineWorkflow;
class pqVesselTouchSessionBinding;
struct pqVesselTouchSessionStatus;
class qVesselTouchDeviceWidget;
class qVesselTouchForceLawWidget;
class qVesselTouchForceZonesWidget;
class qVesselTouchHapticZoomWidget;
class qVesselTouchLoopStatsWidget;
class vtkSMProxy;

namespace Ui
{
class pqVesselTouchDockPanel;
}

class pqVesselTouchDockPanel : public QDockWidget
{
  Q_OBJECT
public:
  explicit pqVesselTouchDockPanel(QWidget* parent = nullptr);
  ~pqVesselTouchDockPanel() override;

  /// The hosted widgets and the session binding (for the view binding and the GUI tests' driver).
  qVesselTouchForceLawWidget* forceLawWidget() const;
  qVesselTouchHapticZoomWidget* zoomWidget() const;
  qVesselTouchForceZonesWidget* zonesWidget() const;
  qVesselTouchDeviceWidget* deviceWidget() const;
  qVesselTouchLoopStatsWidget* loopStatsWidget() const;
  pqVesselTouchSessionBinding* sessionBinding() const;
  /// The text of the red error line ("" when none).
  QString errorText() const;
  /// Gives the session (created if needed) a centerline when it has none: the extracted one, else
  /// port 1 (the analytic centerline) of a chosen VesselPhantom. False when it has none after.
  bool useDefaultCenterline();
  /// The "Centerlines" box: volume, seed, extraction.
  pqVesselTouchCenterlineWorkflow* centerlineWorkflow() const;

  // === Integration point for the view interaction (pqVesselTouchAgentDisplay,
  // pqVesselTouchPointerInteraction): the lead connects these signals to them (or they follow
  // the session with a pqVesselTouchSessionBinding of their own). ===
Q_SIGNALS:
  /// The shared session proxy appeared, was replaced (state load) or went away (null).
  void sessionProxyChanged(vtkSMProxy* session);
  /// The session started (true) or stopped (false, also after a fault or a Stop from Python).
  void runningChanged(bool running);
  /// ParaView's active view changed (the agent display and pointer follow it).
  void activeViewChanged(pqView* view);

public Q_SLOTS:
  /// Start: gives the session a centerline if it has none, copies the active render view's camera,
  /// writes the panel's values, starts with the chosen device. False + red error on failure.
  bool startSession();
  /// Stop: the session zeroes the force, then closes the device.
  void stopSession();
  /// Reads the session's status (loop statistics, state, errors); the ~10 Hz timer calls it.
  void updateSessionStatus();

protected:
  void showEvent(QShowEvent* event) override;
  /// Closing the panel stops a running session (its force goes to zero first).
  void closeEvent(QCloseEvent* event) override;

private Q_SLOTS:
  void setActiveSource(pqPipelineSource* source);
  void updateDatasetInformation();
  /// Shows the panel; the first time a dataset is active, then never again on its own.
  void revealOnce();
  void onSessionProxyChanged(vtkSMProxy* session);
  /// A widget changed: save the settings and write the session's properties.
  void onWidgetsEdited();
  void onLawGainEdited();
  void onZoneGainEdited();
  /// The proxy changed elsewhere (Python, a state file): show its values.
  void pullFromSession();
  void showError(const QString& message);
  /// The pvserver `server` was lost (pqVesselTouchServerCheck): zero force, the skeleton saved,
  /// the fault said in the status line (issue 19, item 6).
  void onConnectionLost(const QString& server);

private:
  /// The open device's capabilities, calibration (read-only, HID devices) and fault in the device
  /// section, and its stiffness limit on the force-law widget.
  void showDevice(const pqVesselTouchSessionStatus& status);
  void connectWidgets();
  void setUpDevices();

  class pqInternals;
  QScopedPointer<pqInternals> Internals;
  Q_DISABLE_COPY(pqVesselTouchDockPanel)
};

#endif

// The panel's scripted self-test for GUI tests (Testing/ParaView/gui/gui_panel_session.py): when
// VESSELTOUCH_GUI_SELFTEST names a file, the panel runs it after start-up. It waits for the
// start-up scene (a VesselPhantom), drives the panel's widgets through their public API (force
// law, zoom, zones, device), reads the values back from the session proxy and its VTK object,
// deletes the session so that the panel must create it, picks a seed where the view shows a vessel
// of the phantom, extracts the centerlines there, starts the session with the simulated device,
// changes the zoom while it runs, stops, reads the device force back, changes the session proxy
// from outside the panel (as Python would), saves and loads a state file and reads the widgets
// back, and writes it all as JSON.
#ifndef pqVesselTouchPanelSelfTest_h
#define pqVesselTouchPanelSelfTest_h

#include <QJsonObject>
#include <QObject>
#include <QPoint>
#include <QPointer>
#include <QString>

class pqPipelineSource;
class pqVesselTouchDockPanel;

class pqVesselTouchPanelSelfTest : public QObject
{
  Q_OBJECT
public:
  /// `reportPath`: the JSON file written at the end (also on failure, with "error").
  pqVesselTouchPanelSelfTest(pqVesselTouchDockPanel* panel, const QString& reportPath);
  ~pqVesselTouchPanelSelfTest() override;

  /// Starts the steps on the event loop (returns at once).
  void start();

private Q_SLOTS:
  void waitForScene();
  void deleteSession();
  void setWidgets();
  void pickAndExtract();
  /// Extract runs in the background: waits for its end, then reports what it made.
  void reportExtraction();
  void startSession();
  void changeWhileRunning();
  void stopSession();
  void editFromOutside();
  void saveAndLoadState();
  void closePanelWhileRunning();
  void finish();

private:
  void fail(const QString& message);
  /// A point in the middle of the phantom's first analytic vessel (port 1), world mm, and where
  /// the active render view shows it, widget pixels (top-left origin).
  bool centerlinePixel(double point_mm[3], QPoint& pixel) const;
  QJsonObject sessionValues() const;
  QJsonObject status() const;

  QPointer<pqVesselTouchDockPanel> Panel;
  QPointer<pqPipelineSource> Phantom;
  QString ReportPath;
  QJsonObject Report;
  int Attempts = 0;
  Q_DISABLE_COPY(pqVesselTouchPanelSelfTest)
};

#endif

// The VesselTouchTestDriver plugin's start-up (a ParaView auto-start interface): once the
// VesselTouch panel and toolbar exist, does what the GUI test's environment asks for.
//   VESSELTOUCH_GUI_DRIVER=DIR      the command driver (pqVesselTouchTestDriver) polls DIR;
//   VESSELTOUCH_GUI_SELFTEST=FILE   the panel's scripted self-test runs, its report in FILE;
//   VESSELTOUCH_GUI_REPORT=FILE     what the panel shows, as JSON, rewritten 4 times a second;
//   VESSELTOUCH_AGENT_REPORT=FILE   the agent display's diagnostics, as JSON, every 30 drawn frames
//                                   (about twice a second), numbered ("sequence");
//   VESSELTOUCH_GUI_AGENT=1         the toolbar's Agent action is checked;
//   VESSELTOUCH_GUI_TRACE_MOUSE=1   the toolbar's Trace with mouse action is checked.
// None of this is in the VesselTouch plugin itself (issue 18, item 4).
#ifndef pqVesselTouchTestHooks_h
#define pqVesselTouchTestHooks_h

#include <QObject>
#include <QPointer>

class pqVesselTouchDockPanel;
class pqVesselTouchShowAgentAction;

class pqVesselTouchTestHooks : public QObject
{
  Q_OBJECT
public:
  explicit pqVesselTouchTestHooks(QObject* parent = nullptr);
  ~pqVesselTouchTestHooks() override;

  void startup();
  void shutdown() {}

private Q_SLOTS:
  /// Waits for the panel and the toolbar's Agent action, then installs the hooks.
  void attach();
  void writePanelReport();
  void onAgentFrameDrawn();

private:
  void install();

  QPointer<pqVesselTouchDockPanel> Panel;
  QPointer<pqVesselTouchShowAgentAction> AgentAction;
  int Attempts = 0;
  int FramesSinceAgentReport = 0;
  long long AgentReports = 0;
  Q_DISABLE_COPY(pqVesselTouchTestHooks)
};

#endif

// Drives the real ParaView GUI for the GUI tests (Testing/ParaView/gui/gui_driver.py), when
// VESSELTOUCH_GUI_DRIVER names a directory: the test writes numbered command files there
// ("cmd-<n>.txt", one line "verb arguments"), the driver runs each on the GUI thread as a user's
// action would run (a QAction triggered as its menu entry does, a button clicked, a spin box
// edited) and answers with "reply-<n>.json": {"ok", "error", "state"}. The state lists every
// named widget of the VesselTouch panel and toolbar (text, value, visibility, screen geometry for
// xdotool), the pipeline sources, the active view's screen geometry and the status of the session
// the panel is bound to, with every session registered as "VesselTouchSession" (global ids) and
// the ids of the panel's volume and centerlines.
//
// Verbs: state | trigger ACTION (queued: the reply comes before any dialog it opens; other commands
// wait until the action is over, except accept and dismiss, which answer its dialogs) | click
// BUTTON | check BUTTON|ACTION 0|1 | set WIDGET VALUE | select SOURCE ("" for none) | python SCRIPT
// (run in the GUI's Python) | capture PNG (the active render view's image) | render | savestate
// FILE and loadstate FILE (.pvsm or .py, through ParaView's File > Save/Load State reactions) |
// seed X Y Z (the seed picker reports a pick at world point X Y Z mm of the chosen volume, as a
// click whose ray's brightest voxel lies there does: for volumes whose brightest voxel under a
// click is not the vessel wanted).
#ifndef pqVesselTouchTestDriver_h
#define pqVesselTouchTestDriver_h

#include <QJsonObject>
#include <QObject>
#include <QPointer>
#include <QString>

#include <functional>

class QWidget;

class pqVesselTouchTestDriver : public QObject
{
  Q_OBJECT
public:
  /// Polls `directory` for command files; `panel` is the VesselTouch dock panel.
  pqVesselTouchTestDriver(QWidget* panel, const QString& directory);
  ~pqVesselTouchTestDriver() override;

  /// The state the replies carry.
  QJsonObject state() const;

private Q_SLOTS:
  void poll();

private:
  void pollOnce();
  /// Runs one command line; "" on success, else the error.
  QString run(const QString& line);
  /// Runs `action` from the event loop (the reply does not wait for its dialogs); until it
  /// returns, only "accept" and "dismiss" commands run.
  void runAsAction(const std::function<void()>& action);

  QPointer<QWidget> Panel;
  QString Directory;
  int Next = 1;
  bool Busy = false;
  bool InAction = false;
  Q_DISABLE_COPY(pqVesselTouchTestDriver)
};

#endif

// Lets one button (the panel's Cancel) be clicked while the client waits for a remote update
// (issue 19 item 1, issue 16 item 6). ParaView 5.11's client does not run Qt's event loop while
// vtkSMSourceProxy::UpdatePipeline waits for the pvserver: the session reads the socket until the
// reply comes, and the progress reports it meets on the way (at most one a second,
// vtkPVProgressHandler's server interval) only repaint the progress bar (pqProgressWidget::updateUI
// calls repaint(); pqProgressManager::setProgress's processEvents has been commented out since
// ParaView 3.12, "so we are sure we don't get tag mismatches"). A click is therefore queued until
// the update is over, on every widget, ParaView's own abort button too. Measured under Xvfb:
// Docs/CLIENT-SERVER.md "Cancel on a pvserver".
//
// processEvents(), called from a progress report of the server (inside the update), runs Qt's
// pending events once through a filter that keeps away what could talk to the server (project
// rule, a precaution: a message sent inside the update would break the session, and a render of
// the view in client/server mode talks to the server): no timer fires (its event is eaten;
// the timer fires again at its next interval, after the update), the window gets only mouse
// events, which it hands to the widget under the pointer, no key or mouse event reaches any widget
// but `clickable`, and no widget outside `panel` paints; then `panel` repaints synchronously (as
// pqProgressWidget repaints ParaView's progress bar). pqProgressManager's blocking is lifted
// meanwhile (unblockEvents): it judges the window, not the widget, so its non-blockable list lets
// no click through. Posted calls (queued signals) still run: they cannot be dropped without loss;
// the extraction runs those posted before the update first (QCoreApplication::sendPostedEvents).
#ifndef pqVesselTouchRemoteUpdateEvents_h
#define pqVesselTouchRemoteUpdateEvents_h

#include <QObject>
#include <QPointer>
#include <QWidget>

class pqVesselTouchRemoteUpdateEvents : public QObject
{
  Q_OBJECT
public:
  /// `panel`: the widgets that may repaint (the progress bar, the message); `clickable`: the
  /// one widget that receives clicks (Cancel), inside `panel`.
  pqVesselTouchRemoteUpdateEvents(QWidget* panel, QWidget* clickable, QObject* parent = nullptr);
  ~pqVesselTouchRemoteUpdateEvents() override;

  /// Runs the pending events once through the filter (never re-entered).
  void processEvents();

protected:
  bool eventFilter(QObject* receiver, QEvent* event) override;

private:
  static bool isInput(const QEvent* event);
  static bool isMouse(const QEvent* event);
  QPointer<QWidget> Panel;
  QPointer<QWidget> Clickable;
  bool Processing = false;
  Q_DISABLE_COPY(pqVesselTouchRemoteUpdateEvents)
};

#endif

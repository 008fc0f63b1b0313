#include "pqVesselTouchRemoteUpdateEvents.h"

#include "pqApplicationCore.h"
#include "pqProgressManager.h"

#include <QCoreApplication>
#include <QEvent>
#include <QEventLoop>
#include <QWindow>

pqVesselTouchRemoteUpdateEvents::pqVesselTouchRemoteUpdateEvents(QWidget* panel,
  QWidget* clickable,
  QObject* parentObject)
  : QObject(parentObject)
  , Panel(panel)
  , Clickable(clickable)
{
}

pqVesselTouchRemoteUpdateEvents::~pqVesselTouchRemoteUpdateEvents() = default;

void pqVesselTouchRemoteUpdateEvents::processEvents()
{
  if (this->Processing || !this->Panel)
  {
    return;
  }
  this->Processing = true;
  // pqProgressManager's own filter eats every key and mouse event whose receiver is not in its
  // non-blockable list, and in Qt 5 that receiver is first the window (QWidgetWindow), which
  // hands the event to the widget only if it passes: so its list alone lets no click through.
  // This filter does the blocking meanwhile.
  pqProgressManager* progress = pqApplicationCore::instance()->getProgressManager();
  const bool blocked = progress ? progress->unblockEvents(true) : false;
  QCoreApplication::instance()->installEventFilter(this);
  QCoreApplication::processEvents(QEventLoop::ExcludeSocketNotifiers);
  // The window's update requests are eaten: the panel paints now, synchronously (as
  // pqProgressWidget paints ParaView's progress bar during an update).
  this->Panel->repaint();
  QCoreApplication::instance()->removeEventFilter(this);
  if (progress)
  {
    progress->unblockEvents(blocked);
  }
  this->Processing = false;
}

bool pqVesselTouchRemoteUpdateEvents::isInput(const QEvent* event)
{
  switch (event->type())
  {
    case QEvent::MouseButtonPress:
    case QEvent::MouseButtonRelease:
    case QEvent::MouseButtonDblClick:
    case QEvent::MouseMove:
    case QEvent::KeyPress:
    case QEvent::KeyRelease:
    case QEvent::ShortcutOverride:
    case QEvent::Shortcut:
    case QEvent::Wheel:
    case QEvent::ContextMenu:
    case QEvent::TouchBegin:
    case QEvent::TouchUpdate:
    case QEvent::TouchEnd:
    case QEvent::TabletPress:
    case QEvent::TabletRelease:
    case QEvent::TabletMove:
    case QEvent::Drop:
      return true;
    default:
      return false;
  }
}

bool pqVesselTouchRemoteUpdateEvents::isMouse(const QEvent* event)
{
  return event->type() == QEvent::MouseButtonPress || event->type() == QEvent::MouseButtonRelease ||
         event->type() == QEvent::MouseButtonDblClick || event->type() == QEvent::MouseMove;
}

bool pqVesselTouchRemoteUpdateEvents::eventFilter(QObject* receiver, QEvent* event)
{
  if (event->type() == QEvent::Timer)
  {
    return true; // the timer fires again at its next interval
  }
  if (qobject_cast<QWindow*>(receiver))
  {
    // The window hands the mouse to the widget under the pointer (judged there); nothing else:
    // no expose or update request, which would paint the render view, and no key.
    return !isMouse(event);
  }
  auto* widget = qobject_cast<QWidget*>(receiver);
  if (!widget)
  {
    return false; // posted calls (MetaCall) and the like: they cannot be dropped without loss
  }
  if (isInput(event))
  {
    return widget != this->Clickable;
  }
  const bool inPanel = widget == this->Panel || this->Panel->isAncestorOf(widget);
  switch (event->type())
  {
    case QEvent::Paint:
    case QEvent::UpdateRequest:
    case QEvent::UpdateLater:
      return !inPanel;
    default:
      return false;
  }
}

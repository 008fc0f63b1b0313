#include "pqVesselTouchPointerInteraction.h"

#include "pqRenderView.h"

#include "vtkSMPropertyHelper.h"
#include "vtkSMProxy.h"
#include "vtkVesselTouchHapticSession.h"
#include "vtkWeakPointer.h"

#include "vtouchViewPointerMapping.h"

#include <QCoreApplication>
#include <QEvent>
#include <QMouseEvent>
#include <QWidget>
#include <QtDebug>

namespace
{
/// Held with a left drag while tracing: rotates the camera instead (issue 20 item 5).
constexpr Qt::KeyboardModifier kRotateModifier = Qt::ControlModifier;
} // namespace

class pqVesselTouchPointerInteraction::pqInternals
{
public:
  vtkWeakPointer<vtkSMProxy> Session;
  vtouch::ViewPointerMapping Mapping;
  bool Pressed = false;

  vtkVesselTouchHapticSession* sessionObject() const
  {
    return this->Session
             ? vtkVesselTouchHapticSession::SafeDownCast(this->Session->GetClientSideObject())
             : nullptr;
  }
};

pqVesselTouchPointerInteraction::pqVesselTouchPointerInteraction(QObject* parentObject)
  : QObject(parentObject)
  , Internals(new pqInternals())
{
}

pqVesselTouchPointerInteraction::~pqVesselTouchPointerInteraction()
{
  this->unwatchWidgets();
  if (this->Enabled && this->ControlsSession)
  {
    this->stopSession();
  }
}

void pqVesselTouchPointerInteraction::setView(pqRenderView* view)
{
  if (view == this->View)
  {
    return;
  }
  this->releaseForces();
  this->unwatchWidgets();
  if (this->Widget)
  {
    QObject::disconnect(this->Widget.data(), nullptr, this, nullptr);
  }
  this->View = view;
  this->Widget = view ? view->widget() : nullptr;
  if (this->Widget)
  {
    this->watchWidgets();
    QObject::connect(this->Widget.data(),
      &QObject::destroyed,
      this,
      &pqVesselTouchPointerInteraction::onWidgetDestroyed);
  }
}

void pqVesselTouchPointerInteraction::watchWidgets()
{
  QList<QWidget*> widgets = this->Widget->findChildren<QWidget*>();
  widgets.prepend(this->Widget);
  for (QWidget* widget : widgets)
  {
    widget->installEventFilter(this);
    widget->setMouseTracking(true); // moves without a button pressed
    this->Watched.append(widget);
  }
}

void pqVesselTouchPointerInteraction::unwatchWidgets()
{
  for (const QPointer<QWidget>& widget : this->Watched)
  {
    if (widget)
    {
      widget->removeEventFilter(this);
    }
  }
  this->Watched.clear();
}

void pqVesselTouchPointerInteraction::setActiveView(pqView* view)
{
  this->setView(qobject_cast<pqRenderView*>(view));
}

void pqVesselTouchPointerInteraction::setSession(vtkSMProxy* session)
{
  if (session && !vtkVesselTouchHapticSession::SafeDownCast(session->GetClientSideObject()))
  {
    qWarning() << "VesselTouch: tracing with the mouse needs a VesselTouchHapticSession proxy in a "
                  "builtin session";
    session = nullptr;
  }
  if (session != this->Internals->Session)
  {
    this->releaseForces();
    this->Internals->Session = session;
    if (session && this->Enabled && this->ControlsSession)
    {
      this->ensurePointerSessionRunning(); // enabled before the session existed
    }
  }
}

void pqVesselTouchPointerInteraction::setEnabled(bool enabled)
{
  if (enabled == this->Enabled)
  {
    return;
  }
  this->Enabled = enabled;
  if (!this->ControlsSession)
  {
    this->releaseForces();
  }
  else if (enabled)
  {
    this->ensurePointerSessionRunning();
  }
  else
  {
    // The session keeps running (Stop is the panel's): the mouse only stops feeding it, and the
    // camera is the mouse's again.
    this->releaseForces();
  }
  this->Rotating = false;
  Q_EMIT this->enabledChanged(enabled);
}

bool pqVesselTouchPointerInteraction::isActive(Qt::KeyboardModifiers modifiers) const
{
  return this->Enabled ||
         (this->Modifiers != Qt::NoModifier && (modifiers & this->Modifiers) == this->Modifiers);
}

bool pqVesselTouchPointerInteraction::ensurePointerSessionRunning()
{
  vtkVesselTouchHapticSession* object = this->Internals->sessionObject();
  if (!object)
  {
    return false;
  }
  if (object->IsRunning() && object->GetDeviceType() == vtkVesselTouchHapticSession::POINTER)
  {
    return true;
  }
  vtkSMProxy* session = this->Internals->Session;
  if (object->IsRunning())
  {
    session->InvokeCommand("Stop");
  }
  vtkSMPropertyHelper(session, "DeviceType").Set(vtkVesselTouchHapticSession::POINTER);
  session->UpdateVTKObjects();
  session->InvokeCommand("Start");
  if (!object->IsRunning())
  {
    qWarning() << "VesselTouch: the pointer session did not start:"
               << object->GetLastErrorMessage();
    return false;
  }
  return true;
}

void pqVesselTouchPointerInteraction::movePointer(QWidget* widget, double x, double y)
{
  vtkVesselTouchHapticSession* object = this->Internals->sessionObject();
  if (!object)
  {
    return;
  }
  vtouch::ViewPointerMapping& mapping = this->Internals->Mapping;
  mapping.setWidgetSize(widget->width(), widget->height(), widget->devicePixelRatioF());
  mapping.setPixelsPerDeviceMm(object->GetHapticParameter("PixelsPerDeviceMm"));
  const vtouch::Vec2 device_mm = mapping.widgetToDevice_mm({ x, y });
  object->SetPointerPosition(device_mm.x, device_mm.y);
  if (!this->Internals->Pressed)
  {
    object->SetPointerPressed(true);
    this->Internals->Pressed = true;
  }
  ++this->PointerEvents;
}

void pqVesselTouchPointerInteraction::releaseForces()
{
  vtkVesselTouchHapticSession* object = this->Internals->sessionObject();
  if (object)
  {
    // Pressure 0: the force zones' gain is zero (no force) and the cursor holds still.
    object->SetPointerPressed(false);
    object->SetPointerButtons(0);
  }
  this->Internals->Pressed = false;
}

void pqVesselTouchPointerInteraction::stopSession()
{
  this->releaseForces();
  vtkVesselTouchHapticSession* object = this->Internals->sessionObject();
  if (object && object->IsRunning() &&
      object->GetDeviceType() == vtkVesselTouchHapticSession::POINTER)
  {
    this->Internals->Session->InvokeCommand("Stop");
  }
}

bool pqVesselTouchPointerInteraction::rotateCamera(QWidget* widget, QMouseEvent* mouse)
{
  // Ctrl + left drag while tracing rotates the camera: ParaView gets the drag as a plain left
  // drag (its rotation; Ctrl + left would be its zoom), the session keeps running, the cursor
  // holds where it was, and the agent display's camera push re-projects the agent and its force.
  const bool press =
    mouse->type() == QEvent::MouseButtonPress || mouse->type() == QEvent::MouseButtonDblClick;
  if (!this->Rotating)
  {
    if (!press || mouse->button() != Qt::LeftButton || !(mouse->modifiers() & kRotateModifier) ||
        !this->isActive(Qt::NoModifier))
    {
      return false;
    }
    this->Rotating = true;
  }
  const bool release =
    mouse->type() == QEvent::MouseButtonRelease && mouse->button() == Qt::LeftButton;
  QMouseEvent plain(
    mouse->type() == QEvent::MouseButtonDblClick ? QEvent::MouseButtonPress : mouse->type(),
    mouse->localPos(),
    mouse->windowPos(),
    mouse->screenPos(),
    mouse->button(),
    mouse->buttons(),
    mouse->modifiers() & ~kRotateModifier);
  this->Forwarding = true;
  QCoreApplication::sendEvent(widget, &plain);
  this->Forwarding = false;
  if (release)
  {
    this->Rotating = false;
  }
  ++this->CameraDragEvents;
  return true;
}

void pqVesselTouchPointerInteraction::onWidgetDestroyed()
{
  this->Watched.clear();
  this->Widget = nullptr;
  this->View = nullptr;
  if (this->Enabled && this->ControlsSession)
  {
    this->stopSession();
  }
  else
  {
    this->releaseForces();
  }
}

bool pqVesselTouchPointerInteraction::eventFilter(QObject* watched, QEvent* event)
{
  auto* widget = qobject_cast<QWidget*>(watched);
  if (!widget || !this->Widget || (widget != this->Widget && !this->Widget->isAncestorOf(widget)))
  {
    return this->QObject::eventFilter(watched, event);
  }
  if (this->Forwarding)
  {
    return this->QObject::eventFilter(watched, event); // our own rotation event, for ParaView
  }
  switch (event->type())
  {
    case QEvent::MouseMove:
    case QEvent::MouseButtonPress:
    case QEvent::MouseButtonRelease:
    case QEvent::MouseButtonDblClick:
    {
      auto* mouse = static_cast<QMouseEvent*>(event);
      if (this->rotateCamera(widget, mouse))
      {
        return true;
      }
      if (!this->isActive(mouse->modifiers()))
      {
        if (this->Internals->Pressed)
        {
          this->releaseForces(); // the modifier was let go
        }
        break;
      }
      if (mouse->buttons() & (Qt::MiddleButton | Qt::RightButton))
      {
        this->releaseForces(); // a camera pan or zoom in progress
        break;
      }
      this->movePointer(widget, mouse->localPos().x(), mouse->localPos().y());
      if (event->type() == QEvent::MouseMove)
      {
        return true; // no camera rotation while tracing
      }
      if (mouse->button() != Qt::LeftButton)
      {
        break; // middle/right buttons still pan and zoom the camera
      }
      vtkVesselTouchHapticSession* object = this->Internals->sessionObject();
      if (object)
      {
        object->SetPointerButtons(event->type() == QEvent::MouseButtonRelease ? 0 : 1);
      }
      return true;
    }
    case QEvent::Leave:
    case QEvent::FocusOut:
    case QEvent::Hide:
      this->releaseForces();
      break;
    default:
      break;
  }
  return this->QObject::eventFilter(watched, event);
}

// The mouse as the haptic session's POINTER device: while enabled (the toolbar's "Trace with
// mouse"), or while the activation modifiers are held, mouse moves over the render view feed
// vtkVesselTouchHapticSession::SetPointerPosition (device mm, vtouch::ViewPointerMapping: centred
// on the viewport, 1 mm = PixelsPerDeviceMm px, y up) with the pointer "pressed" (pressure 1: the
// cursor follows the hand and the force zones are at full gain), and a left click presses button
// 0 (SetPointerButtons: returns from tracing to exploring). Those events do not reach ParaView's
// camera interaction; every other event (and the wheel: zoom) still does.
//
// Ctrl + left drag rotates the camera while tracing (ParaView gets a plain left drag): the session
// keeps running, the cursor holds, and the agent is re-projected with the new camera.
//
// Forces stop (pressure 0: zero force-zone gain, the cursor holds) when the pointer leaves the
// view or the view loses focus or is hidden, or when tracing is disabled (the session keeps
// running: Stop is the panel's); the session is stopped when the view is destroyed.
//
// setEnabled(true) switches the session to the POINTER device and starts it when it is not
// running one already.
#ifndef pqVesselTouchPointerInteraction_h
#define pqVesselTouchPointerInteraction_h

#include <QList>
#include <QObject>
#include <QPointer>

#include <memory>

class pqRenderView;
class pqView;
class vtkSMProxy;
class QMouseEvent;
class QWidget;

class pqVesselTouchPointerInteraction : public QObject
{
  Q_OBJECT
public:
  explicit pqVesselTouchPointerInteraction(QObject* parent = nullptr);
  ~pqVesselTouchPointerInteraction() override;

  bool isEnabled() const { return this->Enabled; }
  /// When on (the default, the toolbar's toggle), setEnabled(true) switches the session to the
  /// POINTER device and starts it, and setEnabled(false) stops it. When off (a panel that starts
  /// and stops the session itself), enabling only forwards the mouse to a running pointer session.
  void setControlsSession(bool controls) { this->ControlsSession = controls; }
  /// Keyboard modifiers that trace with the mouse while held, even when not enabled; none
  /// (Qt::NoModifier, the default) disables this.
  void setActivationModifiers(Qt::KeyboardModifiers modifiers) { this->Modifiers = modifiers; }

  /// Pointer events sent to the session (for tests).
  long long pointerEvents() const { return this->PointerEvents; }
  /// Mouse events of Ctrl + left drags handed to the camera (for tests).
  long long cameraDragEvents() const { return this->CameraDragEvents; }

public Q_SLOTS:
  /// The render view whose widget is watched (null: none).
  void setView(pqRenderView* view);
  /// setView() with any view (not a render view: none), for pqActiveObjects::viewChanged.
  void setActiveView(pqView* view);
  /// The VesselTouchHapticSession proxy (builtin session; null: none).
  void setSession(vtkSMProxy* session);
  void setEnabled(bool enabled);

Q_SIGNALS:
  void enabledChanged(bool enabled);

protected:
  bool eventFilter(QObject* watched, QEvent* event) override;

private:
  class pqInternals;
  bool isActive(Qt::KeyboardModifiers modifiers) const;
  /// A Ctrl + left drag while tracing: forwarded to ParaView as a plain left drag. True when
  /// `mouse` belongs to one (consumed).
  bool rotateCamera(QWidget* widget, QMouseEvent* mouse);
  bool ensurePointerSessionRunning();
  void movePointer(QWidget* widget, double x, double y);
  void releaseForces();
  void stopSession();
  void onWidgetDestroyed();

  void watchWidgets();
  void unwatchWidgets();

  std::unique_ptr<pqInternals> Internals;
  QPointer<pqRenderView> View;
  /// The view's pqQVTKWidget (its destruction stops the forces).
  QPointer<QWidget> Widget;
  /// It and the widgets inside it: the render widget gets the mouse first (VTK's interactor
  /// handles it there), so the filter sits on it too.
  QList<QPointer<QWidget>> Watched;
  bool Enabled = false;
  bool ControlsSession = true;
  Qt::KeyboardModifiers Modifiers = Qt::NoModifier;
  long long PointerEvents = 0;
  long long CameraDragEvents = 0;
  bool Rotating = false;
  bool Forwarding = false;
  Q_DISABLE_COPY(pqVesselTouchPointerInteraction)
};

#endif

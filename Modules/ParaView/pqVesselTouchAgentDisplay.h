// Draws the haptic session's tracing agent in a ParaView render view, at the GUI rate, without
// re-rendering the volume when only the agent moves (pqVesselTouchAgentOverlay), and keeps the
// session's camera equal to the view's (so the haptic thread's scene model follows every camera
// change within one frame).
//
// Every tick (default 60 Hz) while enabled: the view's camera and viewport size are compared with
// what the session last got, and pushed through the session proxy's camera properties when they
// changed (like vesseltouch.HapticSession.SetCameraFromView); the published agent state is read
// (vtkVesselTouchHapticSession::GetAgentState, builtin session) and the agent is drawn: a cone
// (red apex and sides, blue base) along the tangent toward the direction of travel, rolled by the
// torsion angle, in the tracing state; a yellow cursor marker at the device cursor in the
// exploring state; a green force arrow (screen space, 40 px per newton) for pseudo-haptics.
// When the scene changed, a normal (full) ParaView render is requested instead, which captures.
//
// Usage (the dock panel):
//   auto* display = new pqVesselTouchAgentDisplay(this);
//   display->setView(pqActiveObjects::instance().activeView());   // any pqRenderView
//   display->setSession(sessionSource->getProxy());               // VesselTouchHapticSession
//   display->setEnabled(true);
#ifndef pqVesselTouchAgentDisplay_h
#define pqVesselTouchAgentDisplay_h

#include <QJsonObject>
#include <QObject>
#include <QPointer>

#include <memory>

class pqRenderView;
class pqView;
class vtkSMProxy;
class QTimer;

class pqVesselTouchAgentDisplay : public QObject
{
  Q_OBJECT
public:
  explicit pqVesselTouchAgentDisplay(QObject* parent = nullptr);
  ~pqVesselTouchAgentDisplay() override;

  pqRenderView* view() const;
  vtkSMProxy* session() const;
  bool isEnabled() const { return this->Enabled; }
  /// Tick rate, Hz, [1, 240]. Default 60.
  void setRate(double rate_Hz);
  /// Agent cone height on screen, px. Default 36.
  void setAgentHeight(double height_px) { this->AgentHeight_px = height_px; }
  /// Force arrow length per newton, px. Default 40 (at most 160 px).
  void setArrowScale(double pixelsPerNewton) { this->ArrowPixelsPerNewton = pixelsPerNewton; }

  /// Frames in which ParaView drew the scene (the volume) and the overlay captured it.
  long long fullRenders() const;
  /// Agent-only frames drawn over the cached image.
  long long cachedFrames() const;
  /// Mean wall time of an agent-only frame, ms; the volume's render time in the last full
  /// frame, ms.
  double meanCachedFrame_ms() const;
  double lastFullSceneRender_ms() const;
  /// Camera pushes to the session.
  long long cameraPushes() const { return this->CameraPushes; }
  /// Did the last tick draw an agent-only frame?
  bool lastFrameCached() const { return this->LastFrameCached; }
  /// Where the agent (tracing) or the cursor (exploring) was last drawn, display px, bottom-left
  /// origin; the state drawn (-1 hidden, 0 exploring, 1 tracing).
  double lastAgentX() const { return this->LastAgent_px[0]; }
  double lastAgentY() const { return this->LastAgent_px[1]; }
  int lastAgentState() const { return this->LastState; }
  /// What the display is doing, for diagnostics and the GUI tests: enabled, session, frame
  /// counts and times, camera pushes, the agent's state and pixel position, the session's tick,
  /// cursor, device type and view-model builds, the render window's size and the view's place
  /// on the screen (logical px).
  QJsonObject diagnostics() const;

public Q_SLOTS:
  /// The render view to draw in (null: none). The overlay layer moves with it.
  void setView(pqRenderView* view);
  /// setView() with any view (not a render view: none), for pqActiveObjects::viewChanged.
  void setActiveView(pqView* view);
  /// The VesselTouchHapticSession proxy (null: none). Builtin sessions only: the agent state is
  /// read from proxy->GetClientSideObject().
  void setSession(vtkSMProxy* session);
  void setEnabled(bool enabled);
  /// One frame now (the timer calls it).
  void tick();
  /// Forces the next frame to re-render the scene.
  void invalidate();

Q_SIGNALS:
  void enabledChanged(bool enabled);
  /// A tick drew its frame (the view is attached and the display enabled).
  void frameDrawn();

private:
  class pqInternals;
  void attachOverlay();
  void pushCameraIfChanged();
  void updateAgent();
  /// Places the cone from agent state `a`; its display position into `anchor_px`.
  bool placeCone(const double* a, double anchor_px[2]);
  void drawFrame();

  std::unique_ptr<pqInternals> Internals;
  QPointer<pqRenderView> View;
  QTimer* Timer = nullptr;
  bool Enabled = false;
  double AgentHeight_px = 36.0;
  double ArrowPixelsPerNewton = 40.0;
  long long CameraPushes = 0;
  bool LastFrameCached = false;
  double LastAgent_px[2] = { -1.0, -1.0 };
  int LastState = -1;
  Q_DISABLE_COPY(pqVesselTouchAgentDisplay)
};

#endif

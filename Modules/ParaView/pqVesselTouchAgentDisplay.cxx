#include "pqVesselTouchAgentDisplay.h"

#include "pqVesselTouchAgentActors.h"
#include "pqVesselTouchAgentOverlay.h"

#include "pqRenderView.h"

#include "vtkCamera.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSMPropertyHelper.h"
#include "vtkSMProxy.h"
#include "vtkSMRenderViewProxy.h"
#include "vtkVesselTouchHapticSession.h"
#include "vtkWeakPointer.h"

#include "vtouchAgentPose.h"
#include "vtouchAgentStateLayout.h"

#include <QElapsedTimer>
#include <QFile>
#include <QGuiApplication>
#include <QJsonObject>
#include <QTimer>
#include <QWidget>
#include <QtDebug>

#include <algorithm>
#include <array>
#include <cmath>

namespace
{
/// A full render requested but not captured yet is asked for again after this long, ms.
constexpr qint64 kRenderRetry_ms = 1000;
/// Longest force arrow, px.
constexpr double kMaxArrow_px = 160.0;

// Short names for the fields of vtkVesselTouchHapticSession::GetAgentState() used here; the
// layout itself is vtouchAgentStateLayout.h's.
enum AgentField
{
  Tick = vtouch::AgentFieldTick,
  State = vtouch::AgentFieldState,
  CursorX = vtouch::AgentFieldCursor_px,
  PositionX = vtouch::AgentFieldPosition_World_mm,
  TangentX = vtouch::AgentFieldTangent_World,
  Direction = vtouch::AgentFieldDirection,
  Torsion = vtouch::AgentFieldConeRoll_rad,
  ForceX = vtouch::AgentFieldForce_N
};
} // namespace

class pqVesselTouchAgentDisplay::pqInternals
{
public:
  pqInternals()
    : Overlay(Actors)
  {
  }
  pqVesselTouchAgentActors Actors;
  pqVesselTouchAgentOverlay Overlay;
  vtkWeakPointer<vtkSMProxy> Session;
  std::array<double, 12> PushedCamera{};
  bool HasPushedCamera = false;
  int LastDirection = 1;
  std::array<double, 24> DrawnSignature{};
  bool AgentChanged = true;
  bool RenderRequested = false;
  QElapsedTimer SinceRequest;
  long long CapturesAtRequest = 0;

  vtkVesselTouchHapticSession* sessionObject() const
  {
    return this->Session
             ? vtkVesselTouchHapticSession::SafeDownCast(this->Session->GetClientSideObject())
             : nullptr;
  }
};

pqVesselTouchAgentDisplay::pqVesselTouchAgentDisplay(QObject* parentObject)
  : QObject(parentObject)
  , Internals(new pqInternals())
{
  this->Timer = new QTimer(this);
  this->Timer->setTimerType(Qt::PreciseTimer);
  this->Timer->setInterval(16);
  QObject::connect(this->Timer, &QTimer::timeout, this, &pqVesselTouchAgentDisplay::tick);
}

pqVesselTouchAgentDisplay::~pqVesselTouchAgentDisplay()
{
  this->Internals->Overlay.detach();
}

void pqVesselTouchAgentDisplay::setView(pqRenderView* view)
{
  if (view == this->View)
  {
    return;
  }
  this->Internals->Overlay.detach();
  if (this->View)
  {
    this->View->render(); // give the old view back without the agent
  }
  this->View = view;
  this->Internals->HasPushedCamera = false;
  if (this->Enabled)
  {
    this->attachOverlay();
  }
}

void pqVesselTouchAgentDisplay::setActiveView(pqView* view)
{
  this->setView(qobject_cast<pqRenderView*>(view));
}

pqRenderView* pqVesselTouchAgentDisplay::view() const
{
  return this->View;
}

void pqVesselTouchAgentDisplay::setSession(vtkSMProxy* session)
{
  if (session && !vtkVesselTouchHapticSession::SafeDownCast(session->GetClientSideObject()))
  {
    qWarning() << "VesselTouch: the agent display needs a VesselTouchHapticSession proxy in a "
                  "builtin session";
    session = nullptr;
  }
  this->Internals->Session = session;
  this->Internals->HasPushedCamera = false;
  this->Internals->AgentChanged = true;
}

vtkSMProxy* pqVesselTouchAgentDisplay::session() const
{
  return this->Internals->Session;
}

void pqVesselTouchAgentDisplay::setRate(double rate_Hz)
{
  const double rate = std::clamp(std::isfinite(rate_Hz) ? rate_Hz : 60.0, 1.0, 240.0);
  this->Timer->setInterval(static_cast<int>(std::lround(1000.0 / rate)));
}

long long pqVesselTouchAgentDisplay::fullRenders() const
{
  return this->Internals->Overlay.captures();
}

long long pqVesselTouchAgentDisplay::cachedFrames() const
{
  return this->Internals->Overlay.cachedFrames();
}

double pqVesselTouchAgentDisplay::meanCachedFrame_ms() const
{
  return this->Internals->Overlay.meanCachedFrame_ms();
}

double pqVesselTouchAgentDisplay::lastFullSceneRender_ms() const
{
  return this->Internals->Overlay.lastSceneRender_ms();
}

void pqVesselTouchAgentDisplay::setEnabled(bool enabled)
{
  if (enabled == this->Enabled)
  {
    return;
  }
  this->Enabled = enabled;
  if (enabled)
  {
    this->Internals->HasPushedCamera = false;
    this->Internals->AgentChanged = true;
    this->attachOverlay();
    this->Timer->start();
  }
  else
  {
    this->Timer->stop();
    this->Internals->Overlay.detach();
    if (this->View)
    {
      this->View->render();
    }
  }
  Q_EMIT this->enabledChanged(enabled);
}

void pqVesselTouchAgentDisplay::invalidate()
{
  this->Internals->Overlay.invalidate();
}

void pqVesselTouchAgentDisplay::attachOverlay()
{
  this->Internals->Overlay.detach();
  vtkSMRenderViewProxy* proxy = this->View ? this->View->getRenderViewProxy() : nullptr;
  if (!proxy || !proxy->GetRenderWindow() || !proxy->GetRenderer())
  {
    return;
  }
  this->Internals->Overlay.attach(proxy->GetRenderWindow(), proxy->GetRenderer());
  this->Internals->RenderRequested = false;
}

void pqVesselTouchAgentDisplay::tick()
{
  if (!this->Enabled || !this->View)
  {
    return;
  }
  if (!this->Internals->Overlay.isAttached())
  {
    this->attachOverlay();
    if (!this->Internals->Overlay.isAttached())
    {
      return;
    }
  }
  this->pushCameraIfChanged();
  this->updateAgent();
  this->drawFrame();
  Q_EMIT this->frameDrawn();
}

void pqVesselTouchAgentDisplay::pushCameraIfChanged()
{
  pqInternals& in = *this->Internals;
  if (!in.Session)
  {
    return;
  }
  vtkRenderer* scene = this->View->getRenderViewProxy()->GetRenderer();
  vtkCamera* camera = scene->GetActiveCamera();
  const int* size = scene->GetSize();
  if (size[0] <= 0 || size[1] <= 0)
  {
    return;
  }
  const double* p = camera->GetPosition();
  const double* f = camera->GetFocalPoint();
  const double* u = camera->GetViewUp();
  const std::array<double, 12> now{ { p[0],
    p[1],
    p[2],
    f[0],
    f[1],
    f[2],
    u[0],
    u[1],
    u[2],
    camera->GetParallelProjection() ? camera->GetParallelScale() : -camera->GetViewAngle(),
    static_cast<double>(size[0]),
    static_cast<double>(size[1]) } };
  if (in.HasPushedCamera && now == in.PushedCamera)
  {
    return;
  }
  // As vesseltouch.HapticSession.SetCameraFromView: through the proxy, so that Python sees it.
  vtkSMProxy* session = in.Session;
  vtkSMPropertyHelper(session, "CameraPosition").Set(p, 3);
  vtkSMPropertyHelper(session, "CameraFocalPoint").Set(f, 3);
  vtkSMPropertyHelper(session, "CameraViewUp").Set(u, 3);
  vtkSMPropertyHelper(session, "CameraParallelProjection").Set(camera->GetParallelProjection());
  vtkSMPropertyHelper(session, "CameraParallelScale").Set(camera->GetParallelScale());
  vtkSMPropertyHelper(session, "CameraViewAngle").Set(camera->GetViewAngle());
  vtkSMPropertyHelper(session, "ViewportSize").Set(size, 2);
  vtkSMPropertyHelper(session, "UseExplicitMatrices").Set(0);
  session->UpdateVTKObjects();
  in.PushedCamera = now;
  in.HasPushedCamera = true;
  ++this->CameraPushes;
}

void pqVesselTouchAgentDisplay::updateAgent()
{
  pqInternals& in = *this->Internals;
  vtkVesselTouchHapticSession* session = in.sessionObject();
  const double* a = session ? session->GetAgentState() : nullptr;
  std::array<double, 24> signature{};
  if (a)
  {
    std::copy(a + State, a + ForceX + 2, signature.begin());
  }
  signature[23] = a ? 1.0 : 0.0;
  const bool moved = signature != in.DrawnSignature;
  in.AgentChanged = in.AgentChanged || moved;
  in.DrawnSignature = signature;

  vtkRenderer* scene = this->View->getRenderViewProxy()->GetRenderer();
  const bool visible = a && a[Tick] > 0.0;
  const int state = visible ? static_cast<int>(a[State]) : -1;
  this->LastState = state;
  if (state != 1)
  {
    in.Actors.setConeVisible(false);
  }
  const int* viewportOrigin = scene->GetOrigin(); // the session's cursor is viewport-relative
  double anchor[2] = { -1.0, -1.0 };
  if (state == 1)
  {
    const bool placed = this->placeCone(a, anchor);
    in.Actors.setConeVisible(placed);
    in.Actors.setCursor(false, 0.0, 0.0);
  }
  else if (state == 0)
  {
    anchor[0] = a[CursorX] + viewportOrigin[0];
    anchor[1] = a[CursorX + 1] + viewportOrigin[1];
    in.Actors.setCursor(true, anchor[0], anchor[1]);
  }
  else
  {
    in.Actors.setCursor(false, 0.0, 0.0);
  }
  const bool arrow = state >= 0 && anchor[0] >= 0.0;
  const vtouch::Vec2 tip = arrow ? vtouch::forceArrowTip_px({ anchor[0], anchor[1] },
                                     { a[ForceX], a[ForceX + 1] },
                                     this->ArrowPixelsPerNewton,
                                     kMaxArrow_px)
                                 : vtouch::Vec2{};
  const double tip_px[2] = { tip.x, tip.y };
  in.Actors.setForceArrow(arrow, anchor, tip_px);
  this->LastAgent_px[0] = anchor[0];
  this->LastAgent_px[1] = anchor[1];
}

bool pqVesselTouchAgentDisplay::placeCone(const double* a, double anchor_px[2])
{
  // Centred on the agent's centerline point, apex along the tangent x direction of travel,
  // rolled by the torsion angle, AgentHeight_px high on screen at the agent's depth.
  pqInternals& in = *this->Internals;
  vtkRenderer* scene = this->View->getRenderViewProxy()->GetRenderer();
  const vtouch::Vec3 position{ a[PositionX], a[PositionX + 1], a[PositionX + 2] };
  const vtouch::Vec3 tangent{ a[TangentX], a[TangentX + 1], a[TangentX + 2] };
  const vtouch::Vec3 apex =
    vtouch::agentApexDirection(tangent, static_cast<int>(a[Direction]), in.LastDirection);
  vtkCamera* camera = scene->GetActiveCamera();
  vtouch::ScreenScale scale;
  scale.parallelProjection = camera->GetParallelProjection() != 0;
  scale.parallelScale_mm = camera->GetParallelScale();
  scale.viewAngle_deg = camera->GetViewAngle();
  scale.viewportHeight_px = scene->GetSize()[1];
  const double* eye = camera->GetPosition();
  const double* towards = camera->GetDirectionOfProjection();
  const double depth_mm = (position.x - eye[0]) * towards[0] + (position.y - eye[1]) * towards[1] +
                          (position.z - eye[2]) * towards[2];
  const double height_mm = this->AgentHeight_px * vtouch::millimetresPerPixel(scale, depth_mm);
  vtouch::Matrix4x4 matrix{};
  if (!vtouch::agentConeMatrix(position, apex, a[Torsion], height_mm, matrix))
  {
    return false;
  }
  in.Actors.setConeMatrix(matrix);
  scene->SetWorldPoint(position.x, position.y, position.z, 1.0);
  scene->WorldToDisplay();
  const double* d = scene->GetDisplayPoint();
  anchor_px[0] = d[0];
  anchor_px[1] = d[1];
  return true;
}

void pqVesselTouchAgentDisplay::drawFrame()
{
  pqInternals& in = *this->Internals;
  if (in.Overlay.isCacheValid())
  {
    in.RenderRequested = false;
    if (in.AgentChanged)
    {
      in.Overlay.renderCached();
      in.AgentChanged = false;
      this->LastFrameCached = true;
    }
    return;
  }
  // The scene changed (camera, data, transfer function) or nothing was captured yet: ask
  // ParaView for a normal render, which draws the agent too and captures. Not during a mouse
  // drag: the interactor renders on its own, and ParaView renders once more when it ends.
  if (QGuiApplication::mouseButtons() != Qt::NoButton)
  {
    return;
  }
  if (in.RenderRequested && in.Overlay.captures() == in.CapturesAtRequest &&
      in.SinceRequest.elapsed() < kRenderRetry_ms)
  {
    return;
  }
  in.RenderRequested = true;
  in.CapturesAtRequest = in.Overlay.captures();
  in.SinceRequest.start();
  in.AgentChanged = false;
  this->LastFrameCached = false;
  this->View->render();
}

QJsonObject pqVesselTouchAgentDisplay::diagnostics() const
{
  QJsonObject report;
  report.insert("enabled", this->Enabled);
  report.insert("session", this->Internals->Session != nullptr);
  report.insert("full_renders", static_cast<double>(this->fullRenders()));
  report.insert("cached_frames", static_cast<double>(this->cachedFrames()));
  report.insert("camera_pushes", static_cast<double>(this->CameraPushes));
  report.insert("cached_frame_ms_mean", this->meanCachedFrame_ms());
  report.insert("full_scene_render_ms_last", this->lastFullSceneRender_ms());
  report.insert("state", this->LastState);
  if (vtkVesselTouchHapticSession* session = this->Internals->sessionObject())
  {
    const double* a = session->GetAgentState();
    report.insert("tick", a[Tick]);
    report.insert("cursor_x_px", a[CursorX]);
    report.insert("cursor_y_px", a[CursorX + 1]);
    report.insert("running", session->IsRunning());
    report.insert("view_model_builds", static_cast<double>(session->GetViewModelBuilds()));
    report.insert("device_type", session->GetDeviceType());
  }
  report.insert("agent_x_px", this->LastAgent_px[0]);
  report.insert("agent_y_px", this->LastAgent_px[1]);
  vtkSMRenderViewProxy* proxy = this->View ? this->View->getRenderViewProxy() : nullptr;
  if (proxy && proxy->GetRenderWindow())
  {
    const int* size = proxy->GetRenderWindow()->GetSize();
    report.insert("window_width_px", size[0]);
    report.insert("window_height_px", size[1]);
  }
  if (QWidget* widget = this->View ? this->View->widget() : nullptr)
  {
    // Where the view is on the screen (logical px), so a test can crop a screenshot to it.
    const QPoint corner = widget->mapToGlobal(QPoint(0, 0));
    report.insert("view_screen_x", corner.x());
    report.insert("view_screen_y", corner.y());
    report.insert("view_width", widget->width());
    report.insert("view_height", widget->height());
    report.insert("device_pixel_ratio", widget->devicePixelRatioF());
  }
  return report;
}

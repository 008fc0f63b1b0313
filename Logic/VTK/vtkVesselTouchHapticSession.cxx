#include "vtkVesselTouchHapticSession.h"

#include "vtouchPolyDataToQSkeleton.h"

#include "vtouchHapticSession.h"
#include "vtouchHidPidDevice.h"
#include "vtouchHidapiTransport.h"
#include "vtouchPointerDevice.h"
#include "vtouchReplayDevice.h"
#include "vtouchSafeHapticDevice.h"
#include "vtouchSimulatedDevice.h"

#include "vtkDoubleArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkMatrix4x4.h"
#include "vtkObjectFactory.h"
#include "vtkPolyData.h"
#include "vtkTable.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <new>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkVesselTouchHapticSession);

namespace
{
/// Longest log (offline run or real-time capacity): 2e6 entries, about 230 MB.
constexpr int kMaxLogEntries = 2000000;
} // namespace

namespace
{
/// Timed hand samples (device mm), shared with the hand script's lambda (read-only once set).
struct HandTrack
{
  std::vector<double> time_s;
  std::vector<vtouch::Vec2> position_mm;

  /// Linear interpolation, held outside the samples; velocity of the current segment.
  void at(double t, vtouch::Vec2& p, vtouch::Vec2& v) const
  {
    v = {};
    if (time_s.empty())
    {
      p = {};
      return;
    }
    if (t <= time_s.front() || time_s.size() == 1)
    {
      p = position_mm.front();
      return;
    }
    if (t >= time_s.back())
    {
      p = position_mm.back();
      return;
    }
    const std::size_t i =
      static_cast<std::size_t>(std::upper_bound(time_s.begin(), time_s.end(), t) - time_s.begin());
    const double dt = time_s[i] - time_s[i - 1];
    v = (position_mm[i] - position_mm[i - 1]) * (1.0 / dt);
    p = position_mm[i - 1] + v * (t - time_s[i - 1]);
  }
};

/// Row-major (vtkMatrix4x4) -> column-major (vtouch::Mat4): the transpose.
vtouch::Mat4 columnMajor(const double rowMajor[16])
{
  vtouch::Mat4 m{};
  for (int r = 0; r < 4; ++r)
  {
    for (int c = 0; c < 4; ++c)
    {
      m[static_cast<std::size_t>(c * 4 + r)] = rowMajor[r * 4 + c];
    }
  }
  return m;
}

template<typename T>
vtkSmartPointer<T> column(vtkTable* table, const char* name, int components, vtkIdType rows)
{
  auto a = vtkSmartPointer<T>::New();
  a->SetName(name);
  a->SetNumberOfComponents(components);
  a->SetNumberOfTuples(rows);
  table->AddColumn(a);
  return a;
}
} // namespace

class vtkVesselTouchHapticSession::vtkInternals
{
public:
  vtouch::HapticSession Session;
  vtouch::QSkeleton Skeleton;
  bool HasSkeleton = false;
  vtkMTimeType SkeletonTime = 0;
  vtkDataObject* SkeletonSource = nullptr;
  vtouch::Vec3 Center;
  double Radius_mm = 0.0;
  vtouch::HostCamera Camera;
  bool HasCamera = false;
  std::shared_ptr<HandTrack> Track = std::make_shared<HandTrack>();
  vtouch::PointerDevice* Pointer = nullptr; // inside the session's SafeHapticDevice
  double OfflineStart_s = 0.0;
  std::string LastError;
  std::string FaultText;
  std::string SchedulerText;
};

vtkVesselTouchHapticSession::vtkVesselTouchHapticSession()
  : Internals(new vtkInternals)
{
  this->SetNumberOfInputPorts(1);
  this->SetNumberOfOutputPorts(1);
  this->PushParameters();
}

vtkVesselTouchHapticSession::~vtkVesselTouchHapticSession()
{
  this->Internals->Session.stop();
  if (auto device = this->Internals->Session.device())
  {
    device->close();
  }
  this->SetReplayFileName(nullptr);
  this->SetHidPath(nullptr);
}

int vtkVesselTouchHapticSession::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
  // Optional for the pipeline, so that a session created before its centerline (the shared
  // vesseltouch.logic()) reports "no centerline" itself instead of a pipeline error.
  info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
  return 1;
}

void vtkVesselTouchHapticSession::Fail(const std::string& message)
{
  this->Internals->LastError = message;
  vtkErrorMacro(<< message);
}

void vtkVesselTouchHapticSession::Modified()
{
  this->Superclass::Modified();
  if (this->Internals) // not during construction
  {
    this->PushParameters();
  }
}

void vtkVesselTouchHapticSession::PushParameters()
{
  vtouch::HapticSession& s = this->Internals->Session;
  vtouch::HapticParameters p = s.parameters();
  p.forceLaw = static_cast<vtouch::ForceLawId>(std::clamp(this->ForceLaw, 0, 4));
  p.crossfade_s = this->Crossfade;
  p.ldgfLambda_mm = this->LdgfLambda;
  p.cohLambda_mm = this->ChangeOfHeightLambda;
  p.cohZMax_mm = this->ChangeOfHeightZMax; // 0: from the device's resolution
  // ChangeOfHeightForgetTime is ignored: Hayward & Yi's eqs. 8-9 have no forgetting factor.
  p.lateralProbe_px = this->LateralProbe;
  p.proxyStiffness_N_per_m = this->ProxyStiffness;
  p.proxyDamping_N_s_per_m = this->ProxyDamping;
  p.proxyTangentDrag = this->ProxyTangentDrag;
  p.proxyTangentThreshold_N = this->ProxyTangentThreshold;
  p.proxySnapDrag = this->ProxySnapDrag;
  p.proxySnapThreshold_N = this->ProxySnapThreshold;
  p.zoneGain_N = this->ZoneGain;
  p.zoneZeroBelow = this->ZoneZeroBelow;
  p.zoneSaturateAbove = this->ZoneSaturateAbove;
  p.zoom = this->Zoom;
  p.pixelsPerDeviceMm = this->PixelsPerDeviceMm;
  p.maxForceRate_N_per_s = this->MaxForceRate;
  p.contactDwell_s = this->ContactDwell;
  p.contactApproachAtStart = this->ContactApproachAtStart;
  p.tracerRule = this->TracerRule;
  p.slopeForceBudget = this->SlopeForceBudget;
  p.tracerMovementThreshold_px = this->TracerMovementThreshold;
  p.tracerJunctionWindow_px = this->TracerJunctionWindow;
  p.tracerJunctionMargin_px = this->TracerJunctionMargin;
  p.forceInterpolationPerAxis = this->ForceInterpolationPerAxis;
  p.cohZMaxPerResolution = this->ChangeOfHeightZMaxPerResolution;
  p.proxyTangentSnap = this->ProxyTangentSnap;
  p.proxyNormalUnilateral = this->ProxyNormalUnilateral;
  p.proxyThresholdFromData = this->ProxyThresholdFromData;
  p.proxyFriction = this->ProxyFriction;
  p.proxyTickSpacing_mm = this->ProxyTickSpacing;
  p.proxyTickForce_N = this->ProxyTickForce;
  p.proxyTickAtBifurcations = this->ProxyTickAtBifurcations;
  p.proxyFieldForce = this->ProxyFieldForce;
  p.proxyKappaLow = this->ProxyKappaLow;
  p.proxyKappaHigh = this->ProxyKappaHigh;
  p.idleRadius_mm = this->IdleRadius;
  p.idleDwell_s = this->IdleDwell;
  p.idleRamp_s = this->IdleRamp;
  s.setParameters(p);
  if (s.captureRadius_px() != this->CaptureRadius)
  {
    s.setCaptureRadius_px(this->CaptureRadius);
  }
  if (s.slopeWindow_mm() != this->SlopeWindow)
  {
    s.setSlopeWindow_mm(this->SlopeWindow);
  }
  this->ApplyCamera();
}

bool vtkVesselTouchHapticSession::ApplyCamera()
{
  vtkInternals& in = *this->Internals;
  vtouch::HostCamera cam;
  cam.viewportWidth_px = this->ViewportSize[0];
  cam.viewportHeight_px = this->ViewportSize[1];
  if (this->UseExplicitMatrices)
  {
    cam.view_WorldToEye = columnMajor(this->ViewMatrix);
    cam.projection_EyeToClip = columnMajor(this->ProjectionMatrix);
  }
  else
  {
    const vtouch::Vec3 position{
      this->CameraPosition[0], this->CameraPosition[1], this->CameraPosition[2]
    };
    const vtouch::Vec3 focal{
      this->CameraFocalPoint[0], this->CameraFocalPoint[1], this->CameraFocalPoint[2]
    };
    const vtouch::Vec3 up{ this->CameraViewUp[0], this->CameraViewUp[1], this->CameraViewUp[2] };
    cam.view_WorldToEye = vtouch::lookAt(position, focal, up);
    // Clipping range around the centerline's bounding sphere (only NDC depth depends on it).
    const double radius = in.HasSkeleton ? std::max(in.Radius_mm, 1.0) : 1000.0;
    const double centre = in.HasSkeleton ? -cam.worldToEye(in.Center).z : (focal - position).norm();
    const double aspect = this->ViewportSize[1] > 0
                            ? static_cast<double>(this->ViewportSize[0]) / this->ViewportSize[1]
                            : 1.0;
    const double farPlane = std::max(centre + 1.5 * radius, 1.0);
    if (this->CameraParallelProjection)
    {
      const double scale = this->CameraParallelScale > 0.0 ? this->CameraParallelScale
                                                           : 1.05 * (in.HasSkeleton ? radius : 1.0);
      cam.projection_EyeToClip =
        vtouch::orthographic(scale, aspect, centre - 1.5 * radius, farPlane);
    }
    else
    {
      const double nearPlane = std::max(centre - 1.5 * radius, 1e-3 * farPlane);
      cam.projection_EyeToClip =
        vtouch::perspective(this->CameraViewAngle, aspect, nearPlane, farPlane);
    }
  }
  if (in.HasCamera && cam.view_WorldToEye == in.Camera.view_WorldToEye &&
      cam.projection_EyeToClip == in.Camera.projection_EyeToClip &&
      cam.viewportWidth_px == in.Camera.viewportWidth_px &&
      cam.viewportHeight_px == in.Camera.viewportHeight_px)
  {
    return true; // unchanged: no rebuild
  }
  const char* why = cam.validate();
  if (why && *why)
  {
    in.HasCamera = false;
    this->Fail(std::string("unusable camera: ") + why);
    return false;
  }
  if (!in.Session.setCamera(cam))
  {
    in.HasCamera = false;
    this->Fail("unusable camera: " + in.Session.lastError());
    return false;
  }
  in.Camera = cam;
  in.HasCamera = true;
  return true;
}

void vtkVesselTouchHapticSession::SetCameraMatrices(vtkMatrix4x4* view, vtkMatrix4x4* projection)
{
  if (!view || !projection)
  {
    this->Fail("SetCameraMatrices: null matrix");
    return;
  }
  std::copy(&view->Element[0][0], &view->Element[0][0] + 16, this->ViewMatrix);
  std::copy(&projection->Element[0][0], &projection->Element[0][0] + 16, this->ProjectionMatrix);
  this->UseExplicitMatrices = true;
  this->Modified();
}

void vtkVesselTouchHapticSession::AddHandSample(double time_s, double x_mm, double y_mm)
{
  if (this->IsRunning())
  {
    this->Fail("AddHandSample: stop the session first");
    return;
  }
  HandTrack& track = *this->Internals->Track;
  if (!std::isfinite(time_s) || !std::isfinite(x_mm) || !std::isfinite(y_mm) ||
      (!track.time_s.empty() && time_s <= track.time_s.back()))
  {
    this->Fail("AddHandSample: samples need finite values and increasing times");
    return;
  }
  track.time_s.push_back(time_s);
  track.position_mm.push_back({ x_mm, y_mm });
  this->Modified();
}

void vtkVesselTouchHapticSession::ClearHandSamples()
{
  if (this->IsRunning())
  {
    this->Fail("ClearHandSamples: stop the session first");
    return;
  }
  // A new track: a simulated device of an earlier run may still hold the old one.
  this->Internals->Track = std::make_shared<HandTrack>();
  this->Modified();
}

int vtkVesselTouchHapticSession::GetNumberOfHandSamples() const
{
  return static_cast<int>(this->Internals->Track->time_s.size());
}

void vtkVesselTouchHapticSession::SetPointerPosition(double x_mm, double y_mm)
{
  if (this->Internals->Pointer)
  {
    this->Internals->Pointer->setPointerPosition({ x_mm, y_mm });
  }
}

void vtkVesselTouchHapticSession::SetPointerPressed(bool pressed)
{
  if (this->Internals->Pointer)
  {
    this->Internals->Pointer->setModifierPressed(pressed);
  }
}

void vtkVesselTouchHapticSession::SetPointerButtons(int buttons)
{
  if (this->Internals->Pointer)
  {
    this->Internals->Pointer->setButtons(static_cast<std::uint32_t>(buttons));
  }
}

vtkDataObject* vtkVesselTouchHapticSession::UpdateInput()
{
  // Outside a pipeline pass (Start, RunOffline): bring the input up to date first.
  if (this->GetNumberOfInputConnections(0) == 0)
  {
    return nullptr;
  }
  int port = 0;
  vtkAlgorithm* producer = this->GetInputAlgorithm(0, 0, port);
  if (!producer)
  {
    return nullptr;
  }
  producer->Update(port);
  return producer->GetOutputDataObject(port);
}

bool vtkVesselTouchHapticSession::UpdateSkeleton(vtkDataObject* data)
{
  vtkInternals& in = *this->Internals;
  if (!data)
  {
    in.HasSkeleton = false;
    in.SkeletonSource = nullptr;
    this->Fail("no centerline: connect a centerline polydata (VesselCenterline, or VesselPhantom "
               "port 1) to the input");
    return false;
  }
  if (data == in.SkeletonSource && data->GetMTime() == in.SkeletonTime)
  {
    return in.HasSkeleton; // unchanged
  }
  in.SkeletonSource = data;
  in.SkeletonTime = data->GetMTime();
  vtouch::PolyDataToQSkeleton converter;
  std::string error;
  vtouch::QSkeleton skeleton;
  if (!converter.convert(vtkPolyData::SafeDownCast(data), skeleton, error))
  {
    in.HasSkeleton = false;
    this->Fail("centerline: " + error);
    return false;
  }
  if (in.Session.isRunning())
  {
    in.Session.stop(); // the haptic thread must not see the scene swapped under a running agent
  }
  double bounds[6];
  vtkPolyData::SafeDownCast(data)->GetBounds(bounds);
  in.Center = {
    0.5 * (bounds[0] + bounds[1]), 0.5 * (bounds[2] + bounds[3]), 0.5 * (bounds[4] + bounds[5])
  };
  in.Radius_mm = 0.5 * std::sqrt((bounds[1] - bounds[0]) * (bounds[1] - bounds[0]) +
                                 (bounds[3] - bounds[2]) * (bounds[3] - bounds[2]) +
                                 (bounds[5] - bounds[4]) * (bounds[5] - bounds[4]));
  in.Skeleton = std::move(skeleton);
  in.Session.setSkeleton(in.Skeleton);
  in.HasSkeleton = true;
  in.HasCamera = false; // the automatic clipping range and scale depend on the bounds
  return this->ApplyCamera();
}

bool vtkVesselTouchHapticSession::BuildDevice(bool offline)
{
  vtkInternals& in = *this->Internals;
  in.Pointer = nullptr;
  in.Session.setDevice(nullptr);
  std::unique_ptr<vtouch::HapticDevice> inner;
  vtouch::SimulatedDevice* simulated = nullptr;
  switch (this->DeviceType)
  {
    case SIMULATED:
    {
      vtouch::SimulatedDeviceParameters dp;
      dp.clock = offline ? vtouch::SimulatedDeviceParameters::Clock::Manual
                         : vtouch::SimulatedDeviceParameters::Clock::RealTime;
      dp.mass_kg = this->SimulatedMass;
      dp.damping_N_s_per_m = this->SimulatedDamping;
      dp.maxContinuousForce_N = this->SimulatedMaxForce;
      vtouch::HandScript hand;
      hand.drive = vtouch::HandScript::Drive::Position;
      hand.handStiffness_N_per_m = this->HandStiffness;
      hand.handDamping_N_s_per_m = this->HandDamping;
      const double pressure = this->HandPressure;
      const double pxPerMm = this->PixelsPerDeviceMm * this->Zoom;
      vtouch::Vec2 cursor{ this->ViewportSize[0] * 0.5, this->ViewportSize[1] * 0.5 };
      if (this->HandScript == HAND_SWEEP)
      {
        if (!in.HasSkeleton || this->SweepPath < 0 ||
            this->SweepPath >= static_cast<int>(in.Skeleton.paths.size()) || !(pxPerMm > 0.0))
        {
          this->Fail("the sweep needs a centerline and a valid SweepPath");
          return false;
        }
        // The hand follows the path's screen projection: hand mm = (screen - start) / pxPerMm,
        // starting 20 mm to the right and reaching the first point in 0.3 s.
        auto track = std::make_shared<HandTrack>();
        const auto& points = in.Skeleton.paths[static_cast<std::size_t>(this->SweepPath)].points;
        std::vector<vtouch::Vec2> screen;
        for (const vtouch::SkeletonPoint& q : points)
        {
          vtouch::Vec2 s;
          if (in.Camera.eyeToScreen(in.Camera.worldToEye(q.position_World_mm), s))
          {
            screen.push_back(s);
          }
        }
        if (screen.size() < 2)
        {
          this->Fail("the sweep path is not in front of the camera");
          return false;
        }
        const double speed = std::max(this->SweepSpeed, 1e-3);
        double t = 0.3;
        track->time_s.push_back(0.0);
        track->position_mm.push_back({ 20.0, 0.0 });
        track->time_s.push_back(t);
        track->position_mm.push_back({ 0.0, 0.0 });
        for (std::size_t i = 1; i < screen.size(); ++i)
        {
          const double step = (screen[i] - screen[i - 1]).norm() / pxPerMm;
          if (step <= 1e-9)
          {
            continue;
          }
          t += step / speed;
          track->time_s.push_back(t);
          track->position_mm.push_back((screen[i] - screen[0]) * (1.0 / pxPerMm));
        }
        cursor = screen[0] + vtouch::Vec2{ 20.0 * pxPerMm, 0.0 };
        dp.initialPosition_Device_mm = { 20.0, 0.0 };
        hand.trajectory = [track, pressure](double time, vtouch::HandSample& h)
        {
          track->at(time, h.position_Device_mm, h.velocity_Device_mm_per_s);
          h.pressure = pressure;
        };
      }
      else if (this->HandScript == HAND_TRAJECTORY)
      {
        std::shared_ptr<const HandTrack> track = in.Track;
        if (track->time_s.empty())
        {
          this->Fail("the hand trajectory has no samples (AddHandSample)");
          return false;
        }
        dp.initialPosition_Device_mm = track->position_mm.front();
        if (this->InitialCursor[0] >= 0.0 && this->InitialCursor[1] >= 0.0)
        {
          cursor = { this->InitialCursor[0], this->InitialCursor[1] };
        }
        hand.trajectory = [track, pressure](double time, vtouch::HandSample& h)
        {
          track->at(time, h.position_Device_mm, h.velocity_Device_mm_per_s);
          h.pressure = pressure;
        };
      }
      auto sim = std::make_unique<vtouch::SimulatedDevice>(dp);
      sim->setHandScript(hand);
      simulated = sim.get();
      inner = std::move(sim);
      in.Session.pipeline().reset();
      in.Session.pipeline().setCursor_px(cursor);
      break;
    }
    case POINTER:
    {
      auto pointer = std::make_unique<vtouch::PointerDevice>();
      in.Pointer = pointer.get();
      inner = std::move(pointer);
      break;
    }
    case REPLAY:
    {
      vtouch::ReplayDeviceParameters rp;
      rp.clock = vtouch::ReplayDeviceParameters::Clock::RealTime;
      auto replay = std::make_unique<vtouch::ReplayDevice>(rp);
      std::string error;
      if (!this->ReplayFileName || !replay->loadCsv(this->ReplayFileName, error))
      {
        this->Fail(std::string("replay device: ") +
                   (this->ReplayFileName ? error : std::string("no ReplayFileName")));
        return false;
      }
      inner = std::move(replay);
      break;
    }
    case HID:
    {
      if (!this->HidPath || !*this->HidPath)
      {
        this->Fail("HID device: no HidPath");
        return false;
      }
      inner = std::make_unique<vtouch::HidPidDevice>(
        std::make_shared<vtouch::HidapiTransport>(), this->HidPath);
      break;
    }
    default:
      this->Fail("unknown DeviceType");
      return false;
  }
  if (this->DeviceType != SIMULATED)
  {
    in.Session.pipeline().reset(); // a fresh start: exploring, cursor re-centred
  }
  vtouch::SafeHapticDeviceParameters sp;
  sp.filter.maxForce_N = this->MaxForce;
  if (offline)
  {
    // Simulated time drives the slew limit; no watchdog thread between offline runs.
    sp.watchdogThread = false;
    sp.watchdogTimeout_s = 0.0;
    sp.autoReopen = false;
    sp.clock_s = [simulated]() { return simulated->time_s(); };
  }
  auto device = std::make_shared<vtouch::SafeHapticDevice>(std::move(inner), sp);
  if (device->open() != vtouch::DeviceStatus::Ok)
  {
    this->Fail(std::string("the device did not open: ") + device->lastError());
    in.Pointer = nullptr;
    return false;
  }
  vtouch::ForceSafetyParameters safety;
  safety.maxForce_N = this->MaxForce;
  in.Session.setSafetyParameters(safety);
  in.Session.setDevice(device);
  in.Session.clearFault();
  return true;
}

bool vtkVesselTouchHapticSession::ReserveLog(int entries)
{
  try
  {
    this->Internals->Session.setLogCapacity(
      static_cast<std::size_t>(std::clamp(entries, 0, kMaxLogEntries)));
  }
  catch (const std::bad_alloc&)
  {
    this->Fail("not enough memory for a log of this length");
    return false;
  }
  return true;
}

bool vtkVesselTouchHapticSession::Start()
{
  vtkInternals& in = *this->Internals;
  if (in.Session.isRunning())
  {
    return true;
  }
  if (!this->UpdateSkeleton(this->UpdateInput()) || !in.HasCamera)
  {
    if (!in.HasCamera)
    {
      this->Fail("Start: the camera is unusable");
    }
    return false;
  }
  if (!this->BuildDevice(false))
  {
    return false;
  }
  in.Session.clearLog();
  if (!this->ReserveLog(this->LogCapacity))
  {
    return false;
  }
  in.Session.setLogging(this->LogCapacity > 0);
  in.OfflineStart_s = 0.0;
  vtouch::LoopOptions options;
  options.rate_Hz = this->LoopRate;
  if (!in.Session.start(options))
  {
    this->Fail("Start: " + in.Session.lastError());
    return false;
  }
  in.LastError.clear();
  return true;
}

void vtkVesselTouchHapticSession::Stop()
{
  vtkInternals& in = *this->Internals;
  const bool wasRunning = in.Session.isRunning();
  in.Session.stop();
  in.Session.setLogging(false);
  if (auto device = in.Session.device())
  {
    device->close(); // zero force, actuators off
  }
  in.Pointer = nullptr;
  if (wasRunning)
  {
    this->Modified(); // the log output changed
  }
}

bool vtkVesselTouchHapticSession::IsRunning() const
{
  return this->Internals->Session.isRunning();
}

bool vtkVesselTouchHapticSession::RunOffline()
{
  return this->RunOffline(this->OfflineDuration, this->OfflineRate);
}

bool vtkVesselTouchHapticSession::RunOffline(double duration_s, double rate_Hz)
{
  vtkInternals& in = *this->Internals;
  if (in.Session.isRunning())
  {
    this->Fail("RunOffline: stop the real-time session first");
    return false;
  }
  if (!(duration_s >= 0.0) || !std::isfinite(duration_s) || !(rate_Hz >= 1.0) ||
      !(rate_Hz <= 100000.0) || duration_s * rate_Hz > kMaxLogEntries)
  {
    this->Fail("RunOffline: the duration must be finite and >= 0, the rate in [1, 1e5] Hz and "
               "the run at most 2e6 ticks");
    return false;
  }
  if (this->DeviceType != SIMULATED)
  {
    this->Fail("RunOffline needs the simulated device (DeviceType 0)");
    return false;
  }
  if (!this->UpdateSkeleton(this->UpdateInput()))
  {
    return false;
  }
  if (!in.HasCamera)
  {
    this->Fail("RunOffline: the camera is unusable");
    return false;
  }
  if (!this->BuildDevice(true))
  {
    return false;
  }
  in.Session.clearLog();
  if (!this->ReserveLog(static_cast<int>(std::llround(duration_s * rate_Hz)) + 1))
  {
    return false;
  }
  in.OfflineStart_s = in.Session.offlineTime_s();
  const bool ok = in.Session.runOffline(duration_s, rate_Hz);
  in.Session.setLogging(false);
  if (!ok)
  {
    this->Fail("RunOffline: " + in.Session.lastError());
  }
  else
  {
    in.LastError.clear();
  }
  this->Modified(); // the log output changed
  return ok;
}

void vtkVesselTouchHapticSession::ClearFault()
{
  if (auto device =
        std::dynamic_pointer_cast<vtouch::SafeHapticDevice>(this->Internals->Session.device()))
  {
    device->clearFault();
  }
  this->Internals->Session.clearFault();
}

double* vtkVesselTouchHapticSession::GetStatistics()
{
  const vtouch::LoopStatisticsSummary s = this->Internals->Session.statistics();
  const double values[12] = { s.nominalRate_Hz,
    s.achievedRate_Hz,
    static_cast<double>(s.ticks),
    static_cast<double>(s.overruns),
    static_cast<double>(s.skippedDeadlines),
    s.periodErrorP50_us,
    s.periodErrorP99_us,
    s.periodErrorP999_us,
    s.periodErrorMax_us,
    s.tickCostP50_us,
    s.tickCostP99_us,
    s.tickCostMax_us };
  std::copy(values, values + 12, this->Statistics);
  return this->Statistics;
}

double* vtkVesselTouchHapticSession::GetAgentState()
{
  const vtouch::AgentState a = this->Internals->Session.agentState();
  const double values[23] = { a.time_s,
    static_cast<double>(a.tick),
    static_cast<double>(a.state),
    static_cast<double>(a.forceLaw),
    static_cast<double>(a.path),
    static_cast<double>(a.point),
    a.cursor_px.x,
    a.cursor_px.y,
    a.position_World_mm.x,
    a.position_World_mm.y,
    a.position_World_mm.z,
    a.tangent_World.x,
    a.tangent_World.y,
    a.tangent_World.z,
    static_cast<double>(a.directionOfTravel),
    a.coneRoll_rad, // the cone's roll: RMF + integral of torsion (vtouch::AgentFrame)
    a.zoneGain_N,
    a.force_N.x,
    a.force_N.y,
    a.targetForce_N.x,
    a.targetForce_N.y,
    a.hand_Device_mm.x,
    a.hand_Device_mm.y };
  std::copy(values, values + 23, this->AgentState);
  return this->AgentState;
}

double* vtkVesselTouchHapticSession::GetDeviceForce()
{
  vtouch::Vec3 force_N{};
  auto device =
    std::dynamic_pointer_cast<vtouch::SafeHapticDevice>(this->Internals->Session.device());
  if (device && device->isOpen())
  {
    force_N = device->lastSentForce_N();
  }
  this->DeviceForce[0] = force_N.x;
  this->DeviceForce[1] = force_N.y;
  this->DeviceForce[2] = force_N.z;
  return this->DeviceForce;
}

int* vtkVesselTouchHapticSession::GetSessionStatus()
{
  vtkInternals& in = *this->Internals;
  const bool running = in.Session.isRunning();
  this->SessionStatus[0] = running ? 1 : 0;
  this->SessionStatus[1] = static_cast<int>(in.Session.fault());
  // The log vector belongs to the haptic thread while running.
  this->SessionStatus[2] = running ? -1 : static_cast<int>(in.Session.log().size());
  this->SessionStatus[3] = running ? -1 : static_cast<int>(in.Session.droppedLogEntries());
  this->SessionStatus[4] = in.HasSkeleton ? static_cast<int>(in.Skeleton.paths.size()) : 0;
  this->SessionStatus[5] = in.HasSkeleton ? static_cast<int>(in.Skeleton.pointCount()) : 0;
  return this->SessionStatus;
}

double* vtkVesselTouchHapticSession::GetTickOptions()
{
  const vtouch::HapticParameters p = this->Internals->Session.parameters();
  const double values[25] = { static_cast<double>(p.tracerRule),
    p.tracerMovementThreshold_px,
    p.tracerJunctionWindow_px,
    p.tracerJunctionMargin_px,
    p.contactDwell_s,
    p.contactApproachAtStart ? 1.0 : 0.0,
    p.slopeForceBudget,
    p.forceInterpolationPerAxis ? 1.0 : 0.0,
    p.maxForceRate_N_per_s,
    p.cohZMaxPerResolution,
    p.proxyTangentDrag ? 1.0 : 0.0,
    p.proxyTangentSnap ? 1.0 : 0.0,
    p.proxySnapDrag ? 1.0 : 0.0,
    p.proxyNormalUnilateral ? 1.0 : 0.0,
    p.proxyThresholdFromData ? 1.0 : 0.0,
    p.proxyFriction,
    p.proxyTickSpacing_mm,
    p.proxyTickForce_N,
    p.proxyTickAtBifurcations ? 1.0 : 0.0,
    p.proxyFieldForce ? 1.0 : 0.0,
    p.proxyKappaLow,
    p.proxyKappaHigh,
    p.idleRadius_mm,
    p.idleDwell_s,
    p.idleRamp_s };
  std::copy(values, values + 25, this->TickOptions);
  return this->TickOptions;
}

const char* vtkVesselTouchHapticSession::GetLastErrorMessage()
{
  return this->Internals->LastError.c_str();
}

const char* vtkVesselTouchHapticSession::GetFaultMessage()
{
  this->Internals->FaultText = vtouch::toString(this->Internals->Session.fault());
  return this->Internals->FaultText.c_str();
}

const char* vtkVesselTouchHapticSession::GetSchedulerNotice()
{
  this->Internals->SchedulerText = this->Internals->Session.schedulerNotice();
  return this->Internals->SchedulerText.c_str();
}

int vtkVesselTouchHapticSession::RequestData(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkTable* output = vtkTable::GetData(outputVector);
  if (!output)
  {
    vtkErrorMacro("HapticSession: no output table.");
    return 1;
  }
  output->Initialize();
  vtkInternals& in = *this->Internals;
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0]);
  if (!input)
  {
    in.HasSkeleton = false;
    this->Fail("no centerline: the input is not a vtkPolyData");
  }
  else
  {
    this->UpdateSkeleton(input);
  }
  // While running the log belongs to the haptic thread: the table is filled after Stop().
  const std::vector<vtouch::SessionLogEntry> empty;
  const std::vector<vtouch::SessionLogEntry>& log =
    in.Session.isRunning() ? empty : in.Session.log();
  const vtkIdType n = static_cast<vtkIdType>(log.size());
  auto time = column<vtkDoubleArray>(output, "Time", 1, n);
  auto hand = column<vtkDoubleArray>(output, "Hand", 2, n);
  auto cursor = column<vtkDoubleArray>(output, "Cursor", 2, n);
  auto state = column<vtkIntArray>(output, "State", 1, n);
  auto path = column<vtkIntArray>(output, "Path", 1, n);
  auto point = column<vtkIntArray>(output, "Point", 1, n);
  auto position = column<vtkDoubleArray>(output, "Position", 3, n);
  auto target = column<vtkDoubleArray>(output, "TargetForce", 2, n);
  auto force = column<vtkDoubleArray>(output, "Force", 2, n);
  for (vtkIdType i = 0; i < n; ++i)
  {
    const vtouch::SessionLogEntry& e = log[static_cast<std::size_t>(i)];
    time->SetValue(i, e.time_s - in.OfflineStart_s);
    hand->SetTypedTuple(i, &e.hand_Device_mm.x);
    cursor->SetTypedTuple(i, &e.cursor_px.x);
    state->SetValue(i, static_cast<int>(e.state));
    path->SetValue(i, e.path);
    point->SetValue(i, e.point);
    const double p[3] = { e.position_World_mm.x, e.position_World_mm.y, e.position_World_mm.z };
    position->SetTypedTuple(i, p);
    target->SetTypedTuple(i, &e.targetForce_N.x);
    force->SetTypedTuple(i, &e.force_N.x);
  }
  return 1;
}

void vtkVesselTouchHapticSession::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "DeviceType: " << this->DeviceType << "\n";
  os << indent << "HandScript: " << this->HandScript << "\n";
  os << indent << "ForceLaw: " << this->ForceLaw << "\n";
  os << indent << "Zoom: " << this->Zoom << "\n";
  os << indent << "ZoneGain: " << this->ZoneGain << " ZoneZeroBelow: " << this->ZoneZeroBelow
     << " ZoneSaturateAbove: " << this->ZoneSaturateAbove << "\n";
  os << indent << "ViewportSize: " << this->ViewportSize[0] << " x " << this->ViewportSize[1]
     << "\n";
  os << indent << "Running: " << this->IsRunning() << "\n";
}

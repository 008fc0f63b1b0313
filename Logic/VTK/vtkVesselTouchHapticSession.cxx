#include "vtkVesselTouchHapticSession.h"

#include "vtouchPolyDataToQSkeleton.h"

#include "vtouchAgentStateLayout.h"
#include "vtouchDeviceFactory.h"
#include "vtouchHapticParameterTable.h"
#include "vtouchHapticSession.h"
#include "vtouchPointerDevice.h"
#include "vtouchSafeHapticDevice.h"
#include "vtouchSweepHandTrack.h"

#include "vtkDoubleArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkMatrix4x4.h"
#include "vtkObjectFactory.h"
#include "vtkPolyData.h"
#include "vtkTable.h"
#include "vtkWeakPointer.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <new>
#include <sstream>
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
  /// The haptic parameters as set (SetHapticParameter); ApplyProperties publishes them.
  vtouch::HapticParameters Parameters;
  std::string AppliedText;
  vtouch::QSkeleton Skeleton;
  bool HasSkeleton = false;
  vtkMTimeType SkeletonTime = 0;
  vtkDataObject* SkeletonSource = nullptr;
  vtouch::Vec3 Center;
  double Radius_mm = 0.0;
  vtouch::HostCamera Camera;
  bool HasCamera = false;
  std::shared_ptr<vtouch::HandTrack> Track = std::make_shared<vtouch::HandTrack>();
  vtouch::PointerDevice* Pointer = nullptr; // inside the session's SafeHapticDevice
  double OfflineStart_s = 0.0;
  std::string LastError;
  std::string FaultText;
  // After ReportConnectionLost: the held skeleton is used, never the input's producer again.
  bool ConnectionLost = false;
  bool ConnectionFaultLatched = false;
  std::string ConnectionMessage;
  std::string SchedulerText;
  std::string DeviceName;
  // SetDeliveredCenterline's producer (the client-side mover), to detach only that one.
  vtkWeakPointer<vtkAlgorithm> DeliveredProducer;
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

void vtkVesselTouchHapticSession::ApplyProperties()
{
  const vtkMTimeType now = this->GetMTime();
  if (now <= this->AppliedTime)
  {
    return; // nothing changed since the last push
  }
  this->AppliedTime = now;
  this->PushParameters();
}

void vtkVesselTouchHapticSession::PushParameters()
{
  vtouch::HapticSession& s = this->Internals->Session;
  s.setParameters(this->Internals->Parameters);
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

void vtkVesselTouchHapticSession::SetHapticParameter(const char* name, double value)
{
  const vtouch::HapticParameterDescriptor* d = vtouch::findHapticParameter(name);
  if (!d)
  {
    this->Fail(std::string("SetHapticParameter: unknown haptic parameter '") +
               (name ? name : "(null)") + "' (vtouchHapticParameters.def lists them)");
    return;
  }
  const std::string why = vtouch::checkHapticParameter(*d, value);
  if (!why.empty())
  {
    std::ostringstream kept;
    kept.precision(10);
    kept << d->get(this->Internals->Parameters);
    this->Fail("SetHapticParameter: " + why + "; " + d->name + " stays " + kept.str());
    return;
  }
  if (d->get(this->Internals->Parameters) == value)
  {
    return;
  }
  d->set(this->Internals->Parameters, value);
  this->Modified();
}

double vtkVesselTouchHapticSession::GetHapticParameter(const char* name)
{
  const vtouch::HapticParameterDescriptor* d = vtouch::findHapticParameter(name);
  if (!d)
  {
    this->Fail(std::string("GetHapticParameter: unknown haptic parameter '") +
               (name ? name : "(null)") + "'");
    return std::numeric_limits<double>::quiet_NaN();
  }
  return d->get(this->Internals->Parameters);
}

const char* vtkVesselTouchHapticSession::GetAppliedHapticParameters()
{
  const vtouch::HapticParameters applied = this->Internals->Session.parameters();
  std::ostringstream text;
  text.precision(17);
  for (const vtouch::HapticParameterDescriptor& d : vtouch::kHapticParameterDescriptors)
  {
    text << (&d == vtouch::kHapticParameterDescriptors ? "" : " ") << d.name << '='
         << d.get(applied);
  }
  this->Internals->AppliedText = text.str();
  return this->Internals->AppliedText.c_str();
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
  if (!this->Internals->Track->add(time_s, { x_mm, y_mm }))
  {
    this->Fail("AddHandSample: samples need finite values and increasing times");
    return;
  }
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
  this->Internals->Track = std::make_shared<vtouch::HandTrack>();
  this->Modified();
}

int vtkVesselTouchHapticSession::GetNumberOfHandSamples() const
{
  return static_cast<int>(this->Internals->Track->size());
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
  if (!this->Internals->ConnectionLost)
  {
    producer->Update(port); // after a lost connection its data came from the dead server
  }
  return producer->GetOutputDataObject(port);
}

bool vtkVesselTouchHapticSession::UpdateSkeleton(vtkDataObject* data)
{
  vtkInternals& in = *this->Internals;
  if (in.ConnectionLost && in.HasSkeleton)
  {
    return true; // the last skeleton delivered before the server was lost stays
  }
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
  vtouch::DeviceRequest request;
  request.kind = static_cast<vtouch::DeviceKind>(this->DeviceType);
  request.offline = offline;
  request.maxForce_N = this->MaxForce;
  request.simulatedMass_kg = this->SimulatedMass;
  request.simulatedDamping_N_s_per_m = this->SimulatedDamping;
  request.simulatedMaxForce_N = this->SimulatedMaxForce;
  request.handStiffness_N_per_m = this->HandStiffness;
  request.handDamping_N_s_per_m = this->HandDamping;
  request.handPressure = this->HandPressure;
  request.replayFile = this->ReplayFileName ? this->ReplayFileName : "";
  request.hidPath = this->HidPath ? this->HidPath : "";

  // The simulated hand's script and where the cursor starts (the screen centre by default).
  vtouch::Vec2 cursor{ this->ViewportSize[0] * 0.5, this->ViewportSize[1] * 0.5 };
  if (this->DeviceType == SIMULATED && this->HandScript == HAND_SWEEP)
  {
    if (!in.HasSkeleton)
    {
      this->Fail("the sweep needs a centerline and a valid SweepPath");
      return false;
    }
    vtouch::SweepHandTrack sweep = vtouch::makeSweepHandTrack(in.Skeleton,
      in.Camera,
      this->SweepPath,
      in.Parameters.pixelsPerDeviceMm * in.Parameters.zoom,
      this->SweepSpeed);
    if (!sweep.ok())
    {
      this->Fail(sweep.error);
      return false;
    }
    request.hand = std::make_shared<const vtouch::HandTrack>(std::move(sweep.track));
    cursor = sweep.startCursor_px;
  }
  else if (this->DeviceType == SIMULATED && this->HandScript == HAND_TRAJECTORY)
  {
    if (in.Track->empty())
    {
      this->Fail("the hand trajectory has no samples (AddHandSample)");
      return false;
    }
    request.hand = in.Track;
    if (this->InitialCursor[0] >= 0.0 && this->InitialCursor[1] >= 0.0)
    {
      cursor = { this->InitialCursor[0], this->InitialCursor[1] };
    }
  }

  vtouch::BuiltDevice built = vtouch::buildDevice(request);
  if (!built.device)
  {
    this->Fail(built.error);
    return false;
  }
  in.Session.pipeline().reset(); // a fresh start: exploring
  if (this->DeviceType == SIMULATED)
  {
    in.Session.pipeline().setCursor_px(cursor);
  }
  in.Pointer = built.pointer;
  vtouch::ForceSafetyParameters safety;
  safety.maxForce_N = this->MaxForce;
  in.Session.setSafetyParameters(safety);
  in.Session.setDevice(built.device);
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
  if (in.ConnectionFaultLatched)
  {
    this->Fail("Start: " + in.ConnectionMessage +
               " (ClearFault() first to trace on the skeleton kept in this process)");
    return false;
  }
  this->ApplyProperties();
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
  this->ApplyProperties();
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
  this->Internals->ConnectionFaultLatched = false;
}

void vtkVesselTouchHapticSession::ReportConnectionLost(const char* message)
{
  vtkInternals& in = *this->Internals;
  this->Stop(); // zero force first, then the device closes: nothing depends on the server now
  in.ConnectionLost = true;
  in.ConnectionFaultLatched = true;
  in.ConnectionMessage = message && *message ? message : "the connection to the server was lost";
}

int vtkVesselTouchHapticSession::GetConnectionLost()
{
  return this->Internals->ConnectionLost ? 1 : 0;
}

void vtkVesselTouchHapticSession::SetDeliveredCenterline(vtkAlgorithm* producer)
{
  vtkInternals& in = *this->Internals;
  if (producer)
  {
    in.DeliveredProducer = producer;
    this->SetInputConnection(0, producer->GetOutputPort(0));
    return;
  }
  int port = 0;
  vtkAlgorithm* current =
    this->GetNumberOfInputConnections(0) > 0 ? this->GetInputAlgorithm(0, 0, port) : nullptr;
  if (current && current == in.DeliveredProducer.GetPointer())
  {
    this->SetInputConnection(0, nullptr);
  }
  in.DeliveredProducer = nullptr;
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

// GetAgentState's VTK_SIZEHINT and the AgentState member are 23 values: the layout's size.
static_assert(vtouch::AgentFieldCount == 23, "update GetAgentState's size hint and member");

double* vtkVesselTouchHapticSession::GetAgentState()
{
  const vtouch::AgentState a = this->Internals->Session.agentState();
  double* v = this->AgentState;
  auto put2 = [v](int at, const vtouch::Vec2& p)
  {
    v[at] = p.x;
    v[at + 1] = p.y;
  };
  auto put3 = [v](int at, const vtouch::Vec3& p)
  {
    v[at] = p.x;
    v[at + 1] = p.y;
    v[at + 2] = p.z;
  };
  v[vtouch::AgentFieldTime_s] = a.time_s;
  v[vtouch::AgentFieldTick] = static_cast<double>(a.tick);
  v[vtouch::AgentFieldState] = static_cast<double>(a.state);
  v[vtouch::AgentFieldForceLaw] = static_cast<double>(a.forceLaw);
  v[vtouch::AgentFieldPath] = static_cast<double>(a.path);
  v[vtouch::AgentFieldPoint] = static_cast<double>(a.point);
  put2(vtouch::AgentFieldCursor_px, a.cursor_px);
  put3(vtouch::AgentFieldPosition_World_mm, a.position_World_mm);
  put3(vtouch::AgentFieldTangent_World, a.tangent_World);
  v[vtouch::AgentFieldDirection] = static_cast<double>(a.directionOfTravel);
  v[vtouch::AgentFieldConeRoll_rad] =
    a.coneRoll_rad; // RMF + integral of torsion (vtouch::AgentFrame)
  v[vtouch::AgentFieldZoneGain_N] = a.zoneGain_N;
  put2(vtouch::AgentFieldForce_N, a.force_N);
  put2(vtouch::AgentFieldTargetForce_N, a.targetForce_N);
  put2(vtouch::AgentFieldHand_Device_mm, a.hand_Device_mm);
  return this->AgentState;
}

const char* vtkVesselTouchHapticSession::GetAgentStateLayout()
{
  static const std::string layout = vtouch::agentStateLayoutText();
  return layout.c_str();
}

int vtkVesselTouchHapticSession::GetRealTimeScheduling()
{
  return this->Internals->Session.isRunning() && this->Internals->Session.realtimeGranted() ? 1 : 0;
}

vtkIdType vtkVesselTouchHapticSession::GetViewModelBuilds()
{
  return static_cast<vtkIdType>(this->Internals->Session.viewModelBuilds());
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

double* vtkVesselTouchHapticSession::GetDeviceCapabilities()
{
  std::fill(std::begin(this->DeviceCapabilities), std::end(this->DeviceCapabilities), 0.0);
  auto device = this->Internals->Session.device();
  if (!device || !device->isOpen())
  {
    return this->DeviceCapabilities;
  }
  // Set when the device opened and constant while it stays open: safe beside the haptic thread.
  const vtouch::DeviceCapabilities& c = device->capabilities();
  const double values[12] = { 1.0,
    static_cast<double>(c.sensedDof),
    static_cast<double>(c.actuatedDof),
    c.workspace_mm.x,
    c.workspace_mm.y,
    c.workspace_mm.z,
    c.maxContinuousForce_N,
    c.maxStiffness_N_per_m,
    c.maxUpdateRate_Hz,
    c.hasPressure ? 1.0 : 0.0,
    c.positionResolution_mm,
    static_cast<double>(c.buttonCount) };
  std::copy(values, values + 12, this->DeviceCapabilities);
  return this->DeviceCapabilities;
}

double* vtkVesselTouchHapticSession::GetDeviceCalibration()
{
  std::fill(std::begin(this->DeviceCalibration), std::end(this->DeviceCalibration), 0.0);
  auto device = this->Internals->Session.device();
  if (!device || !device->isOpen())
  {
    return this->DeviceCalibration;
  }
  // Fixed when the device opened, like its capabilities.
  const vtouch::DeviceAxisCalibration calibration = device->axisCalibration();
  this->DeviceCalibration[0] = calibration.axisCount;
  for (int i = 0; i < calibration.axisCount; ++i)
  {
    const vtouch::DeviceAxisCalibration::Axis& axis = calibration.axes[i];
    double* out = this->DeviceCalibration + 1 + 4 * i;
    out[0] = axis.rawMinimum;
    out[1] = axis.rawMaximum;
    out[2] = axis.minimum_mm;
    out[3] = axis.maximum_mm;
  }
  return this->DeviceCalibration;
}

const char* vtkVesselTouchHapticSession::GetDeviceName()
{
  auto device = this->Internals->Session.device();
  this->Internals->DeviceName =
    device && device->isOpen() ? std::string(device->capabilities().name) : std::string();
  return this->Internals->DeviceName.c_str();
}

int* vtkVesselTouchHapticSession::GetSessionStatus()
{
  vtkInternals& in = *this->Internals;
  const bool running = in.Session.isRunning();
  this->SessionStatus[0] = running ? 1 : 0;
  this->SessionStatus[1] =
    in.ConnectionFaultLatched ? CONNECTION_LOST_FAULT : static_cast<int>(in.Session.fault());
  // The log vector belongs to the haptic thread while running.
  this->SessionStatus[2] = running ? -1 : static_cast<int>(in.Session.log().size());
  this->SessionStatus[3] = running ? -1 : static_cast<int>(in.Session.droppedLogEntries());
  this->SessionStatus[4] = in.HasSkeleton ? static_cast<int>(in.Skeleton.paths.size()) : 0;
  this->SessionStatus[5] = in.HasSkeleton ? static_cast<int>(in.Skeleton.pointCount()) : 0;
  return this->SessionStatus;
}

const char* vtkVesselTouchHapticSession::GetLastErrorMessage()
{
  return this->Internals->LastError.c_str();
}

const char* vtkVesselTouchHapticSession::GetFaultMessage()
{
  vtkInternals& in = *this->Internals;
  in.FaultText = in.ConnectionFaultLatched ? in.ConnectionMessage
                                           : std::string(vtouch::toString(in.Session.fault()));
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
  for (const vtouch::HapticParameterDescriptor& d : vtouch::kHapticParameterDescriptors)
  {
    os << indent << d.name << ": " << d.get(this->Internals->Parameters) << "\n";
  }
  os << indent << "ViewportSize: " << this->ViewportSize[0] << " x " << this->ViewportSize[1]
     << "\n";
  os << indent << "Running: " << this->IsRunning() << "\n";
}

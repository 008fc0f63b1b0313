#include "vtouchHapticSession.h"

#include "vtouchHapticParameterTable.h"

#include "vtouchSafeHapticDevice.h"
#include "vtouchSimulatedDevice.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace vtouch
{

const char* toString(SessionFault fault)
{
  switch (fault)
  {
    case SessionFault::None:
      return "none";
    case SessionFault::DeviceError:
      return "device read/write failed";
    case SessionFault::NonFiniteForce:
      return "non-finite force";
    case SessionFault::WatchdogOverrun:
      return "haptic loop overrun (watchdog)";
  }
  return "unknown fault";
}

namespace
{
/// The session's filter keeps NaN guard, clamp and slew; its quiet gate is replaced by the ramp.
ForceSafetyParameters withoutEngageGate(ForceSafetyParameters p)
{
  p.engageTicks = 1;
  p.engageThreshold_N = std::numeric_limits<double>::infinity();
  return p;
}
} // namespace

HapticSession::HapticSession()
{
  this->setSafetyParameters(ForceSafetyParameters{});
  this->PublishedParameters.store(this->ControlParameters);
  this->TickParameters = this->ControlParameters;
}

HapticSession::~HapticSession()
{
  this->Loop.stop();
  this->Exchange.clear();
}

void HapticSession::setSkeleton(const QSkeleton& skeleton)
{
  std::lock_guard<std::mutex> lock(this->ControlMutex);
  this->SkeletonCopy = skeleton;
  this->HasSkeleton = true;
  this->Topology = SceneTopology::build(this->SkeletonCopy, this->SlopeWindow_mm);
  this->rebuild();
}

bool HapticSession::setCamera(const HostCamera& camera)
{
  std::lock_guard<std::mutex> lock(this->ControlMutex);
  const std::string why = camera.validate();
  if (!why.empty())
  {
    this->LastError = why;
    return false;
  }
  this->Camera = camera;
  this->HasCamera = true;
  this->rebuild();
  return true;
}

HostCamera HapticSession::camera() const
{
  std::lock_guard<std::mutex> lock(this->ControlMutex);
  return this->Camera;
}

void HapticSession::setCaptureRadius_px(double radius_px)
{
  std::lock_guard<std::mutex> lock(this->ControlMutex);
  this->Builder.setCaptureRadius_px(radius_px);
  this->rebuild();
}

double HapticSession::captureRadius_px() const
{
  std::lock_guard<std::mutex> lock(this->ControlMutex);
  return this->Builder.captureRadius_px();
}

void HapticSession::setSlopeWindow_mm(double window_mm)
{
  std::lock_guard<std::mutex> lock(this->ControlMutex);
  this->SlopeWindow_mm = std::isfinite(window_mm) ? std::clamp(window_mm, 0.0, 100.0) : 1.0;
  if (this->HasSkeleton)
  {
    this->Topology = SceneTopology::build(this->SkeletonCopy, this->SlopeWindow_mm);
    this->rebuild();
  }
}

double HapticSession::slopeWindow_mm() const
{
  std::lock_guard<std::mutex> lock(this->ControlMutex);
  return this->SlopeWindow_mm;
}

void HapticSession::rebuild()
{
  if (!this->HasSkeleton || !this->HasCamera || !this->Topology)
  {
    return;
  }
  this->Exchange.publish(
    this->Builder.build(this->Topology, this->Camera, this->Exchange.takeRecyclable()));
  this->ViewModelBuilds.fetch_add(1);
}

void HapticSession::setDevice(std::shared_ptr<HapticDevice> device)
{
  if (this->Loop.running())
  {
    this->LastError = "setDevice: stop the session first";
    return;
  }
  this->Device = std::move(device);
  this->LastDeviceState = DeviceState{};
  this->ResetSafety.store(true);
}

void HapticSession::setSafetyParameters(const ForceSafetyParameters& parameters)
{
  if (this->Loop.running())
  {
    this->LastError = "setSafetyParameters: stop the session first";
    return;
  }
  this->Safety.setParameters(withoutEngageGate(parameters));
  ForceOnsetRampParameters ramp = this->Onset.parameters();
  ramp.holdTicks = std::max(0, parameters.engageTicks);
  ramp.quietThreshold_N = parameters.engageThreshold_N;
  ramp.maxTickInterval_s = parameters.maxTickInterval_s;
  this->Onset.setParameters(ramp);
}

void HapticSession::setOnsetRampParameters(const ForceOnsetRampParameters& parameters)
{
  if (this->Loop.running())
  {
    this->LastError = "setOnsetRampParameters: stop the session first";
    return;
  }
  this->Onset.setParameters(parameters);
}

HapticParameters HapticSession::parameters() const
{
  std::lock_guard<std::mutex> lock(this->ControlMutex);
  return this->ControlParameters;
}

void HapticSession::setParameters(const HapticParameters& parameters)
{
  std::lock_guard<std::mutex> lock(this->ControlMutex);
  this->ControlParameters = parameters;
  this->ControlParameters.zoom = std::clamp(std::isfinite(parameters.zoom) ? parameters.zoom : 1.0,
    hapticParameter(HapticParameterId::Zoom).minimum,
    hapticParameter(HapticParameterId::Zoom).maximum);
  this->PublishedParameters.store(this->ControlParameters);
}

void HapticSession::setForceLaw(ForceLawId law)
{
  HapticParameters p = this->parameters();
  p.forceLaw = law;
  this->setParameters(p);
}

void HapticSession::setZoom(double r)
{
  HapticParameters p = this->parameters();
  p.zoom = r;
  this->setParameters(p);
}

void HapticSession::setForceZones(double gain_N, double zeroBelow, double saturateAbove)
{
  HapticParameters p = this->parameters();
  p.zoneGain_N = gain_N;
  p.zoneZeroBelow = zeroBelow;
  p.zoneSaturateAbove = saturateAbove;
  this->setParameters(p);
}

bool HapticSession::start(const LoopOptions& options)
{
  if (!this->Device)
  {
    this->LastError = "start: no device";
    return false;
  }
  if (!this->Device->isOpen() && this->Device->open() != DeviceStatus::Ok)
  {
    this->LastError = std::string("start: cannot open the device: ") + this->Device->lastError();
    return false;
  }
  return this->Loop.start(*this, options);
}

void HapticSession::stop()
{
  this->Loop.stop();
  this->Exchange.release(); // the reader is gone; its hazard no longer protects anything
}

SimulatedDevice* HapticSession::simulatedDevice() const
{
  if (auto* sim = dynamic_cast<SimulatedDevice*>(this->Device.get()))
  {
    return sim;
  }
  if (auto* safe = dynamic_cast<SafeHapticDevice*>(this->Device.get()))
  {
    return dynamic_cast<SimulatedDevice*>(&safe->inner());
  }
  return nullptr;
}

bool HapticSession::runOffline(double duration_s, double rate_Hz)
{
  if (this->Loop.running())
  {
    this->LastError = "runOffline: the real-time loop is running";
    return false;
  }
  SimulatedDevice* sim = this->simulatedDevice();
  if (!sim || sim->parameters().clock != SimulatedDeviceParameters::Clock::Manual)
  {
    this->LastError = "runOffline: needs a SimulatedDevice with the Manual clock";
    return false;
  }
  if (!this->Device->isOpen() && this->Device->open() != DeviceStatus::Ok)
  {
    this->LastError =
      std::string("runOffline: cannot open the device: ") + this->Device->lastError();
    return false;
  }
  if (!(rate_Hz > 0.0) || !(duration_s >= 0.0) || !std::isfinite(duration_s))
  {
    this->LastError = "runOffline: rate and duration must be positive and finite";
    return false;
  }
  const double dt = 1.0 / rate_Hz;
  const auto ticks = static_cast<std::size_t>(std::llround(duration_s * rate_Hz));
  this->Logging.store(true);
  this->Log.reserve(this->Log.size() + ticks);
  for (std::size_t k = 0; k < ticks; ++k)
  {
    this->tick(this->OfflineTime_s, dt);
    sim->advance(dt); // the plant feels the written force for one period (zero-order hold)
    this->OfflineTime_s += dt;
  }
  return true;
}

void HapticSession::clearFault()
{
  this->Fault.store(SessionFault::None);
  this->Loop.clearFault();
  this->ResetSafety.store(true);
}

void HapticSession::setLogCapacity(std::size_t entries)
{
  if (!this->Loop.running())
  {
    this->Log.reserve(entries);
  }
}

void HapticSession::clearLog()
{
  if (!this->Loop.running())
  {
    this->Log.clear();
    this->DroppedLog = 0;
  }
}

void HapticSession::latch(SessionFault fault) noexcept
{
  SessionFault expected = SessionFault::None;
  this->Fault.compare_exchange_strong(expected, fault);
}

void HapticSession::emergencyStop() noexcept
{
  this->Pipeline.zeroForce();
  this->Safety.reset();
  this->Onset.reset(); // re-engage softly after a stall or a fault
  if (this->Device)
  {
    this->Device->write(Vec3{});
  }
}

void HapticSession::tick(double time_s, double dt_s) noexcept
{
  if (this->ResetSafety.exchange(false))
  {
    this->Safety.reset();
    this->Onset.reset();
  }
  this->PublishedParameters.tryLoad(this->TickParameters); // keeps the last copy on a race
  const ViewModel* vm = this->Exchange.acquire();
  HapticDevice* dev = this->Device.get();
  if (!dev)
  {
    return;
  }
  DeviceState state = this->LastDeviceState;
  if (dev->read(state) != DeviceStatus::Ok)
  {
    dev->write(Vec3{}); // zero force first, then report
    this->Pipeline.zeroForce();
    this->latch(SessionFault::DeviceError);
    return;
  }
  this->LastDeviceState = state;

  TickInput in;
  in.device = state;
  in.capabilities = &dev->capabilities();
  in.view = vm;
  in.time_s = time_s;
  in.dt_s = dt_s;
  AgentState out = this->Pipeline.step(in, this->TickParameters);

  const bool faulted = this->Fault.load(std::memory_order_relaxed) != SessionFault::None ||
                       this->Loop.fault() != LoopFault::None;
  Vec3 command{ out.force_N.x, out.force_N.y, 0.0 };
  if (faulted)
  {
    command = {};
    this->Pipeline.zeroForce();
    this->Onset.reset(); // after clearFault() the force comes back through the ramp
  }
  command = this->Onset.apply(command, dt_s);
  SafetyFault safety = SafetyFault::None;
  Vec3 force = this->Safety.apply(command, dt_s, &safety);
  if (safety == SafetyFault::NonFiniteForce || !force.isFinite())
  {
    force = {};
    dev->write(force);
    this->latch(SessionFault::NonFiniteForce);
  }
  else if (dev->write(faulted ? Vec3{} : force) != DeviceStatus::Ok)
  {
    dev->write(Vec3{});
    this->latch(SessionFault::DeviceError);
  }
  if (faulted)
  {
    force = {};
  }
  out.force_N = { force.x, force.y };
  this->Published.store(out);

  if (this->Logging.load(std::memory_order_relaxed))
  {
    if (this->Log.size() < this->Log.capacity())
    {
      SessionLogEntry e;
      e.time_s = time_s;
      e.hand_Device_mm = out.hand_Device_mm;
      e.cursor_px = out.cursor_px;
      e.state = out.state;
      e.path = out.path;
      e.point = out.point;
      e.position_World_mm = out.position_World_mm;
      e.targetForce_N = out.targetForce_N;
      e.force_N = out.force_N;
      this->Log.push_back(e); // within the reserved capacity: no allocation
    }
    else
    {
      ++this->DroppedLog;
    }
  }
}

} // namespace vtouch

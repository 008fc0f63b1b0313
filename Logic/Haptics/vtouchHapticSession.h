// The scriptable core: skeleton + camera + device + force law + zones + zoom, run in real time on a
// HapticLoop or offline (deterministic) with a simulated device, through the SAME tick function.
#pragma once

#include "vtouchForceOnsetRamp.h"
#include "vtouchForceSafetyFilter.h"
#include "vtouchHapticDevice.h"
#include "vtouchHapticLoop.h"
#include "vtouchHapticParameters.h"
#include "vtouchHapticPipeline.h"
#include "vtouchSeqLock.h"
#include "vtouchViewModelBuilder.h"
#include "vtouchViewModelExchange.h"

#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace vtouch
{

class SimulatedDevice;

/// Why the session holds the force at zero (atomic, readable from any thread).
enum class SessionFault : std::uint8_t
{
  None = 0,
  DeviceError = 1,    ///< read() or write() failed
  NonFiniteForce = 2, ///< the pipeline produced NaN/Inf (zero was sent instead)
  WatchdogOverrun = 3 ///< the loop woke far too late (see LoopOptions::watchdog_s)
};
const char* toString(SessionFault fault);

/// One record of the session log (offline runs, or real-time runs with a log capacity).
struct SessionLogEntry
{
  double time_s = 0.0;
  Vec2 hand_Device_mm;
  Vec2 cursor_px;
  InteractionState state = InteractionState::Exploring;
  int path = -1;
  int point = -1;
  Vec3 position_World_mm;
  Vec2 targetForce_N;
  Vec2 force_N; ///< as sent to the device (after interpolation and the safety filter)
};

/// Threading: configuration calls (set*, start, stop, runOffline) from one control thread (GUI or
/// Python); agentState(), statistics() and fault() from any thread; tick() from the loop thread.
class HapticSession : public HapticTickTarget
{
public:
  HapticSession();
  ~HapticSession() override;
  HapticSession(const HapticSession&) = delete;
  HapticSession& operator=(const HapticSession&) = delete;

  // --- scene ---
  /// Copies the skeleton's geometry into a new topology and rebuilds the view model if a camera
  /// is set. The agent returns to exploring.
  void setSkeleton(const QSkeleton& skeleton);
  /// Rebuilds and publishes the view model (call on every camera change). False with a reason in
  /// lastError() when the camera is unusable.
  bool setCamera(const HostCamera& camera);
  HostCamera camera() const;
  void setCaptureRadius_px(double radius_px);
  double captureRadius_px() const;
  /// 3D arc length of the dz/dl stencil, mm (rebuilds the topology). Default 1 mm.
  void setSlopeWindow_mm(double window_mm);
  double slopeWindow_mm() const;
  /// View models built and published so far (one per camera, capture radius, stencil or skeleton
  /// change that has both a skeleton and a camera).
  std::uint64_t viewModelBuilds() const { return this->ViewModelBuilds.load(); }
  /// The newest published view model (null before skeleton + camera).
  std::shared_ptr<const ViewModel> viewModel() const { return this->Exchange.current(); }

  // --- device ---
  /// The device to drive (opened by the caller or by start()/runOffline()). Not while running.
  void setDevice(std::shared_ptr<HapticDevice> device);
  std::shared_ptr<HapticDevice> device() const { return this->Device; }
  /// Final safety stage inside the tick (NaN guard, clamp, slew). The filter's hard engage gate
  /// is replaced by the soft onset ramp: engageTicks and engageThreshold_N set the ramp's hold
  /// (zero output) and quiet threshold, maxTickInterval_s its credit per tick.
  void setSafetyParameters(const ForceSafetyParameters& parameters);
  /// Soft onset after start, clearFault() or a device change: hold at zero, then scale the force
  /// from 0 to 1 over rampTime_s (default 50 ms). Not while running.
  void setOnsetRampParameters(const ForceOnsetRampParameters& parameters);
  ForceOnsetRampParameters onsetRampParameters() const { return this->Onset.parameters(); }

  // --- parameters (published to the haptic thread without locks) ---
  HapticParameters parameters() const;
  void setParameters(const HapticParameters& parameters);
  void setForceLaw(ForceLawId law);
  ForceLawId forceLaw() const { return this->parameters().forceLaw; }
  void setZoom(double r);
  double zoom() const { return this->parameters().zoom; }
  void setForceZones(double gain_N, double zeroBelow, double saturateAbove);

  // --- real time ---
  bool start(const LoopOptions& options = LoopOptions{});
  void stop();
  bool isRunning() const { return this->Loop.running(); }
  LoopStatisticsSummary statistics() const { return this->Loop.statistics(); }
  std::string schedulerNotice() const { return this->Loop.schedulerNotice(); }
  /// True when the running loop thread got real-time scheduling (SCHED_FIFO).
  bool realtimeGranted() const { return this->Loop.realtimeGranted(); }

  // --- offline (deterministic) ---
  /// Steps tick() at `rate_Hz` for `duration_s` of simulated time, advancing the simulated device
  /// (its Manual clock) one period between ticks (zero-order hold of each written force). The
  /// device must be a SimulatedDevice, possibly inside a SafeHapticDevice. Opens it if needed.
  bool runOffline(double duration_s, double rate_Hz = 1000.0);
  /// Simulated time of the last offline tick.
  double offlineTime_s() const { return this->OfflineTime_s; }

  // --- outputs ---
  AgentState agentState() const { return this->Published.load(); }
  SessionFault fault() const
  {
    const SessionFault f = this->Fault.load();
    return (f == SessionFault::None && this->Loop.fault() == LoopFault::WatchdogOverrun)
             ? SessionFault::WatchdogOverrun
             : f;
  }
  /// Clears a latched fault; forces re-engage softly through the safety filter.
  void clearFault();
  const std::string& lastError() const { return this->LastError; }
  /// Log: records are kept while logging is on (offline runs turn it on), up to the capacity
  /// reserved before the run (no allocation in the tick; records beyond it are dropped and
  /// counted).
  void setLogging(bool on) { this->Logging.store(on); }
  void setLogCapacity(std::size_t entries);
  const std::vector<SessionLogEntry>& log() const { return this->Log; }
  std::uint64_t droppedLogEntries() const { return this->DroppedLog; }
  void clearLog();

  /// Direct access for tests/scripting when not running.
  HapticPipeline& pipeline() { return this->Pipeline; }
  /// Ticks whose force the safety filter had to clamp in magnitude (read when not running).
  std::uint64_t safetyClampedTicks() const { return this->Safety.clampedTicks(); }

  // HapticTickTarget (loop thread, or the caller of runOffline()).
  void tick(double time_s, double dt_s) noexcept override;
  void emergencyStop() noexcept override;

private:
  void rebuild();
  void latch(SessionFault fault) noexcept;
  SimulatedDevice* simulatedDevice() const;

  mutable std::mutex ControlMutex; // control plane only; never taken by tick()
  QSkeleton SkeletonCopy;
  bool HasSkeleton = false;
  std::shared_ptr<const SceneTopology> Topology;
  HostCamera Camera;
  bool HasCamera = false;
  double SlopeWindow_mm = 1.0;
  ViewModelBuilder Builder;
  ViewModelExchange Exchange;
  std::atomic<std::uint64_t> ViewModelBuilds{ 0 };
  HapticParameters ControlParameters;
  SeqLock<HapticParameters> PublishedParameters;
  SeqLock<AgentState> Published;
  std::shared_ptr<HapticDevice> Device;
  HapticLoop Loop;
  std::string LastError;

  // Haptic-thread state.
  HapticPipeline Pipeline;
  ForceOnsetRamp Onset;
  ForceSafetyFilter Safety;
  std::atomic<bool> ResetSafety{ false };
  HapticParameters TickParameters;
  DeviceState LastDeviceState;
  std::atomic<SessionFault> Fault{ SessionFault::None };
  std::atomic<bool> Logging{ false };
  std::vector<SessionLogEntry> Log;
  std::uint64_t DroppedLog = 0;
  double OfflineTime_s = 0.0;
};

} // namespace vtouch

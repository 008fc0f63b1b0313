// A simulated 2-DOF stylus (a mass with viscous damping) held by a scripted hand. The default
// device of the demo, and the plant of every closed-loop test.
#pragma once

#include "vtouchHandScript.h"
#include "vtouchHapticDevice.h"
#include "vtouchVelocityEstimator.h"

#include <array>
#include <cstdint>

namespace vtouch
{

/// Parameters of the simulated handle. Set before open(); constant while open.
struct SimulatedDeviceParameters
{
  /// Where time comes from.
  enum class Clock : std::uint8_t
  {
    /// The owner calls advance(dt); read()/write() act at the simulated time. Deterministic.
    Manual,
    /// read()/write() first advance the simulation to the steady clock's now.
    RealTime
  };

  /// Time source. Default Manual (tests, the offline session).
  Clock clock = Clock::Manual;
  /// Moving mass of handle and linkage, kg. Default 0.05 kg (a light pantograph).
  double mass_kg = 0.05;
  /// Viscous damping of the mechanism, N·s/m. Default 0.5 N·s/m.
  double damping_N_s_per_m = 0.5;
  /// Integration sub-step, s. advance() takes whole sub-steps of this size plus a last partial
  /// one, so results depend only on the sequence of dt values. Default 1e-4 s (10 kHz).
  double subStep_s = 1e-4;
  /// Largest simulated interval caught up in one real-time call, s (a stalled host must not freeze
  /// the haptic thread in a long catch-up loop). Default 0.05 s.
  double maxCatchUp_s = 0.05;
  /// Sensor latency: read() returns the sample taken this many reads earlier. Default 0, max 63.
  int latency_samples = 0;
  /// Position quantization step of the sensor, mm; 0 = none. Default 0.
  double quantization_mm = 0.0;
  /// Standard deviation of the white Gaussian sensor noise, mm; 0 = none. Default 0.
  double noiseStdDev_mm = 0.0;
  /// Seed of the sensor noise (the same seed gives the same noise). Default 1.
  std::uint64_t noiseSeed = 1;
  /// Handle position at open(), mm. Default the workspace centre (0, 0).
  Vec2 initialPosition_Device_mm;
  /// Largest force the simulated actuators produce (commanded forces saturate here), N. Default 3.
  double maxContinuousForce_N = 3.0;
  /// Largest stable stiffness at 1 kHz reported in the capabilities, N/m. Default 1000.
  double maxStiffness_N_per_m = 1000.0;
  /// Reachable box reported in the capabilities, mm. Default 160 x 120 (no z).
  Vec2 workspace_mm{ 160.0, 120.0 };
  /// Rate reported in the capabilities, Hz. Default 10000.
  double maxUpdateRate_Hz = 10000.0;
  /// Velocity estimator window, samples. Default 8.
  int velocityWindow_samples = 8;
};

/// Energy bookkeeping of the handle since open(), joules. In exact arithmetic
/// kinetic(t) - kinetic(0) = deviceWork + handWork - dampingLoss - integrationLoss; the
/// semi-implicit step makes this hold to rounding (integrationLoss is the step's own numerical
/// dissipation).
struct SimulatedEnergy
{
  double deviceWork_J = 0.0;      ///< work done by the commanded device force on the handle
  double handWork_J = 0.0;        ///< work done by the hand
  double dampingLoss_J = 0.0;     ///< dissipated by the mechanism's damping (>= 0)
  double integrationLoss_J = 0.0; ///< dissipated by the integrator (>= 0)
  double kinetic_J = 0.0;         ///< current kinetic energy of the handle
  double initialKinetic_J = 0.0;  ///< kinetic energy at open()
};

/// A 2-DOF stylus with mass and damping, pushed by the commanded device force and by a scripted
/// hand. Integration is semi-implicit Euler (damping implicit, so stiff damping stays stable) in
/// fixed sub-steps with zero-order hold of the last written force, exactly as a real handle feels a
/// force held between two updates.
///
/// Threading: like every device, read()/write()/advance() belong to one (haptic) thread.
class SimulatedDevice : public HapticDevice
{
public:
  SimulatedDevice();
  explicit SimulatedDevice(const SimulatedDeviceParameters& parameters);
  ~SimulatedDevice() override;

  /// Replaces the parameters; only while closed (returns false when open).
  bool setParameters(const SimulatedDeviceParameters& parameters);
  const SimulatedDeviceParameters& parameters() const { return this->Parameters; }

  /// Sets the hand. Only while closed (returns false when open): it allocates.
  bool setHandScript(HandScript script);

  DeviceStatus open() override;
  void close() override;
  bool isOpen() const override { return this->Open; }
  const DeviceCapabilities& capabilities() const override { return this->Capabilities; }
  DeviceStatus read(DeviceState& state) override;
  DeviceStatus write(const Vec3& force_Device_N) override;
  const char* lastError() const override { return this->LastError; }

  /// Advances the simulation by `dt_s` (Manual clock). Ignored when closed, negative or not finite.
  DeviceStatus advance(double dt_s);

  /// Simulated time since open(), s.
  double time_s() const { return this->Time_s; }
  /// True (noise-free, latency-free) handle position, mm.
  Vec2 truePosition_Device_mm() const { return this->Position_m * 1000.0; }
  /// True handle velocity, mm/s.
  Vec2 trueVelocity_Device_mm_per_s() const { return this->Velocity_m_per_s * 1000.0; }
  /// Force the actuators apply now (the last write, saturated), N.
  Vec2 appliedForce_Device_N() const { return this->Force_N; }
  /// Instantaneous power of the device force into the handle, W (positive: the device gives
  /// energy).
  double devicePower_W() const { return this->Force_N.dot(this->Velocity_m_per_s); }
  /// Energy bookkeeping since open().
  const SimulatedEnergy& energy() const { return this->Energy; }
  /// Number of writes and reads since open().
  std::uint64_t writeCount() const { return this->Writes; }
  std::uint64_t readCount() const { return this->Reads; }

private:
  static constexpr int kMaxLatency = 64;

  void step(double h_s);
  void catchUpToNow();
  double sensorNoise_mm();
  DeviceState sense();

  SimulatedDeviceParameters Parameters;
  HandScript Hand;
  DeviceCapabilities Capabilities;
  bool Open = false;
  const char* LastError = "";

  double Time_s = 0.0;
  double ClockOrigin_s = 0.0;
  Vec2 Position_m;
  Vec2 Velocity_m_per_s;
  Vec2 Force_N;
  HandSample LastHand;
  SimulatedEnergy Energy;

  std::array<DeviceState, kMaxLatency> Delay{};
  int DelayHead = 0;
  int DelayCount = 0;
  VelocityEstimator Velocity;
  std::uint64_t NoiseState = 1;
  bool HasSpareNoise = false;
  double SpareNoise = 0.0;
  std::uint64_t Writes = 0;
  std::uint64_t Reads = 0;
};

} // namespace vtouch

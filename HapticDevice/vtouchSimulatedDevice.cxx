#include "vtouchSimulatedDevice.h"

#include "vtouchSteadyClock.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>

namespace vtouch
{

namespace
{

bool valid(const SimulatedDeviceParameters& p)
{
  return p.mass_kg > 0.0 && std::isfinite(p.mass_kg) && p.damping_N_s_per_m >= 0.0 &&
         p.subStep_s > 0.0 && p.subStep_s <= 0.01 && p.maxCatchUp_s > 0.0 &&
         p.latency_samples >= 0 && p.latency_samples < 64 && p.quantization_mm >= 0.0 &&
         p.noiseStdDev_mm >= 0.0 && p.maxContinuousForce_N >= 0.0 &&
         p.initialPosition_Device_mm.isFinite();
}
} // namespace

SimulatedDevice::SimulatedDevice()
  : SimulatedDevice(SimulatedDeviceParameters{})
{
}

SimulatedDevice::SimulatedDevice(const SimulatedDeviceParameters& parameters)
  : Parameters(parameters)
{
}

SimulatedDevice::~SimulatedDevice() = default;

bool SimulatedDevice::setParameters(const SimulatedDeviceParameters& parameters)
{
  if (this->Open)
  {
    return false;
  }
  this->Parameters = parameters;
  return true;
}

bool SimulatedDevice::setHandScript(HandScript script)
{
  if (this->Open)
  {
    return false;
  }
  this->Hand = std::move(script);
  return true;
}

DeviceStatus SimulatedDevice::open()
{
  const SimulatedDeviceParameters& p = this->Parameters;
  if (!valid(p))
  {
    this->LastError = "simulated device: invalid parameters (mass, sub-step, latency < 64...)";
    return DeviceStatus::InvalidArgument;
  }
  DeviceCapabilities caps;
  std::snprintf(caps.name, sizeof(caps.name), "%s", "VesselTouch simulated stylus");
  caps.sensedDof = 2;
  caps.actuatedDof = 2;
  caps.workspace_mm = Vec3{ p.workspace_mm.x, p.workspace_mm.y, 0.0 };
  caps.maxContinuousForce_N = p.maxContinuousForce_N;
  caps.maxStiffness_N_per_m = p.maxStiffness_N_per_m;
  caps.maxUpdateRate_Hz = p.maxUpdateRate_Hz;
  caps.hasPressure = true;
  caps.buttonCount = 2;
  // The sensor's resolution: its quantization step, or its peak noise (five standard deviations,
  // exceeded about once in two million samples), or a 5 um encoder (a PenCat/Phantom-class
  // stylus) when the simulated sensor is ideal.
  const double sensed_mm = std::max(p.quantization_mm, 5.0 * p.noiseStdDev_mm);
  caps.positionResolution_mm = sensed_mm > 0.0 ? sensed_mm : 0.005;
  this->Capabilities = caps;

  this->Time_s = 0.0;
  this->ClockOrigin_s = steadyNow_s();
  this->Position_m = p.initialPosition_Device_mm * 1e-3;
  this->Velocity_m_per_s = Vec2{};
  this->Force_N = Vec2{};
  this->LastHand = HandSample{};
  this->Energy = SimulatedEnergy{};
  this->DelayHead = 0;
  this->DelayCount = 0;
  this->Velocity =
    VelocityEstimator(static_cast<std::size_t>(std::max(2, p.velocityWindow_samples)));
  this->NoiseState = p.noiseSeed ? p.noiseSeed : 0x9E3779B97F4A7C15ull;
  this->HasSpareNoise = false;
  this->Writes = 0;
  this->Reads = 0;
  this->LastError = "";
  this->Open = true;
  return DeviceStatus::Ok;
}

void SimulatedDevice::close()
{
  this->Force_N = Vec2{};
  this->Open = false;
}

DeviceStatus SimulatedDevice::advance(double dt_s)
{
  if (!this->Open)
  {
    this->LastError = "simulated device: not open";
    return DeviceStatus::NotOpen;
  }
  if (!(dt_s >= 0.0) || !std::isfinite(dt_s))
  {
    this->LastError = "simulated device: advance() needs a finite, non-negative interval";
    return DeviceStatus::InvalidArgument;
  }
  const double h = this->Parameters.subStep_s;
  double remaining = dt_s;
  // Whole sub-steps, then one partial step: the result depends only on the dt sequence.
  while (remaining >= h)
  {
    this->step(h);
    remaining -= h;
  }
  if (remaining > 1e-12)
  {
    this->step(remaining);
  }
  return DeviceStatus::Ok;
}

void SimulatedDevice::step(double h)
{
  const SimulatedDeviceParameters& p = this->Parameters;
  HandSample hand;
  if (this->Hand.trajectory)
  {
    this->Hand.trajectory(this->Time_s, hand);
  }
  const double m = p.mass_kg;
  const double b = p.damping_N_s_per_m;
  Vec2 handExplicit_N; // hand force terms that do not depend on the new velocity
  double bh = 0.0;
  if (this->Hand.drive == HandScript::Drive::Position && this->Hand.trajectory)
  {
    const double kh = this->Hand.handStiffness_N_per_m;
    bh = this->Hand.handDamping_N_s_per_m;
    const Vec2 xh_m = hand.position_Device_mm * 1e-3;
    const Vec2 vh_m_per_s = hand.velocity_Device_mm_per_s * 1e-3;
    handExplicit_N = (xh_m - this->Position_m) * kh + vh_m_per_s * bh;
  }
  else
  {
    handExplicit_N = hand.force_Device_N;
  }
  if (!handExplicit_N.isFinite())
  {
    handExplicit_N = Vec2{};
  }
  const Vec2 v0 = this->Velocity_m_per_s;
  // Semi-implicit Euler, damping implicit: m (v1 - v0) = h (F_dev + F_hand - b v1).
  const Vec2 v1 = (v0 * m + (this->Force_N + handExplicit_N) * h) * (1.0 / (m + h * (b + bh)));
  const Vec2 handForce_N = handExplicit_N - v1 * bh;
  const Vec2 dx = v1 * h;
  this->Position_m = this->Position_m + dx;
  this->Velocity_m_per_s = v1;
  this->Time_s += h;

  const Vec2 dv = v1 - v0;
  this->Energy.deviceWork_J += this->Force_N.dot(dx);
  this->Energy.handWork_J += handForce_N.dot(dx);
  this->Energy.dampingLoss_J += b * v1.dot(v1) * h;
  this->Energy.integrationLoss_J += 0.5 * m * dv.dot(dv);
  this->Energy.kinetic_J = 0.5 * m * v1.dot(v1);
  this->LastHand = hand;
}

void SimulatedDevice::catchUpToNow()
{
  if (this->Parameters.clock != SimulatedDeviceParameters::Clock::RealTime)
  {
    return;
  }
  double dt = (steadyNow_s() - this->ClockOrigin_s) - this->Time_s;
  if (dt > this->Parameters.maxCatchUp_s)
  {
    // Skip the excess: the handle freezes through a host stall instead of the tick stalling too.
    this->Time_s += dt - this->Parameters.maxCatchUp_s;
    dt = this->Parameters.maxCatchUp_s;
  }
  if (dt > 0.0)
  {
    this->advance(dt);
  }
}

double SimulatedDevice::sensorNoise_mm()
{
  if (this->HasSpareNoise)
  {
    this->HasSpareNoise = false;
    return this->SpareNoise;
  }
  // splitmix64 then Box-Muller: the same numbers on every platform for a given seed.
  auto next = [this]()
  {
    std::uint64_t z = (this->NoiseState += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    return (static_cast<double>(z >> 11) + 0.5) * (1.0 / 9007199254740992.0);
  };
  const double u1 = next();
  const double u2 = next();
  const double r = std::sqrt(-2.0 * std::log(u1));
  const double a = 2.0 * 3.14159265358979323846 * u2;
  this->SpareNoise = r * std::sin(a);
  this->HasSpareNoise = true;
  return r * std::cos(a);
}

DeviceState SimulatedDevice::sense()
{
  const SimulatedDeviceParameters& p = this->Parameters;
  DeviceState s;
  s.timestamp_s = p.clock == SimulatedDeviceParameters::Clock::RealTime
                    ? this->ClockOrigin_s + this->Time_s
                    : this->Time_s;
  Vec2 x_mm = this->Position_m * 1000.0;
  if (p.noiseStdDev_mm > 0.0)
  {
    x_mm.x += p.noiseStdDev_mm * this->sensorNoise_mm();
    x_mm.y += p.noiseStdDev_mm * this->sensorNoise_mm();
  }
  if (p.quantization_mm > 0.0)
  {
    x_mm.x = std::round(x_mm.x / p.quantization_mm) * p.quantization_mm;
    x_mm.y = std::round(x_mm.y / p.quantization_mm) * p.quantization_mm;
  }
  s.position_Device_mm = Vec3{ x_mm.x, x_mm.y, 0.0 };
  HandSample hand;
  if (this->Hand.trajectory)
  {
    this->Hand.trajectory(this->Time_s, hand);
  }
  s.pressure = std::clamp(std::isfinite(hand.pressure) ? hand.pressure : 0.0, 0.0, 1.0);
  s.buttons = hand.buttons;
  return s;
}

DeviceStatus SimulatedDevice::read(DeviceState& state)
{
  if (!this->Open)
  {
    this->LastError = "simulated device: not open";
    return DeviceStatus::NotOpen;
  }
  this->catchUpToNow();
  this->Delay[this->DelayHead] = this->sense();
  this->DelayHead = (this->DelayHead + 1) % kMaxLatency;
  this->DelayCount = std::min(this->DelayCount + 1, kMaxLatency);
  // Until the delay line has filled, the oldest sample is the best the sensor has.
  const int lag = std::min(this->Parameters.latency_samples, this->DelayCount - 1);
  DeviceState out = this->Delay[(this->DelayHead + kMaxLatency - 1 - lag) % kMaxLatency];
  this->Velocity.add(out.timestamp_s, out.position_Device_mm);
  out.velocity_Device_mm_per_s = this->Velocity.velocity_mm_per_s();
  state = out;
  ++this->Reads;
  return DeviceStatus::Ok;
}

DeviceStatus SimulatedDevice::write(const Vec3& force_Device_N)
{
  if (!this->Open)
  {
    this->LastError = "simulated device: not open";
    return DeviceStatus::NotOpen;
  }
  this->catchUpToNow();
  ++this->Writes;
  Vec2 f{ force_Device_N.x, force_Device_N.y };
  if (!f.isFinite())
  {
    this->Force_N = Vec2{};
    this->LastError = "simulated device: non-finite force (zero force applied)";
    return DeviceStatus::InvalidArgument;
  }
  // Actuators saturate in magnitude, keeping the direction, like a current-limited amplifier.
  const double magnitude = f.norm();
  const double limit = this->Parameters.maxContinuousForce_N;
  if (magnitude > limit)
  {
    f = magnitude > 0.0 ? f * (limit / magnitude) : Vec2{};
  }
  this->Force_N = f;
  return DeviceStatus::Ok;
}

} // namespace vtouch

// Per-tick force conditioning: NaN guard, engage gate, magnitude clamp and slew-rate limit.
#pragma once

#include "vtouchSafetyFault.h"
#include "vtouchVector.h"

#include <cstdint>

namespace vtouch
{

/// Parameters of the ForceSafetyFilter.
struct ForceSafetyParameters
{
  /// Largest force magnitude let through, N (direction kept). Default 3 N. SafeHapticDevice uses
  /// the smaller of this and the device's maxContinuousForce_N.
  double maxForce_N = 3.0;
  /// Largest change of the force vector per second, N/s. Default 200 N/s (0.2 N per 1 kHz tick,
  /// full scale in 15 ms: smooth for gradients, no kick after a jump in the command).
  double maxSlewRate_N_per_s = 200.0;
  /// The filter engages only after the command stayed below this magnitude, N. Default 0.05 N.
  double engageThreshold_N = 0.05;
  /// ... for this many consecutive ticks. Default 10.
  int engageTicks = 10;
  /// Longest interval the slew limit credits between two ticks, s (a stalled loop must not earn a
  /// full-scale jump). Default 0.002 s.
  double maxTickInterval_s = 0.002;
};

/// Turns a commanded force into a safe one. One instance per haptic thread; never allocates.
///
/// Order: a non-finite command gives zero at once and disengages; until engaged the output is zero;
/// the command is clamped in magnitude; the output moves toward it by at most rate * dt.
class ForceSafetyFilter
{
public:
  explicit ForceSafetyFilter(const ForceSafetyParameters& parameters = ForceSafetyParameters{});

  void setParameters(const ForceSafetyParameters& parameters) { this->Parameters = parameters; }
  const ForceSafetyParameters& parameters() const { return this->Parameters; }

  /// Disengages and sets the output to zero at once (after a fault, a reopen, a clear).
  void reset();

  /// One tick: returns the force to send. `dt_s` is the time since the previous tick.
  /// `fault` (optional) is set to NonFiniteForce when the command was NaN/Inf, else left alone.
  Vec3 apply(const Vec3& commanded_N, double dt_s, SafetyFault* fault = nullptr);

  bool engaged() const { return this->Engaged; }
  Vec3 output_N() const { return this->Output_N; }
  /// Ticks whose command was clamped in magnitude / limited in slew / rejected as non-finite.
  std::uint64_t clampedTicks() const { return this->Clamped; }
  std::uint64_t slewLimitedTicks() const { return this->SlewLimited; }
  std::uint64_t nonFiniteTicks() const { return this->NonFinite; }

private:
  ForceSafetyParameters Parameters;
  bool Engaged = false;
  int QuietTicks = 0;
  Vec3 Output_N;
  std::uint64_t Clamped = 0;
  std::uint64_t SlewLimited = 0;
  std::uint64_t NonFinite = 0;
};

} // namespace vtouch

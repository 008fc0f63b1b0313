// Soft start of the force: a rate-limited ramp-in that replaces the hard engage gate of the
// session's safety stage.
#pragma once

#include "vtouchVector.h"

namespace vtouch
{

/// Parameters of the ForceOnsetRamp.
struct ForceOnsetRampParameters
{
  /// Time for the force scale to go from 0 to 1, s. Default 0.05 s (50 ticks at 1 kHz). 0 = no
  /// ramp (full force right after the hold).
  double rampTime_s = 0.05;
  /// Ticks of zero output after a (re)start before the ramp begins. Default 10: downstream quiet
  /// gates (SafeHapticDevice's ForceSafetyFilter, engageTicks 10 by default) see a quiet command
  /// and engage, so they never hold the force at zero while the agent sits on a slope.
  int holdTicks = 10;
  /// A command that stayed below this magnitude through the hold needs no ramp: the scale jumps
  /// to 1 (the slew limit downstream still bounds the growth). Default 0.05 N.
  double quietThreshold_N = 0.05;
  /// Longest interval credited to the ramp between two ticks, s (a stalled loop must not earn a
  /// large step of the scale). Default 0.002 s.
  double maxTickInterval_s = 0.002;
};

/// Scales the commanded force by s(t): 0 during the hold, then s grows by at most
/// min(dt, maxTickInterval) / rampTime per tick up to 1. A session that starts (or re-engages
/// after a fault) while the agent already sits on a slope thus gets a smooth onset -- neither zero
/// forever (the old quiet gate) nor a step. One instance per haptic thread; never allocates.
class ForceOnsetRamp
{
public:
  explicit ForceOnsetRamp(const ForceOnsetRampParameters& parameters = ForceOnsetRampParameters{})
    : Parameters(parameters)
  {
  }

  void setParameters(const ForceOnsetRampParameters& parameters) { this->Parameters = parameters; }
  const ForceOnsetRampParameters& parameters() const { return this->Parameters; }

  /// Back to the hold with scale 0 (start, fault, clear, device change).
  void reset() noexcept;
  /// One tick: returns commanded_N * scale. `dt_s` is the time since the previous tick.
  Vec3 apply(const Vec3& commanded_N, double dt_s) noexcept;

  /// Current scale in [0, 1].
  double scale() const { return this->Scale; }
  /// True once the hold is over (the ramp runs or has finished).
  bool engaged() const { return this->HeldTicks >= this->Parameters.holdTicks; }

private:
  ForceOnsetRampParameters Parameters;
  int HeldTicks = 0;
  bool QuietThroughHold = true;
  double Scale = 0.0;
};

} // namespace vtouch

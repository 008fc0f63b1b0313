// Yi & Hayward's time-domain force interpolation (their Figure 5).
#pragma once

#include "vtouchVector.h"

namespace vtouch
{

/// A large step of the target force (a projection cusp, a branch switch, a new view) is spread
/// over several ticks: the output moves toward the target by at most maxRate * dt per tick
/// (a vector increment, its direction kept), instead of clamping the force magnitude. Small changes
/// pass through unchanged. Never allocates.
class ForceInterpolator
{
public:
  /// Largest change of the rendered force per second, N/s (> 0). Default 100 N/s: a 1 N step is
  /// spread over 10 ticks at 1 kHz, 40 at 4 kHz (the bound is per second, so rate-independent).
  double maxRate_N_per_s = 100.0;
  /// false (default): the Euclidean bound above (the increment's length <= maxRate dt).
  /// true: Figure 5 as printed: n = max(|dfx| / threshold, |dfy| / threshold, 1) rounded up,
  /// increment = df / n, with threshold = maxRate dt per axis. Same direction as the Euclidean
  /// increment, but the bound is on the larger component, so a diagonal change moves up to
  /// sqrt(2) faster than an axis-aligned one (the smoothing depends on the force's direction on
  /// the device): the reason the Euclidean bound is the default.
  bool perAxis = false;

  /// One tick: returns the force to render.
  Vec2 step(const Vec2& target_N, double dt_s);
  /// Jumps to a value (zero after a fault).
  void reset(const Vec2& value_N = Vec2{}) { this->Output = value_N; }
  Vec2 output() const { return this->Output; }
  /// True when the last step was limited.
  bool limited() const { return this->Limited; }

private:
  Vec2 Output;
  bool Limited = false;
};

} // namespace vtouch

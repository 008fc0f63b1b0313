// The zero-force zone for devices without a pressure or z input (Yi & Hayward §5.2: "a zero-force
// zone prevents any activity when the device is left unattended").
#pragma once

#include "vtouchVector.h"

namespace vtouch
{

/// A dwell gate on the handle's position. A hand holding the handle never keeps it within
/// `radius_mm` for long; a handle let go comes to rest. When the handle has stayed within
/// `radius_mm` of where it settled for `dwell_s`, the gain fades to zero over `ramp_s`; once it
/// leaves that radius the gain fades back in over `ramp_s`. It depends on time and position only,
/// not on speed: a hand moving slowly but steadily keeps the force. A handle pushed by the force
/// itself keeps moving until the force stops pushing it (a valley or an end of the vessel for the
/// slope laws), then comes to rest and is silenced.
///
/// Not thread-safe; lives in the haptic tick. Never allocates, locks or throws.
class IdleGate
{
public:
  double radius_mm = 1.0; ///< motion below this counts as resting. Default 1 mm
  double dwell_s = 1.5;   ///< rest this long silences the force; <= 0 disables. Default 1.5 s
  double ramp_s = 0.05;   ///< fade out and in, s. Default 0.05 s

  void reset() noexcept;
  /// One tick with the handle's position; returns the gain factor in [0, 1].
  double update(const Vec2& position_Device_mm, double dt_s) noexcept;
  double factor() const { return this->Factor; }
  bool idle() const { return this->Idle; }

private:
  bool HasAnchor = false;
  Vec2 Anchor;
  double Rest_s = 0.0;
  bool Idle = false;
  double Factor = 1.0;
};

} // namespace vtouch

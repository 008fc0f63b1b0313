// The built-in demonstration hand of the simulated device ("sweep"): it approaches the first point
// of a centerline path from 20 mm to the right in 0.3 s, then follows the path's screen
// projection at a constant hand speed. Used by the main job's headless run and by tests.
#pragma once

#include "vtouchHandTrack.h"
#include "vtouchHostCamera.h"
#include "vtouchQSkeleton.h"

#include <string>

namespace vtouch
{

struct SweepHandTrack
{
  HandTrack track;     ///< device mm against time s (starts at t = 0)
  Vec2 startCursor_px; ///< where the cursor must start so that hand and screen agree
  std::string error;   ///< why there is no track ("" when there is one)
  bool ok() const { return this->error.empty(); }
};

/// The sweep along `path` of `skeleton` as the `camera` projects it, at `pixelsPerDeviceMm`
/// (mapping x zoom) and `speed_mm_per_s` of hand speed (at least 1e-3 mm/s).
SweepHandTrack makeSweepHandTrack(const QSkeleton& skeleton,
  const HostCamera& camera,
  int path,
  double pixelsPerDeviceMm,
  double speed_mm_per_s);

} // namespace vtouch

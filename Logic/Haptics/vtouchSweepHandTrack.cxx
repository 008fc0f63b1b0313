#include "vtouchSweepHandTrack.h"

#include <algorithm>
#include <vector>

namespace vtouch
{

SweepHandTrack makeSweepHandTrack(const QSkeleton& skeleton,
  const HostCamera& camera,
  int path,
  double pixelsPerDeviceMm,
  double speed_mm_per_s)
{
  SweepHandTrack sweep;
  if (path < 0 || path >= static_cast<int>(skeleton.paths.size()) || !(pixelsPerDeviceMm > 0.0))
  {
    sweep.error = "the sweep needs a centerline and a valid SweepPath";
    return sweep;
  }
  std::vector<Vec2> screen;
  for (const SkeletonPoint& q : skeleton.paths[static_cast<std::size_t>(path)].points)
  {
    Vec2 s;
    if (camera.eyeToScreen(camera.worldToEye(q.position_World_mm), s))
    {
      screen.push_back(s);
    }
  }
  if (screen.size() < 2)
  {
    sweep.error = "the sweep path is not in front of the camera";
    return sweep;
  }
  // Hand mm = (screen - start) / pixelsPerDeviceMm: 20 mm to the right of the path's first point
  // at t = 0, on it at t = 0.3 s, then along the path at the hand speed.
  constexpr double kApproach_mm = 20.0;
  constexpr double kApproach_s = 0.3;
  const double speed = std::max(speed_mm_per_s, 1e-3);
  double t = kApproach_s;
  sweep.track.add(0.0, { kApproach_mm, 0.0 });
  sweep.track.add(t, { 0.0, 0.0 });
  for (std::size_t i = 1; i < screen.size(); ++i)
  {
    const double step = (screen[i] - screen[i - 1]).norm() / pixelsPerDeviceMm;
    if (step <= 1e-9)
    {
      continue;
    }
    t += step / speed;
    sweep.track.add(t, (screen[i] - screen[0]) * (1.0 / pixelsPerDeviceMm));
  }
  sweep.startCursor_px = screen[0] + Vec2{ kApproach_mm * pixelsPerDeviceMm, 0.0 };
  return sweep;
}

} // namespace vtouch

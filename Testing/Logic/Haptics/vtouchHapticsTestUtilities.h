// Small synthetic scenes for the haptics tests, built in code (no files, no randomness unless
// seeded).
#pragma once

#include "vtouchHapticParameters.h"
#include "vtouchHostCamera.h"
#include "vtouchQSkeleton.h"
#include "vtouchSceneTopology.h"
#include "vtouchViewModelBuilder.h"

#include <cmath>
#include <functional>
#include <memory>
#include <vector>

namespace vtouch
{
namespace testing
{

constexpr double kPi = 3.14159265358979323846;

/// A path sampled from r(t), t in [0, 1], with `count` points and finite-difference tangents.
inline SkeletonPath samplePath(const std::function<Vec3(double)>& r, int count)
{
  SkeletonPath path;
  for (int i = 0; i < count; ++i)
  {
    const double t = static_cast<double>(i) / (count - 1);
    const double h = 1e-6;
    Vec3 d = r(std::min(1.0, t + h)) - r(std::max(0.0, t - h));
    const double n = d.norm();
    SkeletonPoint p;
    p.position_World_mm = r(t);
    p.tangent_World = n > 0 ? d * (1.0 / n) : Vec3{ 1, 0, 0 };
    p.radius_mm = 1.0;
    path.points.push_back(p);
  }
  return path;
}

inline QSkeleton singlePath(const std::function<Vec3(double)>& r, int count)
{
  QSkeleton s;
  s.paths.push_back(samplePath(r, count));
  s.paths[0].id = 0;
  return s;
}

inline QSkeleton straightLine(const Vec3& a, const Vec3& b, double spacing_mm)
{
  const int count = std::max(2, static_cast<int>(std::ceil((b - a).norm() / spacing_mm)) + 1);
  return singlePath([a, b](double t) { return a + (b - a) * t; }, count);
}

/// Appends path `child` whose `end` joins point `parentPoint` of `parent`.
inline void join(QSkeleton& s, int child, Junction::End end, int parent, int parentPoint)
{
  Junction j;
  j.childPath = child;
  j.childEnd = end;
  j.parentPath = parent;
  j.parentPoint = parentPoint;
  const int index = static_cast<int>(s.junctions.size());
  s.junctions.push_back(j);
  if (end == Junction::End::Head)
  {
    s.paths[child].head.junction = index;
  }
  else
  {
    s.paths[child].tail.junction = index;
  }
}

/// Orthographic camera looking down -z at `focal` with `mmPerPixel` and an 800x600 viewport.
/// Depth = distance from the eye: larger world z is closer to the viewer.
inline HostCamera topCamera(const Vec3& focal, double mmPerPixel = 0.25, int w = 800, int h = 600)
{
  return makeOrthographicCamera(focal, { 0, 0, -1 }, { 0, 1, 0 }, 0.5 * h * mmPerPixel, w, h);
}

/// Builds a view model for a skeleton and camera.
inline std::shared_ptr<ViewModel> buildView(const QSkeleton& s,
  const HostCamera& cam,
  double captureRadius_px = 12.0,
  double slopeWindow_mm = 1.0)
{
  ViewModelBuilder b;
  b.setCaptureRadius_px(captureRadius_px);
  return b.build(SceneTopology::build(s, slopeWindow_mm), cam);
}

/// Distance from p to the polyline of consecutive points of every path (and junction edges).
inline double distanceToGraph_mm(const SceneTopology& topo, const Vec3& p)
{
  double best = 1e300;
  int nb[16];
  for (int g = 0; g < topo.pointCount(); ++g)
  {
    const int n = topo.neighbours(g, nb, 16);
    for (int k = 0; k < n; ++k)
    {
      const Vec3 a = topo.position_World_mm(g);
      const Vec3 ab = topo.position_World_mm(nb[k]) - a;
      const double l2 = ab.dot(ab);
      const double t = l2 > 0 ? std::clamp((p - a).dot(ab) / l2, 0.0, 1.0) : 0.0;
      best = std::min(best, (p - (a + ab * t)).norm());
    }
  }
  return best;
}

/// The paper's contact rule (Yi & Hayward §3.2: proximity alone captures), for tests whose scene
/// starts with the cursor on a vessel and that measure something else than contact (forces, onset,
/// faults). The product's default also asks for an approach and a dwell (ContactGate).
inline HapticParameters immediateContact(HapticParameters p = HapticParameters{})
{
  p.contactDwell_s = 0.0;
  p.contactApproachAtStart = false;
  return p;
}

} // namespace testing
} // namespace vtouch

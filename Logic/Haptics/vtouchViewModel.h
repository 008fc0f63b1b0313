// The view-dependent scene model the haptic thread works on: the centerline as seen by the host
// camera, plus a contact map. Built off the haptic thread by ViewModelBuilder, then immutable.
#pragma once

#include "vtouchHostCamera.h"
#include "vtouchSceneTopology.h"

#include <cstdint>
#include <memory>
#include <vector>

namespace vtouch
{

/// Conventions (all per global point index g, see SceneTopology):
/// - screen position in pixels, origin bottom-left, y up (HostCamera);
/// - depth_mm: eye-space distance along the view direction, POSITIVE AWAY from the viewer (the
///   paper's z). A vessel "rising toward the viewer" has decreasing depth;
/// - eta: unit projected tangent on the screen toward increasing point index (0,0 when undefined);
/// - dz_mm / dl_mm: depth change and screen arc length over the stencil window w (default 1 mm)
///   toward increasing index: dz = w * (-e_z . D), dl = w * |(e_x . D, e_y . D)| with D the
///   topology's tangent estimate and e_x, e_y, e_z the eye axes. dl is the screen arc length
///   converted to millimetres at the point's depth (pixels x HostCamera::mmPerPixelAt), i.e. the
///   lateral eye-space distance, so dz/dl = tan(beta) is the true slope of the vessel against the
///   screen plane, independent of zoom and window size;
/// - frameStrength: |projected unit 3D tangent| in [0,1]; 0 when the vessel runs along the view
///   direction (the local frame is degenerate there).
///
/// Only the contact map is materialized per view: the per-point quantities are O(1) functions of
/// the topology and the camera, evaluated on demand (the haptic tick reads a handful of points, so
/// computing 1 M of each on every camera change would be wasted; this keeps a 1 M-point rebuild
/// within a frame).
class ViewModel
{
public:
  int pointCount() const { return this->Topology ? this->Topology->pointCount() : 0; }
  const SceneTopology& topology() const { return *this->Topology; }
  const std::shared_ptr<const SceneTopology>& topologyPtr() const { return this->Topology; }
  const HostCamera& camera() const { return this->Camera; }
  /// Increases with every build; lets the haptic thread detect a new snapshot cheaply.
  std::uint64_t generation() const { return this->Generation; }

  Vec2 screen_px(int g) const
  {
    Vec2 s{ 0.0, 0.0 };
    if (!this->Camera.eyeToScreen(this->Camera.worldToEye(this->Topology->position_World_mm(g)), s))
    {
      s = { -1e9, -1e9 }; // behind the camera: far off screen
    }
    return s;
  }
  double depth_mm(int g) const
  {
    return -this->EyeZ.dot(this->Topology->position_World_mm(g)) - this->EyeZOffset;
  }
  Vec2 eta(int g) const;
  double dz_mm(int g) const
  {
    return -this->EyeZ.dot(this->Topology->tangentEstimate(g)) * this->Window_mm;
  }
  double dl_mm(int g) const
  {
    const Vec3& d = this->Topology->tangentEstimate(g);
    return std::hypot(this->EyeX.dot(d), this->EyeY.dot(d)) * this->Window_mm;
  }
  double frameStrength(int g) const;
  /// Millimetres (at the point's depth) per screen pixel.
  double mmPerPixel(int g) const;

  /// Contact map: global point index whose centerline pixel is nearest to pixel (x, y) within the
  /// capture radius, -1 when none or outside the viewport. O(1).
  int contactAt(int x_px, int y_px) const
  {
    if (x_px < 0 || y_px < 0 || x_px >= this->MapWidth || y_px >= this->MapHeight)
    {
      return -1;
    }
    return this->ContactMap[static_cast<std::size_t>(y_px) * this->MapWidth + x_px];
  }
  int mapWidth() const { return this->MapWidth; }
  int mapHeight() const { return this->MapHeight; }
  double captureRadius_px() const { return this->CaptureRadius_px; }

private:
  friend class ViewModelBuilder;
  void setCamera(const HostCamera& camera);

  std::shared_ptr<const SceneTopology> Topology;
  HostCamera Camera;
  Vec3 EyeX, EyeY, EyeZ; // rows of the view rotation (eye axes in world coordinates)
  double EyeZOffset = 0.0;
  double Window_mm = 1.0;
  std::uint64_t Generation = 0;
  std::vector<std::int32_t> ContactMap;
  int MapWidth = 0;
  int MapHeight = 0;
  double CaptureRadius_px = 0.0;
  double MmPerPixelOrtho = 0.0; // > 0 for an orthographic camera
};

} // namespace vtouch

// The host camera as plain numbers: what the VTK facade copies out of vtkCamera/vtkRenderer.
#pragma once

#include "vtouchVector.h"

#include <array>

namespace vtouch
{

/// A 4x4 matrix stored COLUMN-MAJOR (OpenGL order): element (row r, column c) is m[c * 4 + r].
/// vtkMatrix4x4 is row-major: the facade must transpose (vtkMatrix4x4::Transpose or copy
/// Element[r][c]).
using Mat4 = std::array<double, 16>;

Mat4 identityMatrix();
/// c = a * b (column-major).
Mat4 multiply(const Mat4& a, const Mat4& b);

/// The host camera for one view. Conventions:
/// - `view_WorldToEye` maps world millimetres to eye space (camera at the origin looking down -z,
///   y up), like vtkCamera::GetModelViewTransformMatrix().
/// - `projection_EyeToClip` maps eye space to clip space (OpenGL convention, NDC in [-1, 1]),
///   like vtkCamera::GetProjectionTransformMatrix(aspect, -1, 1).
/// - The viewport is in pixels with the origin at the BOTTOM-LEFT corner and y up (VTK/OpenGL
///   convention), so that device +x/+y (right/up) map to screen +x/+y without a flip.
struct HostCamera
{
  Mat4 view_WorldToEye = identityMatrix();
  Mat4 projection_EyeToClip = identityMatrix();
  int viewportWidth_px = 800;
  int viewportHeight_px = 600;

  /// True when the projection is orthographic (last row 0 0 0 1), as in a MIP view with
  /// parallel projection.
  bool isOrthographic() const;

  /// World point -> eye space (mm, the viewer looks down -z).
  Vec3 worldToEye(const Vec3& p_World_mm) const;
  /// Eye point -> window pixel (x right, y up) and NDC depth. Returns false behind the camera.
  bool eyeToScreen(const Vec3& p_Eye_mm, Vec2& screen_px) const;
  /// World millimetres per screen pixel at eye-space distance `distance_mm` in front of the camera
  /// (constant for an orthographic camera). Used to convert screen arc lengths to millimetres.
  double mmPerPixelAt(double distance_mm) const;

  /// "" when usable, else why not (non-finite entries, empty viewport, singular projection).
  const char* validate() const;
};

/// Helpers that build cameras the way VTK does (used by tests, benchmarks and offline sessions).
/// Right-handed look-at: eye at `position`, looking at `focalPoint`, `viewUp` projected to be
/// orthogonal to the view direction.
Mat4 lookAt(const Vec3& position, const Vec3& focalPoint, const Vec3& viewUp);
/// Orthographic projection showing [-parallelScale*aspect, +..] x [-parallelScale, +parallelScale]
/// (parallelScale in mm, half the view height, as vtkCamera::ParallelScale).
Mat4 orthographic(double parallelScale_mm, double aspect, double near_mm, double far_mm);
/// Perspective projection with vertical view angle in degrees (vtkCamera::ViewAngle).
Mat4 perspective(double viewAngle_deg, double aspect, double near_mm, double far_mm);

/// An orthographic camera looking at `focalPoint` from direction `directionOfProjection`
/// (unit vector from the camera toward the scene), fitting a view height of 2*parallelScale mm.
HostCamera makeOrthographicCamera(const Vec3& focalPoint,
  const Vec3& directionOfProjection,
  const Vec3& viewUp,
  double parallelScale_mm,
  int width_px,
  int height_px);

} // namespace vtouch

// Smoothing and differential geometry of a sampled space curve (a Q-skeleton path).
// Plain C++: used by Logic/Skeleton after tracing, and by anything that edits a path.
#pragma once

#include "vtouchQSkeleton.h"

#include <vector>

namespace vtouch
{

/// Per-point result of computeCurveGeometry().
struct CurveSample
{
  Vec3 position;          ///< smoothed position (same frame and unit as the input, mm)
  Vec3 tangent;           ///< unit tangent toward increasing index
  double curvature = 0.0; ///< 1/mm
  double torsion = 0.0;   ///< 1/mm, signed (right-handed helix > 0)
};

/// Half widths (mm of arc length) of the local fits. A derivative of order k amplifies the
/// sampling noise of a voxel curve about like 1/window^k, so each quantity gets its own window.
struct CurveGeometryWindows
{
  double position_mm = 2.0; ///< cubic fit for the smoothed position; <= 0: positions kept
  /// Curvature-adaptive widening of the position fit (mm; <= position_mm: every point uses
  /// position_mm). A point's window grows from position_mm toward this as long as nothing within
  /// it bends with a radius of curvature under window / 1.2: a cubic's error grows like
  /// window^4 / radius^3, while a wider window averages more of the noise (wall bumps) away.
  double widestPosition_mm = 0.0;
  double curvature_mm = 8.0; ///< quartic fit for tangent and curvature
  double torsion_mm = 14.0;  ///< cubic fit for torsion (third derivative)
};

/// The windows VoxelCodingSkeletonFilter smooths a Q-skeleton path with (its SmoothingWindow
/// property, mm): > 0 the cubic over +-W, the quartic over +-6 W and the cubic for torsion over
/// +-7 W; 0 (automatic) positions over 4 max(largest spacing, R), widening to 6 max(...) where the
/// path is straight, derivatives over 6 S and 7 S with S = max(2 largest spacings, R); < 0
/// positions kept (derivatives as automatic). R is the path's median radius (mm). Anything that
/// edits a path's positions after the filter (TubeSectionTracker) re-smooths it with these.
CurveGeometryWindows skeletonPathWindows(double medianRadius_mm,
  double largestSpacing_mm,
  double smoothingWindow_mm);

/// Smooths `points` and differentiates the smoothed curve.
///
/// At each point, weighted least-squares polynomials in arc length are fitted to the points within
/// the windows (tricube weights; near the ends the window slides so it keeps at least 7 points).
/// The value of the position fit is the smoothed position; the derivatives of the fits (the
/// Savitzky-Golay differences of the smoothed curve) give tangent r'/|r'|, curvature
/// |r' x r''| / |r'|^3 and torsion (r' x r'') . r''' / |r' x r''|^2. Polynomials reproduce the
/// local shape without the shrinkage of a moving average, so a helix keeps its curvature and
/// torsion. Curves of fewer than 3 points get chord tangents and zero curvature and torsion.
std::vector<CurveSample> computeCurveGeometry(const std::vector<Vec3>& points,
  const CurveGeometryWindows& windows);

/// Same, for a curve that may turn sharply at the indices in `corners` (a path that runs from a
/// vessel into a branch at a junction). No fit spans a corner: each piece between corners is
/// fitted alone, and a corner point gets the mean of the two one-sided fits that end there
/// (position, curvature and torsion; the tangent is their normalized sum). Indices out of
/// range, repeated, or at the ends are ignored.
std::vector<CurveSample> computeCurveGeometry(const std::vector<Vec3>& points,
  const CurveGeometryWindows& windows,
  std::vector<std::size_t> corners);

/// Applies computeCurveGeometry() to the positions of `path` in place (position, tangent,
/// curvature, torsion); radius and label are left alone.
void applyCurveGeometry(SkeletonPath& path,
  const CurveGeometryWindows& windows,
  const std::vector<std::size_t>& corners = {});

} // namespace vtouch

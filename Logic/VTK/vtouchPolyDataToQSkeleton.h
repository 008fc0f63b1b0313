// Centerline polylines (vtkPolyData) -> vtouch::QSkeleton, the model the haptic session reads.
#pragma once

#include "vtouchQSkeleton.h"

#include <string>

class vtkPolyData;

namespace vtouch
{

/// Converts the output of VesselCenterline (port 0) or VesselPhantom (port 1) to a QSkeleton.
///
/// - One path per polyline cell, in cell order (VesselCenterline writes path i as cell i). A cell
///   whose last point id repeats its first is a closed ring: the repeat is dropped and the tail
///   joins the path's own point 0 (a loop junction, as PhantomGenerator builds rings).
/// - Point arrays used when present: Tangent (3 components; else chord differences), Radius (mm;
///   else 0), Curvature and Torsion (1/mm; else 0), BifurcationLabel (else derived from the
///   topology: ends free -> EndPoint, junction points -> Bifurcation).
/// - Topology: the field arrays PathHeadJunction, PathTailJunction, JunctionChildPath,
///   JunctionChildEnd (0 head, 1 tail), JunctionParentPath, JunctionParentPoint when all present
///   (VesselCenterline). Without them (VesselPhantom's analytic centerline) a free path end is
///   joined to the nearest point of another path when it lies within `junctionTolerance_mm` of it
///   or within the sample spacing there (a branch may start between two samples of its parent).
class PolyDataToQSkeleton
{
public:
  /// Smallest reach of the junction inference (inputs without topology), mm: an end this close to
  /// another path's point joins it even where that path is densely sampled. Default 1e-3 mm.
  double junctionTolerance_mm = 1e-3;

  /// Fills `skeleton`; false with the reason in `error` (null or empty input, no polyline, a path
  /// of fewer than 2 points, non-finite coordinates, inconsistent topology arrays).
  bool convert(vtkPolyData* centerline, QSkeleton& skeleton, std::string& error) const;
};

} // namespace vtouch

// vtouch::QSkeleton -> centerline polylines (vtkPolyData): VesselCenterline's port 0. The
// inverse of PolyDataToQSkeleton: per point Radius, Tangent, Curvature, Torsion,
// BifurcationLabel, PathId, PointIndex; in the field data each path's head and tail junction and
// each junction's child path and end, parent path and point.
#pragma once

#include "vtouchQSkeleton.h"

class vtkPolyData;

namespace vtouch
{
/// Fills `output` (points, lines, arrays; appends to its field data) with `skeleton`.
void qSkeletonToPolyData(const QSkeleton& skeleton, vtkPolyData* output);
} // namespace vtouch

// The smoothing and differential geometry of every path of a Q-skeleton whose points are the
// coder's centres (VoxelCodingSkeletonFilter's last step, Yi & Hayward section 3.1: the skeleton
// carries position, tangent, curvature and torsion), with the windows of skeletonPathWindows:
// they scale with each path's median radius, a property of the whole path.
//
// One function for both places that smooth (issue 19 item 2): the single run's coder
// (VoxelCodingSkeletonFilter::ToWorld) and, in a distributed run, the first rank after the
// stitch. A rank sees only its part of a path that crosses pieces, so its median radius, and
// with it the window, is not the single run's (the 256^3 scaling tree: 3.74 mm over the whole
// path, 4.90 mm over one rank's part; 4 points 0.16 voxel off at a bend). The ranks therefore
// keep their centres (positions unsmoothed) and the stitched whole paths are smoothed here.
#pragma once

#include "vtouchQSkeleton.h"

namespace vtouch
{

/// The SmoothingWindow that keeps the centres: positions unsmoothed, tangents and curvature from
/// the centres (skeletonPathWindows, window < 0).
constexpr double kPositionsKeptWindow_mm = -1.0;

/// Smooths each path of `skeleton` (points: the coder's centres in the world frame, radii set,
/// junctions set) with skeletonPathWindows(its median radius, `largestSpacing_mm`,
/// `smoothingWindow_mm`), no fit spanning a point where another path joins; labels the ends
/// (EndPoint free, Bifurcation attached) and every junction's parent point, and puts each
/// attached end back on its parent point (each path is smoothed alone).
void smoothSkeletonPaths(QSkeleton& skeleton, double largestSpacing_mm, double smoothingWindow_mm);

} // namespace vtouch

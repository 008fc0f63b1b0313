// Removes the one-voxel paths the coder leaves when it codes a piece with the global SS field
// (issue 19 item 2). With VoxelCodingParameters::globalSs_mm a trace that ends where a vessel
// enters the piece stays a path of its own (TraceStage's onlyRootBandIsRoot); where that entry is
// a single voxel (a vessel grazing the piece's face in its ghost margin) the path has one voxel.
// It carries no geometry, and the distributed run's polyline reader refuses a polyline of one
// point ("a path needs at least 2"), which lost the whole piece (the 256^3 tree's rank 1 on
// 2 ranks). Project rule: such a path is dropped; a path hanging on it hangs where it hung, or,
// when it hung nowhere, ends free on its voxel (the entry: a cut end for the stitch).
#pragma once

#include "vtouchVoxelCoding.h"

namespace vtouch
{

/// Drops every path of fewer than 2 voxels and its own attachment; a child hanging on it is
/// re-attached where it hung (through chains of them), or freed with the voxel appended to its
/// end; renumbers the remaining paths and junctions. Returns the paths dropped.
int dropSinglePointPaths(RawSkeleton& skeleton);

} // namespace vtouch

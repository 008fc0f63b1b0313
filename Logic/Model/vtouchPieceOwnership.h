// Which piece of a distributed volume owns a point (issue 19, item 2).
// Plain C++: the executive's piece extents in, one owner per continuous index position out.
#pragma once

#include "vtouchVector.h"

#include <array>
#include <vector>

namespace vtouch
{

/// Point extent {x0, x1, y0, y1, z0, z1} (inclusive voxel indices), as VTK writes extents.
using VoxelExtent6 = std::array<int, 6>;

/// The world <-> index map of a volume: world = origin + direction * (index * spacing).
struct IndexFrame
{
  std::array<double, 3> origin_mm{ 0.0, 0.0, 0.0 };
  std::array<double, 3> spacing_mm{ 1.0, 1.0, 1.0 };
  std::array<double, 9> direction{ 1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0 }; ///< row major
  /// The continuous voxel index of a world point (the direction is a rotation: its transpose
  /// inverts it).
  Vec3 toIndex(const Vec3& position_World_mm) const;
};

/// Every continuous index position has exactly one owner. The executive splits the whole extent
/// by cells, so neighbouring pieces share one layer of points; the shared face belongs to the
/// upper piece: piece r owns [lo_r, hi_r) on an axis where a neighbour follows, and everything
/// beyond the whole extent's faces belongs to the piece on that face (smoothed points may lie a
/// fraction of a voxel outside the volume).
class PieceOwnership
{
public:
  PieceOwnership() = default;
  /// `pieces[r]`: piece r's extent as the executive splits it (no ghost layers); `whole`: the
  /// whole extent. Empty pieces (x1 < x0) own nothing.
  PieceOwnership(std::vector<VoxelExtent6> pieces, const VoxelExtent6& whole);

  std::size_t pieceCount() const { return pieces_.size(); }
  const VoxelExtent6& piece(std::size_t r) const { return pieces_[r]; }
  /// The owner of a continuous index position; a position in no half-open box (a split that
  /// leaves gaps) goes to the nearest box. -1 only when there is no non-empty piece.
  int owner(const Vec3& index) const;
  /// Whether `index` lies within `band` voxels of piece r's owned box (inside it included): the
  /// overlap band a piece sends beyond its shared faces (kOverlapBandVoxels).
  bool withinBand(std::size_t r, const Vec3& index, double band) const;

private:
  /// Distance from `index` to piece r's half-open box along each axis (0 inside).
  double distanceToBox(std::size_t r, const Vec3& index) const;
  std::vector<VoxelExtent6> pieces_;
  VoxelExtent6 whole_{ 0, -1, 0, -1, 0, -1 };
};

/// The ghost margin a piece is grown by on every face it shares with another piece, voxels.
///
/// Project rule (issue 19, item 2), so that every decision about an owned voxel sees what the
/// single-process run sees. The largest reach of a stage around a point, in vessel radii R:
/// - the curve geometry fits positions over up to +-6 max(1 voxel, R) of arc length
///   (Docs/CENTERLINES.md step 8) and a path cut by the piece's face ends about a radius earlier
///   (end cap rule, step 6): 6 R + 1 R + 1 voxel;
/// - spur pruning drops side branches shorter than MinimumBranchLength radii (step 6): a branch
///   leaving an owned point must be seen whole up to that length, plus the junction's own radius
///   (branch length is measured from the parent's axis): (MinimumBranchLength + 1) R;
/// - junction recentring measures arms between 1 and 2.5 junction radii (step 5);
/// - the multi-scale vesselness (when on) reaches 3 sigma_max (a Gaussian derivative kernel).
/// G = ceil(max(7 R + 1 voxel, (MinimumBranchLength + 1) R, 2.5 R) + 3 sigma_max [vesselness])
/// + 2 voxels (the 26-connected trace and the cut's midpoint), in voxels of the smallest spacing.
struct GhostMarginRule
{
  double largestRadius_mm = 0.0;        ///< the largest vessel radius the margin must cover
  double minimumBranchLength = 2.5;     ///< VesselCenterline's MinimumBranchLength (radii)
  bool useVesselness = false;           ///< VesselCenterline's UseVesselness
  double vesselnessSigmaMaximum_mm = 0; ///< VesselCenterline's VesselnessSigmaMaximum
  /// G in voxels of the smallest of `spacing_mm` (>= 2).
  int voxels(const std::array<double, 3>& spacing_mm) const;
};

/// `extent` grown by `margin` voxels on every face that is not a face of `whole` (a face shared
/// with another piece), clipped to `whole`.
VoxelExtent6 grownExtent(const VoxelExtent6& extent, const VoxelExtent6& whole, int margin);

} // namespace vtouch

// Voxel coding on a sparse vessel mask (Zhou & Toga 1999; Yi & Hayward): the algorithmic core of
// vtouch::VoxelCodingSkeletonFilter, kept free of ITK so it can be tested and profiled alone.
//
// Frames: every position here is in the *scaled index frame*, (i * sx, j * sy, k * sz) millimetres;
// the filter maps it to world coordinates with the image origin and direction.
#pragma once

#include "vtouchProgress.h"
#include "vtouchSparseVesselMask.h"

#include <array>
#include <cstdint>
#include <functional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace vtouch
{
namespace skeleton
{
class SkeletonTracer;
} // namespace skeleton

/// Thrown by VoxelCoder::run() when the progress callback asks to stop (a Cancelled: callers
/// that stop several stages catch that).
class VoxelCodingAborted : public Cancelled
{
};

struct VoxelCodingParameters
{
  std::array<double, 3> spacing_mm{ 1.0, 1.0, 1.0 }; ///< voxel size per axis, > 0
  /// The whole volume's index of the mask's voxel (0, 0, 0) (PieceInWhole::first_Whole; 0 for
  /// the single run): the centres (RawSkeletonPath::center_mm) are whole-lattice mm, (whole
  /// index) * spacing, computed as the single run computes them (skeleton::VoxelGrid).
  std::array<std::int64_t, 3> first_Whole{ 0, 0, 0 };
  /// A side branch shorter than this many local radii (of the vessel it joins) is a spur and is
  /// pruned. Loop closures shorter than this are treated as noise of one front. Dimensionless.
  double minimumBranchLength = 2.5;
  /// Components with fewer vessel voxels are ignored when no seed is given. Voxels.
  std::uint64_t minimumComponentSize = 100;
  /// Thickness of the SS bands whose connected parts are the clusters; 0 = the largest spacing. mm.
  double clusterWidth_mm = 0.0;
  bool hasSeed = false;                    ///< skeletonize only the component of the seed
  std::array<std::int64_t, 3> seedIndex{}; ///< seed voxel (root of the single-seed code)
  /// The distributed coding's SS code (vtouch::DistributedSeedCode::ss(): the single run's field
  /// on this piece, mm, indexed by the mask's rank), or null (default): the coder propagates its
  /// own. With it the coder codes the voxels with a finite value as one component, rooted where
  /// the field is lowest (the root, or where the vessels enter the piece), and ignores the rest;
  /// the seed is then not used. Not owned: it must outlive run().
  const std::vector<float>* globalSs_mm = nullptr;
  /// With globalSs_mm on several ranks: the single run's answer for the piece's face tips
  /// (vtouch::DistributedFaceTips::answer: per cluster, kNotAFaceTip, kNoTipBeyond or the rank
  /// key, DistributedTipOrder, of the true tip beyond the face, or a true tip's own), once per
  /// run (a collective: also when the field reaches no voxel of the piece), after the clusters,
  /// before the traces. TraceStage orders the tips by it, a loop's second side last.
  /// Empty (default): face tips keep their own band (the single run has none).
  std::function<std::vector<std::int64_t>(const skeleton::SkeletonTracer&)> faceTipBands;
};

struct RawSkeletonPath
{
  std::vector<std::array<std::int64_t, 3>> voxels; ///< 26-connected voxel chain, head -> tail
  std::vector<std::array<double, 3>> center_mm;    ///< centre per voxel, whole-lattice mm
  std::vector<double> radius_mm;                   ///< local radius from the BS code
  int headJunction = -1;                           ///< index into RawSkeleton::junctions
  int tailJunction = -1;
};

struct RawJunction
{
  int childPath = -1;
  bool childTail = false; ///< false: the child's head attaches; true: its tail
  int parentPath = -1;
  int parentPoint = -1;
};

/// Where a component's SS code was rooted when no seed was given (the automatic root).
struct RawComponentRoot
{
  /// The voxel(s) the SS code was first propagated from: the end cap the double propagation
  /// found (its centre voxel, or the cap's voxels when that centre is background).
  std::vector<std::array<std::int64_t, 3>> extremity;
  bool moved = false;                     ///< re-rooted at the thickest end (then `thickest`)
  std::array<std::int64_t, 3> thickest{}; ///< the thickest end's root voxel, when moved
};

struct RawSkeleton
{
  std::vector<RawSkeletonPath> paths;
  std::vector<RawJunction> junctions;
  std::uint64_t vesselVoxels = 0;
  int components = 0;        ///< components skeletonized
  int loops = 0;             ///< loop closures found
  std::size_t peakBytes = 0; ///< bookkeeping of the largest arrays (mask excluded)
  /// Per component coded from an automatic root (no seed, no global field), in scan order.
  std::vector<RawComponentRoot> roots;
  /// Wall time per stage (name, seconds), accumulated over components: for profiling.
  std::vector<std::pair<std::string, double>> stageSeconds;
};

/// The radius of the vessel at point `point` of a path: that of the largest inscribed ball
/// centred on the path that contains the point. Near an end cap or a junction the radius at the
/// point itself underestimates the vessel (a branch that leaves from a rounded end cap leaves
/// from the vessel, not from the cap's thin apex).
double nearbyRadius(const RawSkeletonPath& path, int point);

/// Appends a voxel and its centre to the path, filling the gap from the previous point with a
/// 26-connected voxel line whose positions and radii interpolate the two points. A voxel equal to
/// the last one is not appended again. Returns the point index of `voxel`.
int appendSkeletonPoint(RawSkeletonPath& path,
  const std::array<std::int64_t, 3>& voxel,
  const std::array<double, 3>& center_mm,
  double radius_mm);

/// Runs BS code, SS code, clustering, cluster graph, back-tracing, loop closing and spur pruning
/// (the stages of vtouch::skeleton, one class each: Docs/CENTERLINES.md, "Stage map").
/// Time and memory are linear in the number of vessel voxels (bucket queues, no heap, no dense
/// per-volume arrays besides the caller's 1-bit mask and its rank index).
class VoxelCoder
{
public:
  /// `mask` must be finalized. Throws std::invalid_argument on an unusable setup.
  VoxelCoder(const SparseVesselMask& mask, const VoxelCodingParameters& parameters);

  /// `progress` (may be empty) receives values in [0,1]; returning false aborts
  /// (VoxelCodingAborted) at the next check point, every 2^16 units of work (about 2^16 / 6
  /// vessel voxels). The BS code's second thread stops at its next plane and is joined first.
  RawSkeleton run(const std::function<bool(double)>& progress = {});

private:
  struct Impl;
  const SparseVesselMask& Mask;
  VoxelCodingParameters Parameters;
};

} // namespace vtouch

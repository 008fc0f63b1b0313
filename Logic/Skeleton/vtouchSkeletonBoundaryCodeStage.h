// Private to Logic/Skeleton: stage 1 of vtouch::VoxelCoder, the boundary-seeded (BS) code.
#pragma once

#include "vtouchSkeletonRunMeter.h"
#include "vtouchSkeletonVoxelGrid.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <thread>
#include <vector>

namespace vtouch
{
namespace skeleton
{

/// The BS code (Zhou & Toga 1999's boundary-seeded code; the voxel coding Yi & Hayward §3.1 build
/// their Q-skeleton with, from their ref. [32]): the exact Euclidean distance
/// (mm) from each vessel voxel centre to the nearest background voxel centre, by a separable
/// transform over the vessel runs.
///
/// Input: the grid. Output: `bs` (one float per vessel voxel, rank order), which must hold
/// VoxelCodes::kInf everywhere when start() is called. The code runs on a second thread for large
/// masks, beside the SS code, until await(); that thread never reports progress (the callback is
/// called from the caller's thread only) and stops at its next plane or row chunk when the
/// meter's stopRequested is set. The destructor joins it.
class BoundaryCodeStage
{
public:
  BoundaryCodeStage(const VoxelGrid& grid, RunMeter& meter, std::vector<float>& bs);
  ~BoundaryCodeStage();
  BoundaryCodeStage(const BoundaryCodeStage&) = delete;
  BoundaryCodeStage& operator=(const BoundaryCodeStage&) = delete;

  /// Starts the code (on a second thread from 2^17 vessel voxels; else computes it here).
  void start();
  /// Joins the thread (if any), rethrows its error and accounts its time and progress. After
  /// this, `bs` is final.
  void await();
  /// The whole-volume index of the grid's first voxel (default 0: the grid is the volume). The
  /// envelope's positions are computed from whole indices, so that a piece's code is the whole
  /// volume's bit for bit on the voxels whose nearest background it holds
  /// (vtouch::DistributedBoundaryCode; with anisotropic voxels i * spacing is not translation
  /// invariant in floating point). Call before start().
  void setOrigin(const std::array<std::int64_t, 3>& origin_Whole) { origin = origin_Whole; }
  /// The stage's largest scratch array, bytes (for RawSkeleton::peakBytes).
  std::size_t scratchBytes() const { return boundaryScratchBytes; }

private:
  /// Squared distance along x to the row's background (runs of consecutive ranks).
  void rowPass();
  /// Squared distance after the pass along `axis` (1 = y, 2 = z), from the previous passes.
  void linePass(int axis);
  /// One vessel run of a column: `count` ranks at positions first.. along an axis of `len` voxels.
  void envelopeOfRun(const std::uint32_t* ranks,
    std::uint32_t first,
    std::uint32_t count,
    std::int64_t len,
    double spacing,
    std::int64_t offset);
  void compute();
  void computeOnThread();
  /// On the BS thread: throws Cancelled when the meter's stopRequested is set.
  void boundaryCheckpoint() const;

  const VoxelGrid& grid;
  RunMeter& meter;
  std::vector<float>& bs;
  std::vector<double> siteX, siteF, envelopeFrom; // scratch of one run's lower envelope
  std::vector<std::size_t> envelopeSite;
  std::vector<std::uint32_t> planeRank, planePosition; // one plane's voxels in column order
  std::size_t boundaryScratchBytes = 0;                // the largest scratch array
  std::thread boundaryThread;
  std::exception_ptr boundaryError;
  double boundarySeconds = 0.0;
  bool boundaryQuiet = false; // no tick() from the passes (second thread)
  std::array<std::int64_t, 3> origin{ 0, 0, 0 };
};

} // namespace skeleton
} // namespace vtouch

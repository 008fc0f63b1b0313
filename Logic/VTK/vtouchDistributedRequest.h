// The centerline filter's distributed request and dispatch (issue 19, item 2): which extent a
// rank asks for, and one rank's run of the distributed extraction (its piece coded, clipped,
// gathered and stitched on the first rank, the stitched output assembled there). Moved out of
// vtkVesselTouchCenterlineFilter unchanged in behaviour; not a wrapped class.
#pragma once

#include "vtouchDistributedCenterline.h" // for VoxelExtent6
#include "vtouchCancellableCollectives.h"
#include "vtouchProgress.h"
#include "vtouchQSkeleton.h"
#include "vtouchRankTimeline.h"

#include <functional>
#include <string>
#include <vector>

class vtkFieldData;
class vtkImageData;
class vtkInformation;
class vtkInformationVector;
class vtkPolyData;

namespace vtouch
{

class DistributedRequest
{
public:
  /// Sets `in`'s request to piece `piece` of `pieces` (the executive's split) grown by
  /// `ghostMarginVoxels` on its shared faces, as one piece of that extent (a reader that splits by
  /// piece number, as ParaView's XML readers do their own way, would intersect its split with the
  /// extent). `extent`: the whole extent in, the grown extent out.
  static void requestGrownPiece(vtkInformation* in,
    int piece,
    int pieces,
    int ghostMarginVoxels,
    int extent[6]);

  /// What the filter gives the distributed run: its own single-process run and its settings.
  struct Hooks
  {
    /// Codes `piece` (an image indexed from 0) into `output`, errors deferred (not reported),
    /// its positions in the whole volume's frame `frame` (the single run's, PieceInWhole).
    std::function<void(vtkImageData* piece, const PieceInWhole& frame, vtkPolyData* output)>
      extractPiece;
    /// The intensity range the last extractPiece used, and its message ("" when it worked).
    std::function<void(double range[2], std::string& message)> lastRun;
    /// Writes a skeleton as the filter's output polydata (points, lines, arrays).
    std::function<void(const QSkeleton& skeleton, vtkPolyData* output)> fill;
    /// The ghost margin for a spacing (GhostMarginRule with the filter's parameters), voxels.
    std::function<int(const double spacing[3])> ghostMarginVoxels;
    bool automaticIntensityRange = true;
    /// This rank's pipeline stamps of the run (the request, RequestData's entry), reported with
    /// the rest of its breakdown (PieceReport).
    RankTimeline timeline;
    /// This rank's cancel request (may be empty): read at the run's cancel points (every
    /// exchange of the ranks, CancellableCollectives); a cancel throws vtouch::Cancelled out of
    /// run() on every rank at the same one.
    std::function<bool()> cancelRequested;
    /// The first rank's stitch's progress and cancel (optional; SkeletonStitcher::progress): the
    /// fraction of the stitch done at its check points, false to stop it. A stop there is taken
    /// by every rank at the cancel point after the stitch (vtouch::Cancelled out of run()).
    ProgressCallback stitchProgress;
    /// Optional, collective: runs on every rank before its piece is coded, with or without an
    /// input (the raw seeded mode's range and region across the ranks).
    std::function<void(vtkImageData* input, const VoxelExtent6& whole)> beforePiece;
    /// Optional, collective: runs on every rank right after its piece's run, with or without an
    /// input (the seeded modes' SS rounds, joined by a rank whose run stopped before its coder).
    std::function<void()> afterExtract;
    /// Optional: runs after the piece was coded (`own`, its polydata) and read into `skeleton`,
    /// on ranks with an input; may add to both.
    std::function<void(vtkImageData* input, vtkPolyData* own, QSkeleton& skeleton)> afterPiece;
    /// Optional: runs on the first rank on the stitched skeleton (not empty) before `fill`, with
    /// the volume's frame (the whole paths' smoothing of the modes whose ranks keep their
    /// centres, smoothSkeletonPaths).
    std::function<void(QSkeleton& stitched, const IndexFrame& frame)> afterStitch;
    /// Optional, collective: runs on every rank after the stitch (after afterStitch), with or
    /// without an input (the raw modes' refinement over the whole stitched paths, the other
    /// ranks serving pages of the volume). `stitched`: the first rank's stitched skeleton, which
    /// it may change (null on the other ranks, and on the first when it is empty); `report`: the
    /// first rank's output field data (null elsewhere). Returns an error, "" when none (the
    /// first rank's counts: it becomes the output's message).
    std::function<std::string(vtkImageData* input,
      const VoxelExtent6& whole,
      QSkeleton* stitched,
      vtkFieldData* report)>
      afterStitchCollective;
    /// Optional: runs on the first rank on the stitched skeleton (not empty) after
    /// afterStitchCollective, right before `fill` (where the single run's last step runs: each
    /// branch's entry into its parent, placeBranchEntries).
    std::function<void(QSkeleton& stitched)> beforeFill;
  };
  /// What the run says; the filter reports it with its own macros.
  struct Outcome
  {
    bool firstRank = false;
    std::string message;               ///< the error of the stitched result ("" when none)
    std::vector<std::string> warnings; ///< one sentence each
    double rangeUsed[2] = { 0.0, 0.0 };
  };
  /// Collective: every rank calls it once per run. `output` is the rank's output (empty on every
  /// rank but the first). Throws vtouch::Cancelled on every rank together when a rank's
  /// hooks.cancelRequested asked at a cancel point, or the first rank's stitch stopped at a check
  /// point (hooks.stitchProgress; the ranks meet at a cancel point after the stitch).
  static Outcome run(vtkInformationVector** inputVector, vtkPolyData* output, const Hooks& hooks);
};

} // namespace vtouch

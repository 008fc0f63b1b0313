// The distributed extraction's collective step (issue 19, item 2): every rank's clipped skeleton
// goes to the first rank, which stitches them (vtouch::SkeletonStitcher). Not a wrapped class:
// the filter's private helper, built into the VesselTouch::Logic module.
#pragma once

#include "vtouchPieceInWhole.h"
#include "vtouchPieceOwnership.h"
#include "vtouchQSkeleton.h"
#include "vtouchProgress.h"
#include "vtouchSkeletonStitcher.h"

#include <string>
#include <vector>

#include "vtkSmartPointer.h" // for pieceFromIndexZero

class vtkFieldData;
class vtkImageData;
class vtkMultiProcessController;

namespace vtouch
{

/// What one rank read and used, reported beside its fragments.
struct PieceReport
{
  VoxelExtent6 inputExtent{ 0, -1, 0, -1, 0, -1 }; ///< the extent the rank's input holds
  double readerBytes = -1.0; ///< the reader's ReaderVoxelBytesRead (-1: not a VesselTouch reader)
  double peakResident_kiB = 0.0; ///< the rank's peak resident set (getrusage), KiB
  double fragments = 0.0;        ///< fragments the rank kept
  double rangeLower = 0.0;       ///< the intensity range the rank's run used
  double rangeUpper = 0.0;
  double extractSeconds = 0.0; ///< the rank's own extraction on its grown piece, wall s
  // Where the rank's time goes (issue 19, item 4). Epoch stamps (vtouch::epochSeconds, 0: not
  // taken) compare between the ranks and the client on one machine.
  double requestLast_Epoch_s = 0.0;  ///< the last RequestUpdateExtent; the input updates after
  double dataEntry_Epoch_s = 0.0;    ///< RequestData's entry
  double extractStart_Epoch_s = 0.0; ///< the piece's own extraction starts
  double gatherEntry_Epoch_s = 0.0;  ///< the rank reaches the gather (the first collective after)
  double maskSeconds = 0.0; ///< of the extraction: the coder's threshold mask (CoderMaskSeconds), s
  double codeSeconds = 0.0; ///< of the extraction: the coding (CoderCoderAllSeconds), s
  double readerSeconds = -1.0; ///< the reader's RequestData for this input (-1: not reported), s
  double readerValueRangeSeconds = -1.0; ///< of which the voxel value range, s
};

class DistributedCenterline
{
public:
  /// The global controller when this run is piece `piece` of `pieces` > 1 on a controller with
  /// that many processes, this process being that piece; else null (one process: built in).
  static vtkMultiProcessController* controllerFor(int piece, int pieces);
  /// The executive's split of `whole` into `pieces` (vtkExtentTranslator, block mode, by cells:
  /// neighbouring pieces share a face layer), the split the readers use.
  static std::vector<VoxelExtent6> pieceExtents(const VoxelExtent6& whole, int pieces);
  /// This process's peak resident set, KiB.
  static double peakResidentKiB();
  /// The world <-> index map of `image`, index 0 at its origin (not at its extent's start).
  static IndexFrame indexFrame(vtkImageData* image);
  /// `piece` (an extent that need not start at 0) as an image whose extent starts at 0 and whose
  /// origin is the world position of its first voxel: the coder indexes voxels from 0 (the
  /// point and field data arrays are shared, not copied).
  static vtkSmartPointer<vtkImageData> pieceFromIndexZero(vtkImageData* piece);
  /// Where `piece` (an extent that need not start at 0, the whole volume's origin) lies in the
  /// whole volume: its extent's start and the whole origin. The coder of pieceFromIndexZero's
  /// image computes its positions in this frame, the single run's (PieceInWhole).
  static PieceInWhole pieceInWhole(vtkImageData* piece);

  struct Result
  {
    QSkeleton skeleton;              ///< the stitched skeleton (first rank only)
    StitchReport stitch;             ///< what stitching did (first rank only)
    std::vector<PieceReport> pieces; ///< every rank's report (first rank only)
    std::string error;               ///< a rank's fragments could not be read (first rank)
    double gatherSeconds = 0.0;      ///< clip, encode and gather, as the first rank waits, s
    double stitchSeconds = 0.0;      ///< decode and stitch on the first rank, s
  };
  /// Collective (every rank calls it once per run): clips `own` (this piece's skeleton, coded on
  /// its grown extent) to the piece's owned extent and its overlap band (kOverlapBandVoxels),
  /// gathers the fragments and reports on the first rank and stitches them there (one copy of
  /// what two pieces both sent kept, kCopyReachVoxels). Returns true on the first rank.
  /// `stitchProgress` (optional): the first rank's stitch's progress and cancel
  /// (SkeletonStitcher::progress); a cancel there throws vtouch::Cancelled on the first rank
  /// only, after the gathers (the caller meets the other ranks at a cancel point of its own).
  static bool gatherAndStitch(vtkMultiProcessController* controller,
    const QSkeleton& own,
    const IndexFrame& frame,
    const VoxelExtent6& whole,
    PieceReport report,
    double joinTolerance_mm,
    Result& result,
    const ProgressCallback& stitchProgress = ProgressCallback());
  /// The stitch's and the ranks' reports as field data of the stitched output (the arrays
  /// DistributedPieces, GhostMarginVoxels, Stitch* (StitchDuplicatesRemoved,
  /// StitchBandStubsDropped, StitchPointsDropped, StitchStrayPointsDropped among them), Piece*,
  /// DistributedGatherSeconds, DistributedStitchSeconds, PieceExtractSeconds and the breakdown
  /// of each rank's time, one value per rank: PieceUpstreamSeconds (the last request to
  /// RequestData: the input's update), PieceReaderSeconds, PieceReaderValueRangeSeconds,
  /// PieceBeforeExtractSeconds,
  /// PieceMaskSeconds, PieceCodeSeconds, PieceAfterExtractSeconds (the extraction's end to the
  /// gather), PieceGatherWaitSeconds (the gather waiting for the last rank); and the epoch stamps
  /// PieceRequestEpoch, PieceRequestDataEntryEpoch, PieceGatherEntryEpoch). Returns whether a rank
  /// that found vessels used another intensity range than `rangeUsed` (also
  /// PieceIntensityRangesDiffer).
  static bool addReports(vtkFieldData* fd,
    const Result& result,
    int ghostMarginVoxels,
    const double rangeUsed[2]);
};

} // namespace vtouch

// VesselCenterline: the voxel-coding Q-skeleton of a vessel volume as polylines.
//
// Input: vtkImageData with one scalar component (any type). Output: vtkPolyData with one polyline
// cell per skeleton path, points in the input's world frame (origin + direction * index * spacing),
// and point arrays Radius (mm), Tangent (3, unit), Curvature (1/mm), Torsion (1/mm),
// BifurcationLabel (0 ordinary, 1 bifurcation, 2 end point), PathId, PointIndex.
// Topology in field data (one tuple per path or per junction, int arrays):
//   PathHeadJunction, PathTailJunction  junction index at each end of each path, -1 when free;
//   JunctionChildPath, JunctionChildEnd (0 head, 1 tail), JunctionParentPath, JunctionParentPoint:
//   the end of the child path attaches to that point of the parent path (loops are junctions too).
// Field data also holds IntensityRangeUsed (lower, upper), IntensityRangeAutomatic (0/1) and
// ExtractionMessage (empty on success, else the user-facing reason).
// Bad input (a seed off the vessels, no vessel-like structure, ...): vtkErrorMacro with the reason,
// the reason in ExtractionMessage and an empty output.
//
// Background runs (the GUI's Extract): a host runs a private copy of this filter (CopyParameters)
// on another thread, on its own shallow copy of the input, with a cancel flag; then it hands the
// copy's output to the pipeline's filter (SetPrecomputedOutput with the copy's GetLastRunKey()),
// whose next run returns it without recomputing when its own input and parameters give the same
// key, and recomputes otherwise: a stale result is never used. Python's UpdatePipeline computes
// as always.
#ifndef vtkVesselTouchCenterlineFilter_h
#define vtkVesselTouchCenterlineFilter_h

#include "vtkPolyDataAlgorithm.h"
#include "vtkSmartPointer.h"           // for the precomputed output
#include "vtkVesselTouchLogicModule.h" // for export macro

#include <string> // for ExtractionMessage
#ifndef __VTK_WRAP__
#include <atomic> // for the cancel flag
#include <memory> // for the cancel socket

#include "vtouchRankTimeline.h" // for the distributed run's time stamps
namespace vtouch
{
struct CandidateRegionOutcome; // the distributed raw seeded mode's region (RequestDistributed)
class DistributedGlobalField;  // the distributed modes' global SS field (RequestDistributed)
struct PieceInWhole;           // a distributed run's piece in the whole volume (ExtractVolume)
class QSkeleton;
class RemoteCancelListener; // the first rank's cancel socket (RequestData)
}
#endif

class vtkDataArray;
class vtkImageData;

class VTKVESSELTOUCHLOGIC_EXPORT vtkVesselTouchCenterlineFilter : public vtkPolyDataAlgorithm
{
public:
  static vtkVesselTouchCenterlineFilter* New();
  vtkTypeMacro(vtkVesselTouchCenterlineFilter, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Estimate the vessel's intensity range (default on): from the seed's neighbourhood when
  /// UseSeedPoint is on, else from the whole volume (IntensityRangeEstimator), then grow the
  /// seed's network and cut its non-tubular parts off (VesselCandidateRegion) before coding. A
  /// two-valued volume (a binary mask) is thresholded at its midpoint, as before. Off: the range
  /// is [LowerThreshold, UpperThreshold] as given (the override), thresholded as before.
  vtkSetMacro(AutomaticIntensityRange, bool);
  vtkGetMacro(AutomaticIntensityRange, bool);
  vtkBooleanMacro(AutomaticIntensityRange, bool);
  /// With AutomaticIntensityRange on (default on): correct the volume's smooth multiplicative
  /// shading before the range (vtouch::ShadingField; only where the fitted gain spans at least
  /// 1.1, else the volume is used as it is). Field data ShadingCorrected (0/1), ShadingGainSpan
  /// (lowest, highest gain relative to the seed) and ShadingMessage say what it did.
  vtkSetMacro(CorrectShading, bool);
  vtkGetMacro(CorrectShading, bool);
  vtkBooleanMacro(CorrectShading, bool);
  /// The range the last run used (also field data "IntensityRangeUsed"), and why the last run
  /// gave an empty output (also field data "ExtractionMessage"; empty on success).
  vtkGetVector2Macro(IntensityRangeUsed, double);
  const char* GetExtractionMessage() const { return this->ExtractionMessage.c_str(); }

  /// With AutomaticIntensityRange off, the vessel is where the scalar lies in
  /// [LowerThreshold, UpperThreshold] (defaults 0.5 and 1e300: a binary mask works as is).
  vtkSetMacro(LowerThreshold, double);
  vtkGetMacro(LowerThreshold, double);
  vtkSetMacro(UpperThreshold, double);
  vtkGetMacro(UpperThreshold, double);

  /// World point (mm) choosing the vessel network and the root of the code (used when
  /// UseSeedPoint is on; default off: every component of at least MinimumComponentSize voxels).
  vtkSetVector3Macro(SeedPoint, double);
  vtkGetVector3Macro(SeedPoint, double);
  vtkSetMacro(UseSeedPoint, bool);
  vtkGetMacro(UseSeedPoint, bool);
  vtkBooleanMacro(UseSeedPoint, bool);

  /// Smallest component skeletonized without a seed, voxels (default 100).
  vtkSetMacro(MinimumComponentSize, int);
  vtkGetMacro(MinimumComponentSize, int);
  /// Side branches shorter than this many local radii are pruned (default 2.5).
  vtkSetMacro(MinimumBranchLength, double);
  vtkGetMacro(MinimumBranchLength, double);
  /// Position smoothing half window, mm (0 = automatic, negative = none; default 0).
  vtkSetMacro(SmoothingWindow, double);
  vtkGetMacro(SmoothingWindow, double);
  /// Code a mask downsampled by this integer factor per axis (block maximum), then re-centre every
  /// point on the full-resolution mask: faster by about F^3, same output frame and voxel paths.
  /// 0 = automatic (full resolution for small masks or thin vessels), 1 = full resolution.
  /// Default 0.
  vtkSetMacro(DownsampleFactor, int);
  vtkGetMacro(DownsampleFactor, int);
  /// The factor the last successful run coded at (the automatic choice when DownsampleFactor is
  /// 0), also in the output's field data as "DownsampleFactorUsed"; 0 before a run.
  vtkGetMacro(DownsampleFactorUsed, int);

  /// Multi-scale Hessian vesselness pre-filter for raw intensity volumes (default off), its
  /// smallest and largest scale in mm (1, 4), number of scales (4) and relative threshold (0.05).
  vtkSetMacro(UseVesselness, bool);
  vtkGetMacro(UseVesselness, bool);
  vtkBooleanMacro(UseVesselness, bool);
  vtkSetMacro(VesselnessSigmaMinimum, double);
  vtkGetMacro(VesselnessSigmaMinimum, double);
  vtkSetMacro(VesselnessSigmaMaximum, double);
  vtkGetMacro(VesselnessSigmaMaximum, double);
  vtkSetMacro(VesselnessNumberOfScales, int);
  vtkGetMacro(VesselnessNumberOfScales, int);
  vtkSetMacro(VesselnessThreshold, double);
  vtkGetMacro(VesselnessThreshold, double);

  /// On a parallel pvserver (MPI), who codes the volume (issue 19 item 2; Docs/CLIENT-SERVER.md,
  /// "Distributed extraction"). Not used built in.
  /// - DistributedExtractionOff (0): the first rank codes the whole volume (the single run's
  ///   result exactly; no memory scaling).
  /// - DistributedExtractionOn (1): each rank codes its own piece grown by the ghost margin, sends
  ///   its owned points and an overlap band, and the first rank stitches the pieces (the memory per
  ///   rank falls with the ranks), in every mode.
  /// - DistributedExtractionAutomatic (2, the default since 27 Nov): On where the distributed run
  ///   codes with the single run's SS field from the single run's root (a thresholded or binary
  ///   mask and the raw mode, with or without a seed, at full resolution; see
  ///   DistributesExactly), Off elsewhere (an explicit DownsampleFactor > 1; vesselness), where
  ///   only the first rank gives the single run's network (project rule: the default never
  ///   trades the single run's network for memory). Measured: the single run's topology on every
  ///   volume measured, up to the 1024 x 1024 x 512 scaling tree (Docs/CLIENT-SERVER.md,
  ///   "Automatic").
  enum
  {
    DistributedExtractionOff = 0,
    DistributedExtractionOn = 1,
    DistributedExtractionAutomatic = 2
  };
  vtkSetClampMacro(DistributedExtraction,
    int,
    DistributedExtractionOff,
    DistributedExtractionAutomatic);
  vtkGetMacro(DistributedExtraction, int);
  /// Whether the current settings are a mode the distributed run codes with the single run's field
  /// (what DistributedExtractionAutomatic distributes).
  bool DistributesExactly() const;
  /// Distributed extraction (pvserver under MPI, issue 19 item 2): the largest vessel radius, mm,
  /// the ghost margin around each rank's piece must cover (vtouch::GhostMarginRule). 0 (default)
  /// = automatic: 10 voxels of the largest spacing. Not used by a one-process run.
  vtkSetMacro(LargestVesselRadius, double);
  vtkGetMacro(LargestVesselRadius, double);
  /// The ghost margin, voxels, for an input of this spacing (the rule with these parameters).
  int GetGhostMarginVoxels(const double spacing[3]) const;

  /// Copies every parameter above and the input array selection of `other` (not its input).
  void CopyParameters(vtkVesselTouchCenterlineFilter* other);
  /// The last run's key: the input's scalars (the array and its modification time), the input's
  /// geometry and every parameter. Empty before a run and after an input error.
  const char* GetLastRunKey() const { return this->LastRunKey.c_str(); }
  /// `output` (a run of a copy of this filter, whose GetLastRunKey() was `runKey`) is what the
  /// next run returns if its key is `runKey`; that run consumes it. Null forgets it.
  void SetPrecomputedOutput(vtkPolyData* output, const char* runKey);
  /// Whether the last run returned a precomputed output instead of computing: a background run's
  /// (SetPrecomputedOutput) or the output a cancelled run kept from the run before it, when the
  /// parameters are back to that run's (project rule: after a Cancel on a pvserver the panel
  /// restores them, and every rank returns its kept piece of the output at once).
  vtkGetMacro(LastRunPrecomputed, bool);
  /// Whether the last run was cancelled (the cancel flag or AbortExecute): an empty output with
  /// ExtractionMessage "Cancelled.".
  vtkGetMacro(LastRunCancelled, bool);
  /// A cancel from the client on a pvserver (issue 19 item 1, issue 16 item 6): when not empty,
  /// every rank opens a socket for the run (vtouch::RemoteCancelListener), the first names its
  /// port in the progress text ("VesselCenterline: cancel port <port>") and, when a connection
  /// sends this token (one line), tells the others' sockets; every rank stops. The client chooses
  /// the token (a random string per proxy: vesseltouch.remote_cancel). Default empty: no socket.
  void SetRemoteCancelToken(const char* token)
  {
    const std::string t = token ? token : "";
    if (t != this->RemoteCancelToken)
    {
      this->RemoteCancelToken = t;
      this->Modified();
    }
  }
  const char* GetRemoteCancelToken() const { return this->RemoteCancelToken.c_str(); }
  /// The port the last run's cancel socket listened on (0: none; an informational property).
  vtkGetMacro(RemoteCancelPort, int);
#ifndef __VTK_WRAP__
  /// A flag another thread sets to stop the run at its next check point (the stages check it
  /// every few milliseconds of work). The caller keeps it alive while the filter runs; null
  /// (default): none. AbortExecute, set on this filter's thread, stops it too.
  void SetCancelFlag(const std::atomic<bool>* flag)
  {
    this->CancelFlag = flag;
  }
#endif

protected:
  vtkVesselTouchCenterlineFilter();
  ~vtkVesselTouchCenterlineFilter() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  /// In a parallel pipeline (pvserver under MPI) each rank asks for its own piece (the
  /// executive's split) grown by the ghost margin on every face shared with another piece; its
  /// skeleton is clipped to the piece and the pieces are stitched on the first rank
  /// (RequestDistributed). In the raw seeded mode (AutomaticIntensityRange with UseSeedPoint) the
  /// ranks estimate the range and grow the region together (vtouch::DistributedRawRegion).
  int RequestUpdateExtent(vtkInformation* request,
    vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;
  int RequestData(vtkInformation* request,
    vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;

private:
  vtkVesselTouchCenterlineFilter(const vtkVesselTouchCenterlineFilter&) = delete;
  void operator=(const vtkVesselTouchCenterlineFilter&) = delete;

  /// The single-process extraction of `input` into `output` (the whole run of a one-process
  /// pipeline, one piece's run of a distributed one: `pieceInWhole` is then where the piece lies
  /// in the whole volume, and the coder computes its positions in the whole volume's frame).
  int ExtractVolume(vtkInformationVector** inputVector,
    vtkImageData* input,
    vtkPolyData* output,
    const vtouch::PieceInWhole* pieceInWhole = nullptr);
  /// One rank's part of the distributed extraction: its piece, clipped, gathered and stitched on
  /// the first rank (the others output nothing: the delivery's ReductionFilter appends).
  int RequestDistributed(vtkInformationVector** inputVector, vtkPolyData* output);
#ifndef __VTK_WRAP__
  /// The distributed raw seeded mode on the seed's rank: codes `rest` (the parts of the network
  /// that reach the seed only outside this piece) and appends its paths to `skeleton`.
  void AddRestOfRegion(vtkInformationVector** inputVector,
    vtkImageData* input,
    const vtouch::CandidateRegionOutcome& rest,
    vtouch::QSkeleton& skeleton);
  /// The network's last step, on the whole network (the single run's, or the first rank's
  /// stitched one): each branch's entry into its parent on the branch's own axis
  /// (vtouch::placeBranchEntries), unless the positions are kept (a negative SmoothingWindow).
  void PlaceBranchEntries(vtouch::QSkeleton& skeleton) const;
#endif
  /// Whether this run is piece `piece` of a distributed extraction over `pieces` ranks.
  bool Distributed(int piece, int pieces) const;
  /// vtkErrorMacro, unless a distributed piece's run defers its errors to the stitched result.
  void Complain(const std::string& message);
  std::string RunKey(vtkImageData* input, vtkDataArray* scalars) const;
  /// Whether the run is to stop (cancel flag, AbortExecute, or the client's remote cancel).
  bool CancelRequested();
  /// RequestData's run (RequestData opens the first rank's cancel socket around it).
  int ExecuteRequest(vtkInformationVector** inputVector, vtkInformationVector* outputVector);
  /// Opens the first rank's cancel socket when RemoteCancelToken is set and names its port in
  /// the progress text (a socket that cannot open: a warning, the run goes on uncancellable).
  void OpenRemoteCancel();
  /// Closes it and clears the progress text.
  void CloseRemoteCancel();
  /// Collective (distributed runs with a token): the ranks' cancel sockets to the first rank,
  /// which tells them when it hears the client (RemoteCancelListener::forwardTo).
  void ShareRemoteCancelPorts();
  /// Returns the precomputed output in `output` when `key` is its key (and forgets it).
  bool UsePrecomputed(const std::string& key, vtkPolyData* output);
  /// `output` becomes `from` (a shallow copy), with the members a run sets read from its field
  /// data (the range used, the message, the downsample factor).
  void RestoreOutput(vtkPolyData* from, vtkPolyData* output);
  /// This rank's key of the request (RunKey of its input), "" when the input has no scalars.
  std::string RequestKey(vtkInformationVector** inputVector);

  bool AutomaticIntensityRange = true;
  double IntensityRangeUsed[2] = { 0.0, 0.0 };
  std::string ExtractionMessage;
  double LowerThreshold = 0.5;
  double UpperThreshold = 1e300;
  double SeedPoint[3] = { 0.0, 0.0, 0.0 };
  bool UseSeedPoint = false;
  bool CorrectShading = true;
  int MinimumComponentSize = 100;
  double MinimumBranchLength = 2.5;
  double SmoothingWindow = 0.0;
  int DownsampleFactor = 0;
  int DownsampleFactorUsed = 0;
  bool UseVesselness = false;
  double VesselnessSigmaMinimum = 1.0;
  double VesselnessSigmaMaximum = 4.0;
  int VesselnessNumberOfScales = 4;
  double VesselnessThreshold = 0.05;
  double LargestVesselRadius = 0.0;
  int DistributedExtraction = DistributedExtractionAutomatic;
  bool QuietErrors = false;
  std::string LastRunKey;
  vtkSmartPointer<vtkPolyData> PrecomputedOutput;
  std::string PrecomputedKey;
  bool LastRunPrecomputed = false;
  bool LastRunCancelled = false;
  /// This rank's output of its last run that completed, and that run's key (RequestKey): after a
  /// cancelled run, a run with that key returns it at once (project rule, Docs/CLIENT-SERVER.md
  /// "Cancel on a pvserver": the panel restores the previous parameters after a remote cancel).
  vtkSmartPointer<vtkPolyData> CompletedOutput;
  std::string CompletedRunKey;
  std::string RemoteCancelToken;
  int RemoteCancelPort = 0;
#ifndef __VTK_WRAP__
  const std::atomic<bool>* CancelFlag = nullptr;
  /// The first rank's cancel socket while a run with a RemoteCancelToken runs (else null).
  std::unique_ptr<vtouch::RemoteCancelListener> RemoteCancel;
  /// Set by RequestDistributed in the raw seeded mode while ExtractVolume runs on the piece: the
  /// candidate region the ranks computed together, used instead of the piece's own.
  const vtouch::CandidateRegionOutcome* DistributedRegion = nullptr;
  /// Set by RequestDistributed in the raw modes while the run uses the piece: the piece's
  /// scalars corrected by the ranks' common shading field (vtouch::DistributedShading), read
  /// instead of the input's array; null when there is no shading to correct.
  vtkSmartPointer<vtkDataArray> DistributedShadedScalars;
  /// Set by RequestDistributed (the seeded modes, and the unseeded thresholded or binary mask)
  /// while ExtractVolume runs on the piece: the global SS field across the ranks, which the
  /// coder codes with (its hook).
  vtouch::DistributedGlobalField* DistributedField = nullptr;
  /// Set by RequestDistributed in the modes coded with the global field (thresholded, binary
  /// or raw) while ExtractVolume runs on the piece: the coder keeps its centres (positions
  /// unsmoothed) and the first rank smooths the stitched whole paths (smoothSkeletonPaths),
  /// whose median radius sets the windows: a rank sees only its part of a path.
  bool DeferPathSmoothing = false;
  /// Set by RequestDistributed in the raw modes coded with the global field while ExtractVolume
  /// runs on the piece: the piece skips the raw path's refinement (RawSkeletonRefinement); the
  /// first rank runs it on the whole stitched paths (vtouch::DistributedWholePathRefinement).
  bool DeferRawRefinement = false;
  /// Set by RequestDistributed while ExtractVolume runs on the piece: the piece's paths keep
  /// their coded entries into their parents; the first rank places them on the stitched whole
  /// network (PlaceBranchEntries, the single run's last step).
  bool DeferBranchEntries = false;
  /// The distributed run's pipeline stamps on this rank (issue 19 item 4: where the time goes).
  vtouch::RankTimeline DistributedTimeline;
#endif
};

#endif

// VesselCandidateRegion: the candidate vessel mask the centerline extraction codes, to preview
// over the MIP before extracting.
//
// Input: vtkImageData with one scalar component. Output: vtkImageData on the input's grid with one
// unsigned char point array "CandidateVessel" (1 vessel, 0 not): with AutomaticIntensityRange on
// (default) the seed's network (or, without a seed, every region in range) in the estimated range
// with its non-tubular parts cut off (vtouch::VesselCandidateRegion, the same code
// VesselCenterline runs); off: the voxels in [LowerThreshold, UpperThreshold] connected to the
// seed. Field data: IntensityRangeUsed (lower, upper), IntensityRangeAutomatic (0/1),
// ExtractionMessage (empty on success, else the user-facing reason; the mask is then all 0).
// The GUI's Preview runs a private instance on another thread with a cancel flag.
#ifndef vtkVesselTouchCandidateRegionFilter_h
#define vtkVesselTouchCandidateRegionFilter_h

#include "vtkImageAlgorithm.h"
#include "vtkVesselTouchLogicModule.h" // for export macro

#include <string> // for ExtractionMessage
#ifndef __VTK_WRAP__
#include <atomic> // for the cancel flag
#endif

class VTKVESSELTOUCHLOGIC_EXPORT vtkVesselTouchCandidateRegionFilter : public vtkImageAlgorithm
{
public:
  static vtkVesselTouchCandidateRegionFilter* New();
  vtkTypeMacro(vtkVesselTouchCandidateRegionFilter, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// As vtkVesselTouchCenterlineFilter's properties of the same names.
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
  vtkSetMacro(LowerThreshold, double);
  vtkGetMacro(LowerThreshold, double);
  vtkSetMacro(UpperThreshold, double);
  vtkGetMacro(UpperThreshold, double);
  vtkSetVector3Macro(SeedPoint, double);
  vtkGetVector3Macro(SeedPoint, double);
  vtkSetMacro(UseSeedPoint, bool);
  vtkGetMacro(UseSeedPoint, bool);
  vtkBooleanMacro(UseSeedPoint, bool);

  vtkGetVector2Macro(IntensityRangeUsed, double);
  const char* GetExtractionMessage() const { return this->ExtractionMessage.c_str(); }
  /// Whether the last run was cancelled: an all-0 mask with ExtractionMessage "Cancelled.".
  vtkGetMacro(LastRunCancelled, bool);
#ifndef __VTK_WRAP__
  /// As vtkVesselTouchCenterlineFilter::SetCancelFlag.
  void SetCancelFlag(const std::atomic<bool>* flag)
  {
    this->CancelFlag = flag;
  }
#endif

protected:
  vtkVesselTouchCandidateRegionFilter();
  ~vtkVesselTouchCandidateRegionFilter() override = default;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestInformation(vtkInformation* request,
    vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;
  int RequestData(vtkInformation* request,
    vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;

private:
  vtkVesselTouchCandidateRegionFilter(const vtkVesselTouchCandidateRegionFilter&) = delete;
  void operator=(const vtkVesselTouchCandidateRegionFilter&) = delete;

  bool AutomaticIntensityRange = true;
  double LowerThreshold = 0.5;
  double UpperThreshold = 1e300;
  double SeedPoint[3] = { 0.0, 0.0, 0.0 };
  bool UseSeedPoint = false;
  bool CorrectShading = true;
  double IntensityRangeUsed[2] = { 0.0, 0.0 };
  std::string ExtractionMessage;
  bool LastRunCancelled = false;
#ifndef __VTK_WRAP__
  const std::atomic<bool>* CancelFlag = nullptr;
#endif
};

#endif

// Voxel-coding Q-skeleton of a vessel network (Zhou & Toga 1999; Yi & Hayward), as an ITK filter.
//
// Input: a 3D scalar volume. The vessel is where the value lies in [LowerThreshold, UpperThreshold]
// (a binary mask works with the defaults), optionally restricted to voxels of strong multi-scale
// Hessian vesselness, and to the connected network of SeedPoint when one is set (seeded region
// growing). Output: a vtouch::QSkeleton in the world frame of the volume (origin + direction *
// (index * spacing)), one 26-connected voxel path per branch before smoothing, with radius,
// tangent, curvature, torsion, labels and junctions (loop closures included).
//
// Memory grows with vessel voxels: a 1-bit mask with a rank index (1.5 bits per volume voxel) and
// about 17 bytes per vessel voxel for the codes. The optional vesselness pre-filter is the
// exception: it needs dense float images over the volume.
#pragma once

#include "vtouchPieceInWhole.h"
#include "vtouchQSkeletonObject.h"
#include "vtouchVoxelCoding.h"

#include <itkImage.h>
#include <itkProcessObject.h>

#include <functional>
#include <limits>
#include <memory>
#include <utility>
#include <vector>

namespace vtouch
{

template<typename TInputImage>
class VoxelCodingSkeletonFilter : public itk::ProcessObject
{
public:
  ITK_DISALLOW_COPY_AND_MOVE(VoxelCodingSkeletonFilter);

  using Self = VoxelCodingSkeletonFilter;
  using Superclass = itk::ProcessObject;
  using Pointer = itk::SmartPointer<Self>;
  using ConstPointer = itk::SmartPointer<const Self>;

  itkNewMacro(Self);
  itkTypeMacro(VoxelCodingSkeletonFilter, ProcessObject);

  using InputImageType = TInputImage;
  using PixelType = typename InputImageType::PixelType;
  using PointType = typename InputImageType::PointType;
  using IndexType = typename InputImageType::IndexType;
  static constexpr unsigned int ImageDimension = InputImageType::ImageDimension;
  static_assert(ImageDimension == 3, "VoxelCodingSkeletonFilter needs a 3D image");
  static_assert(std::is_arithmetic<PixelType>::value,
    "VoxelCodingSkeletonFilter needs scalar pixels");

  void SetInput(const InputImageType* image);
  const InputImageType* GetInput() const;

  /// The Q-skeleton (world frame, mm). Valid after Update().
  QSkeletonObject* GetOutput();
  const QSkeleton& GetSkeleton() const;
  /// The voxel paths before smoothing, in the scaled index frame (index * spacing, mm).
  const RawSkeleton& GetRawSkeleton() const { return this->m_RawSkeleton; }

  /// Lowest value that counts as vessel (inclusive). Default 0.5: a 0/1 or 0/255 mask works as is.
  itkSetMacro(LowerThreshold, double);
  itkGetConstMacro(LowerThreshold, double);
  /// Highest value that counts as vessel (inclusive). Default: the largest double.
  itkSetMacro(UpperThreshold, double);
  itkGetConstMacro(UpperThreshold, double);

  /// World point (mm) inside the vessel network to extract; it is also the root of the single-seed
  /// code. Setting it turns UseSeedPoint on. Without a seed every connected component of at least
  /// MinimumComponentSize voxels is skeletonized from an automatic root at one of its extremities.
  virtual void SetSeedPoint(const PointType& p);
  itkGetConstReferenceMacro(SeedPoint, PointType);
  itkSetMacro(UseSeedPoint, bool);
  itkGetConstMacro(UseSeedPoint, bool);
  itkBooleanMacro(UseSeedPoint);

  /// Components smaller than this are ignored when no seed is set. Voxels. Default 100.
  itkSetMacro(MinimumComponentSize, unsigned long);
  itkGetConstMacro(MinimumComponentSize, unsigned long);
  /// Side branches shorter than this many local radii of the vessel they join are spurs and are
  /// pruned. Dimensionless, >= 0. Default 2.5.
  itkSetMacro(MinimumBranchLength, double);
  itkGetConstMacro(MinimumBranchLength, double);
  /// Half width W (mm of arc length) of the local cubic fit that smooths the positions; tangent and
  /// curvature use a quartic fit over 6 W and torsion a cubic fit over 7 W (higher derivatives
  /// need more support). 0 = automatic: positions over 4 max(1 voxel, R) (two diameters),
  /// derivatives over 6 S and 7 S, with R the median radius of the path and
  /// S = max(2 voxels, R). No fit spans a point where another path joins (a corner where the
  /// trace turns into a branch). Negative = positions left at the center-adjusted voxel positions
  /// (derivatives as automatic). Default 0.
  itkSetMacro(SmoothingWindow, double);
  itkGetConstMacro(SmoothingWindow, double);
  /// Thickness (mm) of the single-seed code bands whose connected parts form the clusters.
  /// 0 = automatic (the largest voxel side). Default 0.
  itkSetMacro(ClusterWidth, double);
  itkGetConstMacro(ClusterWidth, double);
  /// Code a coarser mask, then refine on the input's: each block of F x F x F voxels is vessel
  /// when any of its voxels is (block maximum); the voxel coding runs on these blocks (time and
  /// code memory fall by about F^3) and CoarseSkeletonRefiner re-centres every point on the
  /// full-resolution cross-section, measures its radius there and rebuilds 26-connected paths of
  /// input voxels. Thin vessels (radius below ~2 F voxels) lose topology first.
  /// 0 = automatic (AutomaticDownsampling): full resolution for masks under 2^18 vessel voxels,
  /// else the largest F <= 4 that keeps 4 coarse voxels in the typical radius, falling back to
  /// full resolution when a coded branch is thinner than 2 coarse voxels. 1 = full resolution.
  /// Integer in [0, 64], default 0.
  itkSetMacro(DownsampleFactor, unsigned int);
  itkGetConstMacro(DownsampleFactor, unsigned int);

  /// Multiply the threshold mask by a multi-scale Hessian vesselness test (Frangi-type measure,
  /// bright tubes) for raw intensity volumes. Default off.
  itkSetMacro(UseVesselness, bool);
  itkGetConstMacro(UseVesselness, bool);
  itkBooleanMacro(UseVesselness);
  /// Smallest and largest Gaussian scale of the vesselness measure, mm. Defaults 1 and 4.
  itkSetMacro(VesselnessSigmaMinimum, double);
  itkGetConstMacro(VesselnessSigmaMinimum, double);
  itkSetMacro(VesselnessSigmaMaximum, double);
  itkGetConstMacro(VesselnessSigmaMaximum, double);
  /// Number of scales between the two (logarithmic steps). Default 4.
  itkSetMacro(VesselnessNumberOfScales, unsigned int);
  itkGetConstMacro(VesselnessNumberOfScales, unsigned int);
  /// A voxel is vessel only if its vesselness is at least this fraction of the volume's maximum
  /// vesselness. Dimensionless in [0, 1]. Default 0.05.
  itkSetMacro(VesselnessThreshold, double);
  itkGetConstMacro(VesselnessThreshold, double);

  /// A vessel mask computed beforehand (VesselCandidateRegion: the raw-angiogram path) on the
  /// input's grid: when set, it replaces the threshold (and vesselness) mask; the input still
  /// gives the geometry. Null (default): the mask is thresholded from the input.
  void SetVesselMask(std::shared_ptr<const SparseVesselMask> mask)
  {
    this->m_VesselMask = std::move(mask);
    this->Modified();
  }

  /// The distributed seeded modes' global SS code (issue 19 item 2; vtouch::SeededDistributedCoding
  /// on the pvserver's ranks): when set, the filter calls it once with the final mask (after the
  /// threshold or the vessel mask; it may clear voxels it cannot code exactly) and codes that mask
  /// at full resolution with the returned field (VoxelCodingParameters::globalSs_mm) instead of
  /// propagating its own from a root; the seed point is then not used (the field's root is the
  /// seed). A throw (std::exception) becomes the filter's exception. Empty (default): the single
  /// run.
  using GlobalSeedCodeFunction = std::function<std::vector<float>(SparseVesselMask& mask)>;
  void SetGlobalSeedCode(GlobalSeedCodeFunction function)
  {
    this->m_GlobalSeedCode = std::move(function);
    this->Modified();
  }
  /// With GlobalSeedCode on several ranks: the single run's answer for the piece's face tips
  /// (VoxelCodingParameters::faceTipBands; vtouch::DistributedFaceTips), a collective the coder
  /// calls once per run after its clusters. Empty (default): face tips keep their own band.
  using GlobalFaceTipsFunction =
    std::function<std::vector<std::int64_t>(const skeleton::SkeletonTracer& tracer)>;
  void SetGlobalFaceTips(GlobalFaceTipsFunction function)
  {
    this->m_GlobalFaceTips = std::move(function);
    this->Modified();
  }
  /// A distributed run's piece (the input, its index 0 at its first voxel): where it lies in the
  /// whole volume. Coded at full resolution, the centres and the world positions are then
  /// computed in the whole volume's frame, the single run's operations on the single run's
  /// numbers (PieceInWhole; issue 19 item 2). Departure: coded on blocks (an effective factor
  /// > 1) they stay in the piece's frame (the blocks are the piece's, not the whole volume's, so
  /// the run departs from the single run anyway). Not called (default): the single run.
  void SetPieceInWhole(const PieceInWhole& frame)
  {
    this->m_PieceInWhole = frame;
    this->m_HasPieceInWhole = true;
    this->Modified();
  }
  /// Number of vessel voxels of the last run (input resolution), and the bytes used by the masks
  /// and the codes.
  itkGetConstMacro(NumberOfVesselVoxels, unsigned long long);
  /// The factor the last run coded at (DownsampleFactor, or the automatic choice) and the number
  /// of vessel voxels it coded.
  itkGetConstMacro(EffectiveDownsampleFactor, unsigned int);
  itkGetConstMacro(NumberOfCodedVoxels, unsigned long long);
  itkGetConstMacro(CodeMemoryBytes, unsigned long long);

protected:
  VoxelCodingSkeletonFilter();
  ~VoxelCodingSkeletonFilter() override = default;

  void VerifyPreconditions() ITKv5_CONST override;
  void GenerateData() override;
  void PrintSelf(std::ostream& os, itk::Indent indent) const override;
  itk::DataObject::Pointer MakeOutput(DataObjectPointerArraySizeType idx) override;
  using Superclass::MakeOutput;

private:
  SparseVesselMask BuildMask();
  /// A check point between stages: reports `progress` (observers may set AbortGenerateData on
  /// it) and throws itk::ProcessAborted when the run is to stop.
  void CheckAbort(float progress);
  IndexType SeedIndex(const SparseVesselMask& mask) const;
  /// GenerateData with GlobalSeedCode set: the rounds on the final mask, then its coding.
  void GenerateFromGlobalSeedCode(SparseVesselMask& mask, double maskSeconds);
  /// The last stages of both: the empty-skeleton check, the world frame and its geometry.
  void FinishOutput();
  QSkeleton ToWorld(const RawSkeleton& raw) const;
  /// Voxel coding of `mask`, whose voxels are blocks of `factor`^3 input voxels; `seed` (input
  /// voxel index) or nullptr.
  /// `globalSs_mm`: the field to code with (GlobalSeedCode), or nullptr.
  RawSkeleton Code(const SparseVesselMask& mask,
    unsigned int factor,
    const IndexType* seed,
    const std::vector<float>* globalSs_mm = nullptr);

  double m_LowerThreshold{ 0.5 };
  double m_UpperThreshold{ std::numeric_limits<double>::max() };
  PointType m_SeedPoint{};
  bool m_UseSeedPoint{ false };
  unsigned long m_MinimumComponentSize{ 100 };
  double m_MinimumBranchLength{ 2.5 };
  double m_SmoothingWindow{ 0.0 };
  double m_ClusterWidth{ 0.0 };
  unsigned int m_DownsampleFactor{ 0 };
  bool m_UseVesselness{ false };
  double m_VesselnessSigmaMinimum{ 1.0 };
  double m_VesselnessSigmaMaximum{ 4.0 };
  unsigned int m_VesselnessNumberOfScales{ 4 };
  double m_VesselnessThreshold{ 0.05 };
  unsigned long long m_NumberOfVesselVoxels{ 0 };
  unsigned long long m_NumberOfCodedVoxels{ 0 };
  unsigned int m_EffectiveDownsampleFactor{ 1 };
  unsigned long long m_CodeMemoryBytes{ 0 };
  RawSkeleton m_RawSkeleton;
  std::shared_ptr<const SparseVesselMask> m_VesselMask;
  GlobalSeedCodeFunction m_GlobalSeedCode;
  GlobalFaceTipsFunction m_GlobalFaceTips;
  PieceInWhole m_PieceInWhole;
  bool m_HasPieceInWhole{ false };
  /// The last Code() computed its centres in the whole volume's frame (m_PieceInWhole).
  bool m_CodedInWholeFrame{ false };
  /// The mask's share of the run's progress (the vesselness, when on, takes half the run).
  float m_MaskProgressShare{ 0.05F };
};

} // namespace vtouch

#include "vtouchVoxelCodingSkeletonFilter.hxx"

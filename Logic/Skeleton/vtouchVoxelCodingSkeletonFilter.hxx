#pragma once

#include "vtouchVoxelCodingSkeletonFilter.h"

#include "vtouchAutomaticDownsampling.h"
#include "vtouchCoarseSkeletonRefiner.h"
#include "vtouchCurveGeometry.h"
#include "vtouchSeedVoxel.h"
#include "vtouchSinglePointPaths.h"
#include "vtouchSkeletonPathSmoothing.h"

#include <itkCommand.h>
#include <itkHessianToObjectnessMeasureImageFilter.h>
#include <itkMultiScaleHessianBasedMeasureImageFilter.h>
#include <itkSymmetricSecondRankTensor.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>
#include <thread>
#include <type_traits>

namespace vtouch
{

template<typename TInputImage>
VoxelCodingSkeletonFilter<TInputImage>::VoxelCodingSkeletonFilter()
{
  this->SetNumberOfRequiredInputs(1);
  this->SetNumberOfRequiredOutputs(1);
  this->SetNthOutput(0, this->MakeOutput(0));
  this->m_SeedPoint.Fill(0.0);
}

template<typename TInputImage>
void VoxelCodingSkeletonFilter<TInputImage>::SetInput(const InputImageType* image)
{
  this->SetNthInput(0, const_cast<InputImageType*>(image));
}

template<typename TInputImage>
auto VoxelCodingSkeletonFilter<TInputImage>::GetInput() const -> const InputImageType*
{
  return itkDynamicCastInDebugMode<const InputImageType*>(this->GetPrimaryInput());
}

template<typename TInputImage>
QSkeletonObject* VoxelCodingSkeletonFilter<TInputImage>::GetOutput()
{
  return static_cast<QSkeletonObject*>(this->GetPrimaryOutput());
}

template<typename TInputImage>
const QSkeleton& VoxelCodingSkeletonFilter<TInputImage>::GetSkeleton() const
{
  return static_cast<const QSkeletonObject*>(this->GetPrimaryOutput())->Get();
}

template<typename TInputImage>
itk::DataObject::Pointer VoxelCodingSkeletonFilter<TInputImage>::MakeOutput(
  DataObjectPointerArraySizeType)
{
  return QSkeletonObject::New().GetPointer();
}

template<typename TInputImage>
void VoxelCodingSkeletonFilter<TInputImage>::SetSeedPoint(const PointType& p)
{
  if (this->m_SeedPoint != p || !this->m_UseSeedPoint)
  {
    this->m_SeedPoint = p;
    this->m_UseSeedPoint = true;
    this->Modified();
  }
}

template<typename TInputImage>
void VoxelCodingSkeletonFilter<TInputImage>::VerifyPreconditions() ITKv5_CONST
{
  Superclass::VerifyPreconditions();
  const double lo = this->m_LowerThreshold;
  const double hi = this->m_UpperThreshold;
  if (std::isnan(lo) || std::isnan(hi) || lo > hi)
  {
    itkExceptionMacro("LowerThreshold (" << lo << ") must not exceed UpperThreshold (" << hi
                                         << ") and neither may be NaN");
  }
  if (!std::isfinite(this->m_MinimumBranchLength) || this->m_MinimumBranchLength < 0.0 ||
      this->m_MinimumBranchLength > 1000.0)
  {
    itkExceptionMacro(
      "MinimumBranchLength must be in [0, 1000] local radii, got " << this->m_MinimumBranchLength);
  }
  if (!std::isfinite(this->m_SmoothingWindow) || !std::isfinite(this->m_ClusterWidth) ||
      this->m_ClusterWidth < 0.0)
  {
    itkExceptionMacro("SmoothingWindow must be finite and ClusterWidth finite and >= 0");
  }
  if (this->m_UseVesselness &&
      (!(this->m_VesselnessSigmaMinimum > 0.0) ||
        !(this->m_VesselnessSigmaMaximum >= this->m_VesselnessSigmaMinimum) ||
        !std::isfinite(this->m_VesselnessSigmaMaximum) || this->m_VesselnessNumberOfScales < 1 ||
        !(this->m_VesselnessThreshold >= 0.0 && this->m_VesselnessThreshold <= 1.0)))
  {
    itkExceptionMacro("Vesselness needs 0 < SigmaMinimum <= SigmaMaximum (mm), at least one "
                      "scale and a threshold in [0, 1]");
  }
  if (this->m_DownsampleFactor > 64)
  {
    itkExceptionMacro("DownsampleFactor must be 0 (automatic) or an integer in [1, 64], got "
                      << this->m_DownsampleFactor);
  }
  const InputImageType* input = this->GetInput();
  const auto size = input->GetLargestPossibleRegion().GetSize();
  for (unsigned int a = 0; a < ImageDimension; ++a)
  {
    if (size[a] < 1 || !(input->GetSpacing()[a] > 0.0) || !std::isfinite(input->GetSpacing()[a]))
    {
      itkExceptionMacro("the volume must have at least one voxel per axis and positive spacing");
    }
  }
  if (this->m_UseSeedPoint)
  {
    for (unsigned int a = 0; a < ImageDimension; ++a)
    {
      if (!std::isfinite(this->m_SeedPoint[a]))
      {
        itkExceptionMacro("SeedPoint is not finite: " << this->m_SeedPoint);
      }
    }
    IndexType index;
    if (!input->TransformPhysicalPointToIndex(this->m_SeedPoint, index))
    {
      itkExceptionMacro("SeedPoint " << this->m_SeedPoint << " is outside the volume");
    }
  }
}

template<typename TInputImage>
void VoxelCodingSkeletonFilter<TInputImage>::CheckAbort(float progress)
{
  this->UpdateProgress(progress);
  if (this->GetAbortGenerateData())
  {
    itk::ProcessAborted e(__FILE__, __LINE__);
    e.SetLocation(ITK_LOCATION);
    e.SetDescription("VoxelCodingSkeletonFilter aborted");
    throw e;
  }
}

template<typename TInputImage>
SparseVesselMask VoxelCodingSkeletonFilter<TInputImage>::BuildMask()
{
  const InputImageType* input = this->GetInput();
  const auto size = input->GetLargestPossibleRegion().GetSize();
  if (input->GetBufferedRegion() != input->GetLargestPossibleRegion())
  {
    itkExceptionMacro("the whole volume must be buffered");
  }
  if (this->m_VesselMask)
  {
    const auto& d = this->m_VesselMask->dims();
    if (d[0] != static_cast<std::int64_t>(size[0]) || d[1] != static_cast<std::int64_t>(size[1]) ||
        d[2] != static_cast<std::int64_t>(size[2]))
    {
      itkExceptionMacro("the vessel mask's grid differs from the input's");
    }
    if (this->m_VesselMask->vesselCount() == 0)
    {
      itkExceptionMacro("the vessel mask is empty");
    }
    return *this->m_VesselMask;
  }
  // One streaming pass over the volume.
  const std::array<std::int64_t, 3> fine{ static_cast<std::int64_t>(size[0]),
    static_cast<std::int64_t>(size[1]),
    static_cast<std::int64_t>(size[2]) };
  SparseVesselMask mask(fine);
  const PixelType* voxels = input->GetBufferPointer();
  const std::uint64_t n = static_cast<std::uint64_t>(fine[0] * fine[1] * fine[2]);

  using RealImageType = itk::Image<float, 3>;
  typename RealImageType::Pointer vesselness;
  float vesselnessCut = 0.0F;
  if (this->m_UseVesselness)
  {
    using HessianPixelType = itk::SymmetricSecondRankTensor<double, 3>;
    using HessianImageType = itk::Image<HessianPixelType, 3>;
    using ObjectnessType =
      itk::HessianToObjectnessMeasureImageFilter<HessianImageType, RealImageType>;
    using MultiScaleType = itk::
      MultiScaleHessianBasedMeasureImageFilter<InputImageType, HessianImageType, RealImageType>;
    auto objectness = ObjectnessType::New();
    objectness->SetObjectDimension(1);
    objectness->SetBrightObject(true);
    auto multiScale = MultiScaleType::New();
    multiScale->SetInput(input);
    multiScale->SetHessianToMeasureFilter(objectness);
    multiScale->SetSigmaMinimum(this->m_VesselnessSigmaMinimum);
    multiScale->SetSigmaMaximum(this->m_VesselnessSigmaMaximum);
    multiScale->SetNumberOfSigmaSteps(this->m_VesselnessNumberOfScales);
    multiScale->SetSigmaStepMethodToLogarithmic();
    multiScale->GenerateScalesOutputOff();
    multiScale->GenerateHessianOutputOff();
    // Its progress is this filter's mask share, and an abort of this filter aborts it (ITK's
    // own check points: its mini-pipeline's filters stop at their next progress report).
    auto relay = itk::CStyleCommand::New();
    struct Relay
    {
      Self* self;
      itk::ProcessObject* inner;
    } context{ this, multiScale.GetPointer() };
    relay->SetClientData(&context);
    relay->SetCallback(
      [](itk::Object*, const itk::EventObject&, void* data)
      {
        auto* c = static_cast<Relay*>(data);
        c->self->UpdateProgress(c->self->m_MaskProgressShare * c->inner->GetProgress());
        if (c->self->GetAbortGenerateData())
        {
          c->inner->SetAbortGenerateData(true);
        }
      });
    multiScale->AddObserver(itk::ProgressEvent(), relay);
    multiScale->Update();
    vesselness = multiScale->GetOutput();
    const float* v = vesselness->GetBufferPointer();
    const float vmax = *std::max_element(v, v + n);
    vesselnessCut = static_cast<float>(this->m_VesselnessThreshold) * vmax;
  }
  const float* vness = vesselness ? vesselness->GetBufferPointer() : nullptr;
  // Each 64-voxel word of the mask is built in a register, branch-free; the two halves of the
  // volume on two threads for large volumes (the threshold pass streams the whole volume and is
  // memory bound). A non-finite voxel is only flagged here and located afterwards.
  const double lower = this->m_LowerThreshold;
  const double upper = this->m_UpperThreshold;
  const auto thresholdWords = [&](std::uint64_t wordBegin, std::uint64_t wordEnd)
  {
    bool finite = true;
    for (std::uint64_t w = wordBegin; w < wordEnd; ++w)
    {
      const std::uint64_t first = w * 64;
      const std::uint64_t last = std::min(first + 64, n);
      std::uint64_t bits = 0;
      for (std::uint64_t i = first; i < last; ++i)
      {
        const double value = static_cast<double>(voxels[i]);
        if constexpr (std::is_floating_point<PixelType>::value)
        {
          finite &= std::isfinite(value);
        }
        const bool vessel =
          (value >= lower) & (value <= upper) & (!vness || vness[i] >= vesselnessCut);
        bits |= static_cast<std::uint64_t>(vessel) << (i - first);
      }
      mask.setWord(w, bits);
    }
    return finite;
  };
  const std::uint64_t words = (n + 63) / 64;
  constexpr std::uint64_t kThreadFromVoxels = std::uint64_t{ 1 } << 22;
  bool finite = true;
  if (n >= kThreadFromVoxels)
  {
    bool secondFinite = true;
    std::thread second([&] { secondFinite = thresholdWords(words / 2, words); });
    finite = thresholdWords(0, words / 2);
    second.join();
    finite = finite && secondFinite;
  }
  else
  {
    finite = thresholdWords(0, words);
  }
  if (!finite)
  {
    for (std::uint64_t i = 0; i < n; ++i)
    {
      if (!std::isfinite(static_cast<double>(voxels[i])))
      {
        itkExceptionMacro("the volume holds a NaN or infinite voxel (linear index " << i << ")");
      }
    }
  }
  mask.finalize();
  if (mask.vesselCount() == 0)
  {
    itkExceptionMacro("no voxel lies in [" << this->m_LowerThreshold << ", "
                                           << this->m_UpperThreshold
                                           << "]: the vessel mask is empty");
  }
  if (mask.vesselCount() == mask.voxelCount())
  {
    itkExceptionMacro("every voxel lies in [" << this->m_LowerThreshold << ", "
                                              << this->m_UpperThreshold
                                              << "]: an all-vessel mask has no centerline");
  }
  return mask;
}

template<typename TInputImage>
auto VoxelCodingSkeletonFilter<TInputImage>::SeedIndex(const SparseVesselMask& mask) const
  -> IndexType
{
  const InputImageType* input = this->GetInput();
  IndexType index;
  if (!input->TransformPhysicalPointToIndex(this->m_SeedPoint, index))
  {
    itkExceptionMacro("SeedPoint " << this->m_SeedPoint << " is outside the volume");
  }
  // A click may land a voxel off the vessel: the nearest vessel voxel of the 3x3x3 block.
  const std::array<std::int64_t, 3> near =
    nearestVesselVoxel(mask, { index[0], index[1], index[2] });
  const IndexType found{ { near[0], near[1], near[2] } };
  if (near[0] < 0)
  {
    itkExceptionMacro("SeedPoint " << this->m_SeedPoint << " (voxel " << index
                                   << ") is not inside any vessel: its value is outside ["
                                   << this->m_LowerThreshold << ", " << this->m_UpperThreshold
                                   << "]");
  }
  return found;
}

template<typename TInputImage>
QSkeleton VoxelCodingSkeletonFilter<TInputImage>::ToWorld(const RawSkeleton& raw) const
{
  const InputImageType* input = this->GetInput();
  // A piece coded in the whole volume's frame: its centres are whole-lattice mm, so the world
  // position is the whole origin plus them, the single run's sum (SetPieceInWhole).
  std::array<double, 3> origin{
    input->GetOrigin()[0], input->GetOrigin()[1], input->GetOrigin()[2]
  };
  if (this->m_CodedInWholeFrame)
  {
    origin = this->m_PieceInWhole.wholeOrigin_World_mm;
  }
  const auto& dir = input->GetDirection();
  double maxSpacing = 0.0;
  for (unsigned int a = 0; a < 3; ++a)
  {
    maxSpacing = std::max(maxSpacing, static_cast<double>(input->GetSpacing()[a]));
  }
  QSkeleton s;
  s.paths.resize(raw.paths.size());
  for (std::size_t p = 0; p < raw.paths.size(); ++p)
  {
    const RawSkeletonPath& rp = raw.paths[p];
    SkeletonPath& path = s.paths[p];
    path.id = static_cast<int>(p);
    path.head.junction = rp.headJunction;
    path.tail.junction = rp.tailJunction;
    path.points.resize(rp.voxels.size());
    for (std::size_t i = 0; i < rp.voxels.size(); ++i)
    {
      const std::array<double, 3>& c = rp.center_mm[i];
      double w[3];
      for (unsigned int r = 0; r < 3; ++r)
      {
        w[r] = origin[r] + dir[r][0] * c[0] + dir[r][1] * c[1] + dir[r][2] * c[2];
      }
      path.points[i].position_World_mm = Vec3{ w[0], w[1], w[2] };
      path.points[i].radius_mm = rp.radius_mm[i];
    }
  }
  for (const RawJunction& rj : raw.junctions)
  {
    Junction j;
    j.childPath = rj.childPath;
    j.childEnd = rj.childTail ? Junction::End::Tail : Junction::End::Head;
    j.parentPath = rj.parentPath;
    j.parentPoint = rj.parentPoint;
    s.junctions.push_back(j);
  }
  // The centres smoothed path by path (one function with the distributed run's first rank,
  // which smooths the stitched whole paths: smoothSkeletonPaths).
  smoothSkeletonPaths(s, maxSpacing, this->m_SmoothingWindow);
  return s;
}

template<typename TInputImage>
RawSkeleton VoxelCodingSkeletonFilter<TInputImage>::Code(const SparseVesselMask& mask,
  unsigned int factor,
  const IndexType* seed,
  const std::vector<float>* globalSs_mm)
{
  this->m_NumberOfCodedVoxels = mask.vesselCount();
  VoxelCodingParameters par;
  const auto& spacing = this->GetInput()->GetSpacing();
  const double f = static_cast<double>(factor);
  par.spacing_mm = { f * spacing[0], f * spacing[1], f * spacing[2] };
  // Blocks are the piece's, not the whole volume's: coded on blocks the piece keeps its frame.
  this->m_CodedInWholeFrame = this->m_HasPieceInWhole && factor == 1;
  if (this->m_CodedInWholeFrame)
  {
    par.first_Whole = this->m_PieceInWhole.first_Whole;
  }
  par.minimumBranchLength = this->m_MinimumBranchLength;
  // The component size is counted in input voxels.
  par.minimumComponentSize =
    std::max<unsigned long>(1, this->m_MinimumComponentSize / (factor * factor * factor));
  par.clusterWidth_mm = this->m_ClusterWidth;
  par.globalSs_mm = globalSs_mm;
  if (globalSs_mm)
  {
    par.faceTipBands = this->m_GlobalFaceTips;
  }
  if (seed)
  {
    // The block of a vessel voxel is vessel (block maximum).
    par.hasSeed = true;
    par.seedIndex = { (*seed)[0] / factor, (*seed)[1] / factor, (*seed)[2] / factor };
  }
  try
  {
    VoxelCoder coder(mask, par);
    return coder.run(
      [this](double p)
      {
        const float share = this->m_MaskProgressShare;
        this->UpdateProgress(share + (0.95F - share) * static_cast<float>(p));
        return !this->GetAbortGenerateData();
      });
  }
  catch (const VoxelCodingAborted&)
  {
    itk::ProcessAborted e(__FILE__, __LINE__);
    e.SetLocation(ITK_LOCATION);
    e.SetDescription("VoxelCodingSkeletonFilter aborted");
    throw e;
  }
  catch (const std::invalid_argument& e)
  {
    itkExceptionMacro(<< e.what());
  }
  catch (const std::bad_alloc&)
  {
    itkExceptionMacro(
      "not enough memory for the voxel codes of " << mask.vesselCount() << " vessel voxels");
  }
}

template<typename TInputImage>
void VoxelCodingSkeletonFilter<TInputImage>::GenerateFromGlobalSeedCode(SparseVesselMask& mask,
  double maskSeconds)
{
  // Full resolution (project rule, issue 19 item 2): the field is the whole volume's, computed on
  // the input's grid across the ranks; a coarse block grid would start at each piece's first
  // voxel, not on one grid of the whole volume, so no factor > 1 gives every rank the same coding.
  const auto t0 = std::chrono::steady_clock::now();
  std::vector<float> ss;
  try
  {
    ss = this->m_GlobalSeedCode(mask); // collective: every rank calls it once per run
  }
  catch (const std::exception& e)
  {
    itkExceptionMacro(<< e.what());
  }
  const double roundsSeconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  this->m_NumberOfVesselVoxels = mask.vesselCount();
  this->CheckAbort(this->m_MaskProgressShare);
  this->m_RawSkeleton = this->Code(mask, 1, nullptr, &ss);
  dropSinglePointPaths(this->m_RawSkeleton); // entries a voxel wide at the piece's faces
  this->m_EffectiveDownsampleFactor = 1;
  this->m_RawSkeleton.stageSeconds.emplace_back("mask", maskSeconds);
  this->m_RawSkeleton.stageSeconds.emplace_back("globalSeedCode", roundsSeconds);
  this->m_CodeMemoryBytes = mask.memoryBytes() + this->m_RawSkeleton.peakBytes;
  this->FinishOutput();
}

template<typename TInputImage>
void VoxelCodingSkeletonFilter<TInputImage>::FinishOutput()
{
  if (this->m_RawSkeleton.paths.empty())
  {
    itkExceptionMacro("no vessel component of at least " << this->m_MinimumComponentSize
                                                         << " voxels has a centerline");
  }
  this->CheckAbort(0.95F);
  const auto t0 = std::chrono::steady_clock::now();
  this->GetOutput()->Get() = this->ToWorld(this->m_RawSkeleton);
  this->m_RawSkeleton.stageSeconds.emplace_back(
    "geometry", std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  this->UpdateProgress(1.0F);
}

template<typename TInputImage>
void VoxelCodingSkeletonFilter<TInputImage>::GenerateData()
{
  QSkeletonObject* output = this->GetOutput();
  output->Get() = QSkeleton{};
  this->m_RawSkeleton = RawSkeleton{};
  this->UpdateProgress(0.0F);
  using Clock = std::chrono::steady_clock;
  const auto seconds = [](Clock::time_point t0)
  { return std::chrono::duration<double>(Clock::now() - t0).count(); };
  auto t0 = Clock::now();
  this->m_MaskProgressShare = this->m_UseVesselness && !this->m_VesselMask ? 0.5F : 0.05F;
  SparseVesselMask mask = this->BuildMask();
  const double maskSeconds = seconds(t0);
  this->CheckAbort(this->m_MaskProgressShare);
  if (this->m_GlobalSeedCode)
  {
    this->GenerateFromGlobalSeedCode(mask, maskSeconds);
    return;
  }
  this->m_NumberOfVesselVoxels = mask.vesselCount();
  IndexType seedIndex;
  if (this->m_UseSeedPoint)
  {
    seedIndex = this->SeedIndex(mask);
  }
  const IndexType* seed = this->m_UseSeedPoint ? &seedIndex : nullptr;
  const bool automatic = this->m_DownsampleFactor == 0;
  const auto& spacing = this->GetInput()->GetSpacing();
  unsigned int factor =
    automatic ? AutomaticDownsampling::factorFor(mask, { spacing[0], spacing[1], spacing[2] })
              : this->m_DownsampleFactor;
  std::size_t coarseMaskBytes = 0;
  double scaleSeconds = seconds(t0) - maskSeconds;
  if (factor > 1)
  {
    t0 = Clock::now();
    const SparseVesselMask coarse = mask.downsampled(factor);
    scaleSeconds += seconds(t0);
    coarseMaskBytes = coarse.memoryBytes();
    this->m_RawSkeleton = this->Code(coarse, factor, seed);
    const double coarseVoxel_mm = factor * std::max({ spacing[0], spacing[1], spacing[2] });
    if (automatic &&
        !AutomaticDownsampling::resolvesEveryBranch(this->m_RawSkeleton, coarseVoxel_mm))
    {
      factor = 1; // a thin branch: code the full resolution after all
      coarseMaskBytes = 0;
    }
    else
    {
      CoarseSkeletonRefiner refiner(mask, { spacing[0], spacing[1], spacing[2] }, factor);
      this->m_RawSkeleton = refiner.refine(this->m_RawSkeleton);
      this->CheckAbort(0.95F);
    }
  }
  if (factor == 1)
  {
    this->m_RawSkeleton = this->Code(mask, 1, seed);
  }
  this->m_EffectiveDownsampleFactor = factor;
  // The filter's own stages, for profiling beside the coder's (GetRawSkeleton().stageSeconds).
  this->m_RawSkeleton.stageSeconds.emplace_back("mask", maskSeconds);
  this->m_RawSkeleton.stageSeconds.emplace_back("scale", scaleSeconds);
  this->m_CodeMemoryBytes = mask.memoryBytes() + coarseMaskBytes + this->m_RawSkeleton.peakBytes;
  this->FinishOutput();
}

template<typename TInputImage>
void VoxelCodingSkeletonFilter<TInputImage>::PrintSelf(std::ostream& os, itk::Indent indent) const
{
  Superclass::PrintSelf(os, indent);
  os << indent << "LowerThreshold: " << this->m_LowerThreshold << "\n";
  os << indent << "UpperThreshold: " << this->m_UpperThreshold << "\n";
  os << indent << "UseSeedPoint: " << this->m_UseSeedPoint << "\n";
  os << indent << "SeedPoint: " << this->m_SeedPoint << "\n";
  os << indent << "MinimumComponentSize: " << this->m_MinimumComponentSize << "\n";
  os << indent << "MinimumBranchLength: " << this->m_MinimumBranchLength << "\n";
  os << indent << "SmoothingWindow: " << this->m_SmoothingWindow << "\n";
  os << indent << "ClusterWidth: " << this->m_ClusterWidth << "\n";
  os << indent << "DownsampleFactor: " << this->m_DownsampleFactor << "\n";
  os << indent << "UseVesselness: " << this->m_UseVesselness << "\n";
  os << indent << "VesselnessSigmaMinimum: " << this->m_VesselnessSigmaMinimum << "\n";
  os << indent << "VesselnessSigmaMaximum: " << this->m_VesselnessSigmaMaximum << "\n";
  os << indent << "VesselnessNumberOfScales: " << this->m_VesselnessNumberOfScales << "\n";
  os << indent << "VesselnessThreshold: " << this->m_VesselnessThreshold << "\n";
  os << indent << "NumberOfVesselVoxels: " << this->m_NumberOfVesselVoxels << "\n";
}

} // namespace vtouch

#include "vtouchVolumeSkeletonizer.h"

#include "vtouchSparseVesselMask.h"
#include "vtouchVoxelCodingSkeletonFilter.h"

#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkMatrix3x3.h"

#include <itkCommand.h>
#include <itkImportImageFilter.h>

#include <algorithm>

namespace vtouch
{
namespace
{
/// Wraps the VTK scalars as an ITK image (no copy) with the VTK geometry.
template<typename T>
typename itk::Image<T, 3>::Pointer importImage(vtkImageData* image, T* data)
{
  using Import = itk::ImportImageFilter<T, 3>;
  auto importer = Import::New();
  int dims[3];
  image->GetDimensions(dims);
  typename Import::SizeType size;
  typename Import::RegionType region;
  double origin[3], spacing[3];
  image->GetOrigin(origin);
  image->GetSpacing(spacing);
  typename Import::DirectionType direction;
  vtkMatrix3x3* m = image->GetDirectionMatrix();
  for (int r = 0; r < 3; ++r)
  {
    size[r] = static_cast<itk::SizeValueType>(dims[r]);
    for (int c = 0; c < 3; ++c)
    {
      direction[r][c] = m ? m->GetElement(r, c) : (r == c ? 1.0 : 0.0);
    }
  }
  region.SetSize(size);
  importer->SetRegion(region);
  importer->SetOrigin(origin);
  importer->SetSpacing(spacing);
  importer->SetDirection(direction);
  importer->SetImportPointer(
    data, static_cast<itk::SizeValueType>(dims[0]) * dims[1] * dims[2], false);
  importer->Update();
  return importer->GetOutput();
}

/// Runs the ITK filter; throws itk::ExceptionObject (itk::ProcessAborted when aborted).
/// `stageSeconds` receives the filter's and the coder's stage times (mask, scale, the coder's
/// stages, geometry).
template<typename T>
QSkeleton skeletonize(vtkImageData* image,
  T* data,
  const CoderSettings& s,
  int& factorUsed,
  std::vector<std::pair<std::string, double>>& stageSeconds)
{
  using Image = itk::Image<T, 3>;
  using Filter = VoxelCodingSkeletonFilter<Image>;
  typename Image::Pointer itkImage = importImage<T>(image, data);
  auto filter = Filter::New();
  filter->SetInput(itkImage);
  filter->SetLowerThreshold(s.lower);
  filter->SetUpperThreshold(s.upper);
  if (s.useSeed)
  {
    typename Filter::PointType p;
    p[0] = s.seed[0];
    p[1] = s.seed[1];
    p[2] = s.seed[2];
    filter->SetSeedPoint(p);
  }
  filter->SetMinimumComponentSize(static_cast<unsigned long>(std::max(0, s.minimumComponentSize)));
  filter->SetMinimumBranchLength(s.minimumBranchLength);
  filter->SetSmoothingWindow(s.smoothing);
  filter->SetUseVesselness(s.useVesselness);
  filter->SetVesselnessSigmaMinimum(s.sigmaMin);
  filter->SetVesselnessSigmaMaximum(s.sigmaMax);
  filter->SetVesselnessNumberOfScales(static_cast<unsigned int>(std::max(0, s.scales)));
  filter->SetVesselnessThreshold(s.vesselnessThreshold);
  filter->SetDownsampleFactor(static_cast<unsigned int>(std::max(0, s.downsampleFactor)));
  filter->SetVesselMask(s.mask);
  if (s.globalSeedCode)
  {
    filter->SetGlobalSeedCode(s.globalSeedCode);
  }
  if (s.pieceInWhole)
  {
    filter->SetPieceInWhole(*s.pieceInWhole);
  }
  if (s.globalFaceTips)
  {
    filter->SetGlobalFaceTips(s.globalFaceTips);
  }
  // Progress to VTK; VTK's abort flag and the cancel flag to ITK (on the thread that runs the
  // filter: ITK invokes progress events on the thread that called Update()).
  auto progress = itk::CStyleCommand::New();
  struct Context
  {
    const CoderSettings* settings;
    Filter* filter;
  } context{ &s, filter.GetPointer() };
  progress->SetClientData(&context);
  progress->SetCallback(
    [](itk::Object*, const itk::EventObject&, void* data)
    {
      auto* c = static_cast<Context*>(data);
      if (c->settings->progress && !c->settings->progress(c->filter->GetProgress()))
      {
        c->filter->SetAbortGenerateData(true);
      }
    });
  filter->AddObserver(itk::ProgressEvent(), progress);
  filter->Update();
  factorUsed = static_cast<int>(filter->GetEffectiveDownsampleFactor());
  stageSeconds = filter->GetRawSkeleton().stageSeconds;
  return filter->GetSkeleton();
}
} // namespace

CoderRun skeletonizeVolume(vtkImageData* image, vtkDataArray* scalars, const CoderSettings& s)
{
  CoderRun run;
  void* data = scalars->GetVoidPointer(0);
  switch (scalars->GetDataType())
  {
    case VTK_FLOAT:
      run.skeleton =
        skeletonize(image, static_cast<float*>(data), s, run.factorUsed, run.stageSeconds);
      break;
    case VTK_UNSIGNED_CHAR:
      run.skeleton =
        skeletonize(image, static_cast<unsigned char*>(data), s, run.factorUsed, run.stageSeconds);
      break;
    case VTK_SHORT:
      run.skeleton =
        skeletonize(image, static_cast<short*>(data), s, run.factorUsed, run.stageSeconds);
      break;
    case VTK_UNSIGNED_SHORT:
      run.skeleton = skeletonize(
        image, static_cast<unsigned short*>(data), s, run.factorUsed, run.stageSeconds);
      break;
    default:
    {
      // Other types: one float copy of the volume.
      std::vector<float> copy(static_cast<std::size_t>(scalars->GetNumberOfTuples()));
      for (vtkIdType i = 0; i < scalars->GetNumberOfTuples(); ++i)
      {
        copy[static_cast<std::size_t>(i)] = static_cast<float>(scalars->GetComponent(i, 0));
      }
      run.skeleton = skeletonize(image, copy.data(), s, run.factorUsed, run.stageSeconds);
    }
  }
  return run;
}
} // namespace vtouch

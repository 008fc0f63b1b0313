#include "pqVesselTouchVoxelSample.h"

#include "pqVesselTouchVolumeJob.h"

#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkPointData.h"

#include <algorithm>
#include <vector>

namespace
{
/// The manual range's starting lower bound: the intensity above which this fraction of the voxels
/// lie (the histogram's upper tail). Vessels fill a few percent of an angiogram's field of view;
/// the automatic estimate (the filter's, from the seed's neighbourhood) replaces it after Extract.
constexpr double kVesselTailFraction = 0.03;
/// Voxels sampled for the percentiles (evenly strided).
constexpr vtkIdType kTailSamples = 1 << 18;
} // namespace

namespace pqVesselTouchVoxelSample
{

bool neighbourhoodMedian(pqPipelineSource* volume, const double point_mm[3], double& median)
{
  vtkImageData* image = pqVesselTouchVolumeJob::localImage(volume);
  vtkDataArray* scalars = image ? image->GetPointData()->GetScalars() : nullptr;
  if (!scalars)
  {
    return false;
  }
  int centre[3];
  double pcoords[3];
  if (!image->ComputeStructuredCoordinates(point_mm, centre, pcoords))
  {
    return false;
  }
  const int* extent = image->GetExtent();
  std::vector<double> values;
  for (int k = -1; k <= 1; ++k)
  {
    for (int j = -1; j <= 1; ++j)
    {
      for (int i = -1; i <= 1; ++i)
      {
        int ijk[3] = {
          centre[0] + i + extent[0], centre[1] + j + extent[2], centre[2] + k + extent[4]
        };
        if (ijk[0] <= extent[1] && ijk[1] <= extent[3] && ijk[2] <= extent[5] &&
            ijk[0] >= extent[0] && ijk[1] >= extent[2] && ijk[2] >= extent[4])
        {
          values.push_back(scalars->GetComponent(image->ComputePointId(ijk), 0));
        }
      }
    }
  }
  if (values.empty())
  {
    return false;
  }
  std::nth_element(
    values.begin(), values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2), values.end());
  median = values[values.size() / 2];
  return true;
}

bool voxelValue(pqPipelineSource* volume, const double point_mm[3], double& value)
{
  vtkImageData* image = pqVesselTouchVolumeJob::localImage(volume);
  vtkDataArray* scalars = image ? image->GetPointData()->GetScalars() : nullptr;
  const vtkIdType id = scalars ? image->FindPoint(point_mm[0], point_mm[1], point_mm[2]) : -1;
  if (id < 0)
  {
    return false;
  }
  value = scalars->GetComponent(id, 0);
  return true;
}

VoxelSample sampleVoxels(pqPipelineSource* volume)
{
  VoxelSample result;
  vtkImageData* image = pqVesselTouchVolumeJob::localImage(volume);
  vtkDataArray* scalars = image ? image->GetPointData()->GetScalars() : nullptr;
  const vtkIdType count = scalars ? scalars->GetNumberOfTuples() : 0;
  if (count <= 0)
  {
    return result;
  }
  const vtkIdType stride = std::max<vtkIdType>(1, count / kTailSamples);
  std::vector<double> samples;
  samples.reserve(static_cast<size_t>(count / stride + 1));
  for (vtkIdType i = 0; i < count; i += stride)
  {
    samples.push_back(scalars->GetComponent(i, 0));
  }
  const auto at = [&samples](double quantile)
  {
    const auto rank =
      static_cast<std::ptrdiff_t>(quantile * static_cast<double>(samples.size() - 1));
    std::nth_element(samples.begin(), samples.begin() + rank, samples.end());
    return samples[static_cast<size_t>(rank)];
  };
  result.tail = at(1.0 - kVesselTailFraction);
  result.background = at(0.5);
  result.noise = result.background - at(0.1587);
  result.ok = true;
  return result;
}

} // namespace pqVesselTouchVoxelSample

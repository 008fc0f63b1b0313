#include "pqVesselTouchRemoteRayProbe.h"

#include "vtouchRayMaximum.h"

#include "pqOutputPort.h"
#include "pqPipelineSource.h"
#include "pqServer.h"
#include "vtkAlgorithm.h"
#include "vtkDataArray.h"
#include "vtkDataObject.h"
#include "vtkDataSetAttributes.h"
#include "vtkPVArrayInformation.h"
#include "vtkPVDataInformation.h"
#include "vtkPVDataSetAttributesInformation.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkSMPropertyHelper.h"
#include "vtkSMSessionProxyManager.h"
#include "vtkSMSourceProxy.h"
#include "vtkSmartPointer.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace
{
/// Samples per smallest voxel spacing along the ray (project rule: every voxel crossed is
/// sampled within half a voxel of its centre).
constexpr double kSamplesPerVoxel = 2.0;
/// At most this many samples (a ray through a 1024^3 volume's diagonal at 2 per voxel is 3548).
constexpr int kMaxSamples = 20000;
/// ProbeLine's "Sample Uniformly" (its SamplingPattern enumeration).
constexpr int kSampleUniformly = 2;
constexpr int kPolyData = 0; // ClientServerMoveData's OutputDataType

vtkSmartPointer<vtkSMSourceProxy> newFilter(vtkSMSessionProxyManager* pxm, const char* name)
{
  return vtkSmartPointer<vtkSMSourceProxy>::Take(
    vtkSMSourceProxy::SafeDownCast(pxm->NewProxy("filters", name)));
}
}

bool pqVesselTouchRemoteRayProbe::clipToBounds(const double bounds[6],
  const double near_mm[3],
  const double far_mm[3],
  double p0[3],
  double p1[3])
{
  const std::array<double, 3> low{ bounds[0], bounds[2], bounds[4] };
  const std::array<double, 3> high{ bounds[1], bounds[3], bounds[5] };
  const std::array<double, 3> start{ near_mm[0], near_mm[1], near_mm[2] };
  const std::array<double, 3> end{ far_mm[0], far_mm[1], far_mm[2] };
  double t0 = 0.0, t1 = 1.0;
  if (!vtouch::RayMaximum::clipSegmentToBox(low, high, start, end, t0, t1))
  {
    return false;
  }
  for (int i = 0; i < 3; ++i)
  {
    p0[i] = near_mm[i] + t0 * (far_mm[i] - near_mm[i]);
    p1[i] = near_mm[i] + t1 * (far_mm[i] - near_mm[i]);
  }
  return true;
}

pqVesselTouchRemoteRayProbe::Result pqVesselTouchRemoteRayProbe::find(pqPipelineSource* volume,
  const double near_mm[3],
  const double far_mm[3])
{
  Result result;
  vtkPVDataInformation* info = volume ? volume->getOutputPort(0)->getDataInformation() : nullptr;
  if (!info || info->GetDataSetType() != VTK_IMAGE_DATA || info->GetNumberOfPoints() <= 0)
  {
    result.error = QObject::tr("Pick seed: the volume is not image data on the server.");
    return result;
  }
  const double* bounds = info->GetBounds();
  const int* extent = info->GetExtent();
  double spacing[3];
  double smallest = std::numeric_limits<double>::max();
  for (int i = 0; i < 3; ++i)
  {
    const int cells = extent[2 * i + 1] - extent[2 * i];
    spacing[i] = cells > 0 ? (bounds[2 * i + 1] - bounds[2 * i]) / cells : 1.0;
    if (cells > 0)
    {
      smallest = std::min(smallest, spacing[i]);
    }
  }
  double p0[3];
  double p1[3];
  if (!(smallest > 0.0) || !clipToBounds(bounds, near_mm, far_mm, p0, p1))
  {
    result.error = QObject::tr("Pick seed: the click's ray misses the volume.");
    return result;
  }
  const double length_mm =
    std::sqrt((p1[0] - p0[0]) * (p1[0] - p0[0]) + (p1[1] - p0[1]) * (p1[1] - p0[1]) +
              (p1[2] - p0[2]) * (p1[2] - p0[2]));
  const int resolution = std::clamp(
    static_cast<int>(std::ceil(kSamplesPerVoxel * length_mm / smallest)), 1, kMaxSamples);

  vtkPVArrayInformation* scalars =
    info->GetPointDataInformation()
      ? info->GetPointDataInformation()->GetAttributeInformation(vtkDataSetAttributes::SCALARS)
      : nullptr;
  if (!scalars || !scalars->GetName())
  {
    result.error = QObject::tr("Pick seed: the volume has no image scalars.");
    return result;
  }
  const std::string scalarName = scalars->GetName();

  vtkSMSessionProxyManager* pxm = volume->proxyManager();
  vtkSmartPointer<vtkSMSourceProxy> probe = newFilter(pxm, "ProbeLine");
  vtkSmartPointer<vtkSMSourceProxy> mover = newFilter(pxm, "ClientServerMoveData");
  if (!probe || !mover)
  {
    result.error = QObject::tr("Pick seed: ParaView's ProbeLine is not available.");
    return result;
  }
  vtkSMPropertyHelper(probe, "Input").Set(volume->getProxy(), 0);
  vtkSMPropertyHelper(probe, "Point1").Set(p0, 3);
  vtkSMPropertyHelper(probe, "Point2").Set(p1, 3);
  vtkSMPropertyHelper(probe, "Resolution").Set(resolution);
  vtkSMPropertyHelper(probe, "SamplingPattern").Set(kSampleUniformly);
  probe->UpdateVTKObjects();
  vtkSMPropertyHelper(mover, "Input").Set(probe, 0);
  vtkSMPropertyHelper(mover, "OutputDataType").Set(kPolyData);
  mover->UpdateVTKObjects();
  probe->UpdatePipeline();
  mover->UpdatePipeline(); // every process: rank 0 sends, the client receives

  auto* moved = vtkAlgorithm::SafeDownCast(mover->GetClientSideObject());
  vtkPolyData* samples = moved ? vtkPolyData::SafeDownCast(moved->GetOutputDataObject(0)) : nullptr;
  vtkDataArray* values = samples ? samples->GetPointData()->GetArray(scalarName.c_str()) : nullptr;
  vtkDataArray* valid = samples ? samples->GetPointData()->GetArray("vtkValidPointMask") : nullptr;
  if (!values)
  {
    result.error = QObject::tr("Pick seed: the server returned no samples along the ray.");
    return result;
  }
  vtkIdType best = -1;
  for (vtkIdType i = 0; i < samples->GetNumberOfPoints(); ++i)
  {
    if (valid && valid->GetComponent(i, 0) == 0.0)
    {
      continue;
    }
    ++result.samples;
    const double v = values->GetComponent(i, 0);
    if (best < 0 || v > result.value)
    {
      best = i;
      result.value = v;
    }
  }
  if (best < 0)
  {
    result.error = QObject::tr("Pick seed: the click's ray misses the volume.");
    return result;
  }
  double at[3];
  samples->GetPoint(best, at);
  for (int i = 0; i < 3; ++i)
  {
    // The nearest voxel (bounds[2i] is the first voxel's centre).
    const int cells = extent[2 * i + 1] - extent[2 * i];
    const double index = cells > 0 ? std::round((at[i] - bounds[2 * i]) / spacing[i]) : 0.0;
    result.seed_mm[i] = bounds[2 * i] + std::clamp(index, 0.0, double(cells)) * spacing[i];
  }
  result.found = true;
  return result;
}

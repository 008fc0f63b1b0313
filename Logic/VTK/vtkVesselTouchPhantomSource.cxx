#include "vtkVesselTouchPhantomSource.h"

#include "vtouchPhantomGenerator.h"

#include "vtkCellArray.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkUnsignedShortArray.h"

vtkStandardNewMacro(vtkVesselTouchPhantomSource);

namespace
{
vtouch::PhantomSpec makeSpec(const vtkVesselTouchPhantomSource* s)
{
  vtouch::PhantomSpec spec;
  auto* self = const_cast<vtkVesselTouchPhantomSource*>(s);
  spec.shape = static_cast<vtouch::PhantomShape>(self->GetShape());
  for (int a = 0; a < 3; ++a)
  {
    spec.dimensions[a] = self->GetDimensions()[a];
    spec.spacing_mm[a] = self->GetSpacing()[a];
    spec.origin_mm[a] = self->GetOrigin()[a];
  }
  spec.radiusFraction = self->GetRadiusFraction();
  spec.taperRatio = self->GetTaperRatio();
  spec.helixRadiusFraction = self->GetHelixRadiusFraction();
  spec.helixPitchFraction = self->GetHelixPitchFraction();
  spec.helixTurns = self->GetHelixTurns();
  spec.windingAmplitudeFraction = self->GetWindingAmplitudeFraction();
  spec.windingPeriods = self->GetWindingPeriods();
  spec.treeDepth = self->GetTreeDepth();
  spec.treeRadiusRatio = self->GetTreeRadiusRatio();
  spec.profile = static_cast<vtouch::PhantomSpec::Profile>(self->GetProfile());
  spec.backgroundIntensity = self->GetBackgroundIntensity();
  spec.peakIntensity = self->GetPeakIntensity();
  spec.noiseStdDev = self->GetNoiseStandardDeviation();
  spec.seed = static_cast<std::uint32_t>(self->GetSeed());
  spec.wallRoughness = self->GetWallRoughness();
  spec.angiogramSegments = self->GetAngiogramSegments();
  spec.angiogramLargestRadius_vox = self->GetAngiogramLargestRadius();
  spec.angiogramSmallestRadius_vox = self->GetAngiogramSmallestRadius();
  spec.noiseModel = static_cast<vtouch::PhantomSpec::NoiseModel>(self->GetNoiseModel());
  spec.biasAmplitude = self->GetBiasAmplitude();
  spec.clutterCount = self->GetClutterCount();
  spec.tissueIntensity = self->GetTissueIntensity();
  return spec;
}

void fillCenterline(const vtouch::QSkeleton& skeleton, vtkPolyData* output)
{
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->Allocate(static_cast<vtkIdType>(skeleton.pointCount()));
  vtkNew<vtkDoubleArray> radius;
  radius->SetName("Radius");
  vtkNew<vtkDoubleArray> tangent;
  tangent->SetName("Tangent");
  tangent->SetNumberOfComponents(3);
  vtkNew<vtkCellArray> lines;
  for (const vtouch::SkeletonPath& path : skeleton.paths)
  {
    const bool closed =
      path.tail.junction >= 0 && skeleton.junctions[path.tail.junction].parentPath == path.id;
    const vtkIdType n = static_cast<vtkIdType>(path.points.size());
    lines->InsertNextCell(closed ? n + 1 : n);
    const vtkIdType first = points->GetNumberOfPoints();
    for (const vtouch::SkeletonPoint& p : path.points)
    {
      const vtkIdType id = points->InsertNextPoint(
        p.position_World_mm.x, p.position_World_mm.y, p.position_World_mm.z);
      radius->InsertNextValue(p.radius_mm);
      tangent->InsertNextTuple3(p.tangent_World.x, p.tangent_World.y, p.tangent_World.z);
      lines->InsertCellPoint(id);
    }
    if (closed)
    {
      lines->InsertCellPoint(first);
    }
  }
  output->SetPoints(points);
  output->SetLines(lines);
  output->GetPointData()->AddArray(radius);
  output->GetPointData()->AddArray(tangent);
  output->GetPointData()->SetActiveScalars("Radius");
}
} // namespace

vtkVesselTouchPhantomSource::vtkVesselTouchPhantomSource()
{
  this->SetNumberOfInputPorts(0);
  this->SetNumberOfOutputPorts(2);
}

int vtkVesselTouchPhantomSource::FillOutputPortInformation(int port, vtkInformation* info)
{
  if (port == 1)
  {
    info->Set(vtkDataObject::DATA_TYPE_NAME(), "vtkPolyData");
    return 1;
  }
  return this->Superclass::FillOutputPortInformation(port, info);
}

std::string vtkVesselTouchPhantomSource::Validate() const
{
  if (this->OutputScalarType != VTK_UNSIGNED_SHORT && this->OutputScalarType != VTK_FLOAT)
  {
    return "OutputScalarType must be unsigned short (5) or float (10)";
  }
  return makeSpec(this).validate();
}

int vtkVesselTouchPhantomSource::RequestInformation(vtkInformation*,
  vtkInformationVector**,
  vtkInformationVector* outputVector)
{
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  const std::string error = this->Validate();
  int extent[6] = { 0, -1, 0, -1, 0, -1 };
  if (error.empty())
  {
    extent[1] = this->Dimensions[0] - 1;
    extent[3] = this->Dimensions[1] - 1;
    extent[5] = this->Dimensions[2] - 1;
    outInfo->Set(vtkDataObject::SPACING(), this->Spacing, 3);
    outInfo->Set(vtkDataObject::ORIGIN(), this->Origin, 3);
  }
  outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent, 6);
  vtkDataObject::SetPointDataActiveScalarInfo(outInfo, this->OutputScalarType, 1);
  return 1;
}

int vtkVesselTouchPhantomSource::RequestData(vtkInformation*,
  vtkInformationVector**,
  vtkInformationVector* outputVector)
{
  vtkImageData* image = vtkImageData::GetData(outputVector, 0);
  vtkPolyData* centerline = vtkPolyData::GetData(outputVector, 1);
  if (!image || !centerline)
  {
    vtkErrorMacro("VesselPhantom: missing output data objects.");
    return 0;
  }
  const std::string error = this->Validate();
  if (!error.empty())
  {
    vtkErrorMacro("VesselPhantom: " << error << ". The output is empty.");
    image->Initialize();
    centerline->Initialize();
    return 1;
  }
  const vtouch::PhantomGenerator generator(makeSpec(this));

  image->SetDimensions(this->Dimensions);
  image->SetSpacing(this->Spacing);
  image->SetOrigin(this->Origin);
  const vtkIdType count =
    static_cast<vtkIdType>(this->Dimensions[0]) * this->Dimensions[1] * this->Dimensions[2];
  auto progress = [this](double fraction)
  {
    this->UpdateProgress(fraction);
    return !this->CheckAbort();
  };
  bool completed = false;
  if (this->OutputScalarType == VTK_FLOAT)
  {
    vtkNew<vtkFloatArray> scalars;
    scalars->SetName("Intensity");
    scalars->SetNumberOfTuples(count);
    completed = generator.fill(scalars->GetPointer(0), progress);
    image->GetPointData()->SetScalars(scalars);
  }
  else
  {
    vtkNew<vtkUnsignedShortArray> scalars;
    scalars->SetName("Intensity");
    scalars->SetNumberOfTuples(count);
    completed = generator.fill(scalars->GetPointer(0), progress);
    image->GetPointData()->SetScalars(scalars);
  }
  if (!completed)
  {
    image->Initialize();
    centerline->Initialize();
    return 1; // aborted by the user: an empty output, no error
  }
  fillCenterline(generator.centerline(), centerline);
  return 1;
}

void vtkVesselTouchPhantomSource::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Shape: " << vtouch::toString(static_cast<vtouch::PhantomShape>(this->Shape))
     << "\n"
     << indent << "Dimensions: " << this->Dimensions[0] << " " << this->Dimensions[1] << " "
     << this->Dimensions[2] << "\n"
     << indent << "Spacing: " << this->Spacing[0] << " " << this->Spacing[1] << " "
     << this->Spacing[2] << "\n"
     << indent << "RadiusFraction: " << this->RadiusFraction << "\n"
     << indent << "NoiseStandardDeviation: " << this->NoiseStandardDeviation << "\n"
     << indent << "Seed: " << this->Seed << "\n"
     << indent << "AngiogramSegments: " << this->AngiogramSegments << "\n"
     << indent << "AngiogramRadii (voxels): " << this->AngiogramSmallestRadius << " .. "
     << this->AngiogramLargestRadius << "\n"
     << indent << "NoiseModel: " << this->NoiseModel << "\n"
     << indent << "BiasAmplitude: " << this->BiasAmplitude << "\n"
     << indent << "ClutterCount: " << this->ClutterCount << "\n"
     << indent << "TissueIntensity: " << this->TissueIntensity << "\n"
     << indent << "OutputScalarType: " << this->OutputScalarType << "\n";
}

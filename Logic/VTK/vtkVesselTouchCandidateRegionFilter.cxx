#include "vtkVesselTouchCandidateRegionFilter.h"

#include "vtouchShadingCorrection.h"

#include "vtouchCandidateRegionRunner.h"
#include "vtouchDistributedCenterline.h"

#include "vtkDataObject.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <exception>
#include <new>

vtkStandardNewMacro(vtkVesselTouchCandidateRegionFilter);

vtkVesselTouchCandidateRegionFilter::vtkVesselTouchCandidateRegionFilter()
{
  this->SetInputArrayToProcess(
    0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, vtkDataSetAttributes::SCALARS);
}

int vtkVesselTouchCandidateRegionFilter::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  return 1;
}

int vtkVesselTouchCandidateRegionFilter::RequestInformation(vtkInformation*,
  vtkInformationVector**,
  vtkInformationVector* outputVector)
{
  vtkDataObject::SetPointDataActiveScalarInfo(
    outputVector->GetInformationObject(0), VTK_UNSIGNED_CHAR, 1);
  return 1;
}

int vtkVesselTouchCandidateRegionFilter::RequestData(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkImageData* input = vtkImageData::GetData(inputVector[0]);
  vtkImageData* output = vtkImageData::GetData(outputVector);
  if (!input || !output)
  {
    vtkErrorMacro("VesselCandidateRegion needs a vtkImageData input.");
    return 1;
  }
  output->Initialize();
  output->CopyStructure(input);
  vtkNew<vtkUnsignedCharArray> vessel;
  vessel->SetName("CandidateVessel");
  vessel->SetNumberOfTuples(input->GetNumberOfPoints());
  vessel->FillValue(0);
  output->GetPointData()->SetScalars(vessel);
  this->IntensityRangeUsed[0] = this->LowerThreshold;
  this->IntensityRangeUsed[1] = this->UpperThreshold;
  this->ExtractionMessage.clear();
  this->LastRunCancelled = false;
  const auto finish = [this, output](const std::string& message)
  {
    this->ExtractionMessage = message;
    vtouch::addRangeFieldData(output->GetFieldData(),
      this->IntensityRangeUsed[0],
      this->IntensityRangeUsed[1],
      this->AutomaticIntensityRange,
      message);
    if (!message.empty() && !this->LastRunCancelled)
    {
      vtkErrorMacro(<< message);
    }
    return 1;
  };
  int dims[3];
  input->GetDimensions(dims);
  if (dims[0] < 2 || dims[1] < 2 || dims[2] < 2)
  {
    return finish("VesselCandidateRegion needs a 3D volume.");
  }
  vtkDataArray* scalars = this->GetInputArrayToProcess(0, inputVector);
  if (!scalars)
  {
    scalars = input->GetPointData()->GetScalars();
  }
  if (!scalars || scalars->GetNumberOfComponents() != 1)
  {
    return finish("The input has no one-component point scalars to find vessels in.");
  }
  // The shading correction VesselCenterline applies (vtouch::ShadingField), so that the preview
  // is the region the extraction codes.
  vtkSmartPointer<vtkImageData> fromZero = vtouch::DistributedCenterline::pieceFromIndexZero(input);
  vtouch::ShadingCorrection shading;
  if (this->AutomaticIntensityRange && this->CorrectShading)
  {
    shading = vtouch::correctShading(fromZero, scalars, this->UseSeedPoint, this->SeedPoint);
    if (shading.scalars)
    {
      scalars = shading.scalars;
    }
    vtouch::addShadingFieldData(output->GetFieldData(), shading);
  }
  vtouch::CandidateRegionRequest request;
  request.automatic = this->AutomaticIntensityRange;
  request.lower = this->LowerThreshold;
  request.upper = this->UpperThreshold;
  request.useSeed = this->UseSeedPoint;
  std::copy(this->SeedPoint, this->SeedPoint + 3, request.seed_World_mm);
  request.progress = [this](double fraction)
  {
    this->UpdateProgress(fraction);
    return !vtouch::cancelRequested(this->CancelFlag, this);
  };
  vtouch::CandidateRegionOutcome region;
  try
  {
    // From index 0 whatever the input's extent (Extract Subset, a VOI): the runner indexes the
    // voxels from the first one; the output keeps the input's extent, in the same voxel order.
    region = vtouch::runCandidateRegion(fromZero.Get(), scalars, request);
  }
  catch (const vtouch::Cancelled&)
  {
    this->LastRunCancelled = true;
    return finish(vtouch::cancelledMessage());
  }
  catch (const std::bad_alloc&)
  {
    return finish("VesselCandidateRegion: not enough memory for this volume.");
  }
  catch (const std::exception& e)
  {
    return finish(std::string("VesselCandidateRegion: ") + e.what());
  }
  this->IntensityRangeUsed[0] = region.lower;
  this->IntensityRangeUsed[1] = region.upper;
  if (!region.ok)
  {
    return finish(region.message);
  }
  unsigned char* out = vessel->GetPointer(0);
  region.mask->forEach([out](std::uint64_t lin) { out[lin] = 1; });
  return finish(std::string());
}

void vtkVesselTouchCandidateRegionFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "AutomaticIntensityRange: " << this->AutomaticIntensityRange << "\n";
  os << indent << "CorrectShading: " << this->CorrectShading << "\n";
  os << indent << "LowerThreshold: " << this->LowerThreshold << "\n";
  os << indent << "UpperThreshold: " << this->UpperThreshold << "\n";
  os << indent << "UseSeedPoint: " << this->UseSeedPoint << "\n";
  os << indent << "SeedPoint: " << this->SeedPoint[0] << " " << this->SeedPoint[1] << " "
     << this->SeedPoint[2] << "\n";
}

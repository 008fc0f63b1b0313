#include "vtkVesselTouchVersion.h"

#include "vtkObjectFactory.h"
#include "vtkVersion.h"

#include <hidapi.h>
#include <itkConfigure.h>

#define VTOUCH_STRINGIFY_(x) #x
#define VTOUCH_STRINGIFY(x) VTOUCH_STRINGIFY_(x)

vtkStandardNewMacro(vtkVesselTouchVersion);

const char* vtkVesselTouchVersion::GetVesselTouchVersion()
{
  return VESSELTOUCH_VERSION_STRING;
}

const char* vtkVesselTouchVersion::GetVTKVersion()
{
  return vtkVersion::GetVTKVersion();
}

const char* vtkVesselTouchVersion::GetITKVersion()
{
  return VTOUCH_STRINGIFY(ITK_VERSION_MAJOR) "." VTOUCH_STRINGIFY(
    ITK_VERSION_MINOR) "." VTOUCH_STRINGIFY(ITK_VERSION_PATCH);
}

const char* vtkVesselTouchVersion::GetHIDAPIVersion()
{
  return HID_API_VERSION_STR;
}

void vtkVesselTouchVersion::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "VesselTouch: " << GetVesselTouchVersion() << "\n"
     << indent << "VTK: " << GetVTKVersion() << "\n"
     << indent << "ITK: " << GetITKVersion() << "\n"
     << indent << "hidapi: " << GetHIDAPIVersion() << "\n";
}

// Version of VesselTouch and of the libraries this build was compiled against.
#ifndef vtkVesselTouchVersion_h
#define vtkVesselTouchVersion_h

#include "vtkObject.h"
#include "vtkVesselTouchLogicModule.h" // for export macro

class VTKVESSELTOUCHLOGIC_EXPORT vtkVesselTouchVersion : public vtkObject
{
public:
  static vtkVesselTouchVersion* New();
  vtkTypeMacro(vtkVesselTouchVersion, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// VesselTouch's own version, e.g. "0.1.0".
  static const char* GetVesselTouchVersion();
  /// The VTK this build was compiled against (ParaView's bundled VTK).
  static const char* GetVTKVersion();
  /// ITK, from itkVersion.h at build time.
  static const char* GetITKVersion();
  /// hidapi, from hidapi.h at build time.
  static const char* GetHIDAPIVersion();

protected:
  vtkVesselTouchVersion() = default;
  ~vtkVesselTouchVersion() override = default;

private:
  vtkVesselTouchVersion(const vtkVesselTouchVersion&) = delete;
  void operator=(const vtkVesselTouchVersion&) = delete;
};

#endif

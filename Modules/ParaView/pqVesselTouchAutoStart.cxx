#include "pqVesselTouchAutoStart.h"

#include "pqVesselTouchBlendModeNames.h"

#include "pqApplicationCore.h"
#include "pqRepresentation.h"
#include "pqServerManagerModel.h"

#include "vtkSMProxy.h"
#include "vtkSMSettings.h"

pqVesselTouchAutoStart::pqVesselTouchAutoStart(QObject* parentObject)
  : QObject(parentObject)
{
}

void pqVesselTouchAutoStart::startup()
{
  // ParaView 5.11 has no reader priority: File > Open asks when several readers match, unless a
  // "ReaderDetails" default names one. These defaults sit at priority 0.5, below the user's own
  // settings (priority 1), so a user's choice still wins.
  vtkSMSettings::GetInstance()->AddCollectionFromString(
    R"json({"settings": {"RepresentedArrayListSettings": {"ReaderDetails": [
      "*.nii *.nii.gz", "NIfTI, oriented (VesselTouch)", "AnatomicalNIfTIReader",
      "*.nrrd *.nhdr", "NRRD, oriented (VesselTouch)", "AnatomicalNrrdReader",
      "*.mha *.mhd", "MetaImage, oriented (VesselTouch)", "AnatomicalMetaImageReader",
      "*.dcm", "DICOM series, oriented (VesselTouch)", "AnatomicalDICOMSeriesReader"]}}})json",
    0.5);

  // Every representation, also those a state file brings back, names blend mode 1 "Maximum
  // Intensity" so the Properties panel tells the truth about VesselTouch's MIP (issue 20, item 11).
  pqServerManagerModel* model = pqApplicationCore::instance()->getServerManagerModel();
  QObject::connect(model,
    &pqServerManagerModel::representationAdded,
    this,
    [](pqRepresentation* representation)
    { pqVesselTouchBlendModeNames::nameMaximumIntensity(representation->getProxy()); });
  for (pqRepresentation* representation : model->findItems<pqRepresentation*>())
  {
    pqVesselTouchBlendModeNames::nameMaximumIntensity(representation->getProxy());
  }
}

#include "pqVesselTouchAutoStart.h"

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
}

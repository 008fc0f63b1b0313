// The panel's words for a run's shading correction (vtouch::ShadingField, issue 16 item 1): from
// the output's field data ShadingCorrected and ShadingGainSpan, which VesselCenterline and
// VesselCandidateRegion write. Empty when the run corrected nothing.
#pragma once

#include <QCoreApplication>
#include <QString>

#include "vtkDataArray.h"
#include "vtkFieldData.h"

inline QString pqVesselTouchShadingNote(vtkFieldData* fields)
{
  vtkDataArray* corrected = fields ? fields->GetArray("ShadingCorrected") : nullptr;
  vtkDataArray* span = fields ? fields->GetArray("ShadingGainSpan") : nullptr;
  if (!corrected || corrected->GetNumberOfTuples() < 1 || corrected->GetComponent(0, 0) == 0.0 ||
      !span || span->GetNumberOfTuples() < 2)
  {
    return QString();
  }
  return QCoreApplication::translate("pqVesselTouchShadingNote",
    "Shading corrected (the volume's brightness varies %1 to %2 times the seed's); the range is "
    "in the seed's intensities.")
    .arg(span->GetComponent(0, 0), 0, 'f', 2)
    .arg(span->GetComponent(1, 0), 0, 'f', 2);
}

#include "pqVesselTouchDatasetSummary.h"

#include "pqOutputPort.h"
#include "pqPipelineSource.h"

#include "vtkDataSetAttributes.h"
#include "vtkPVArrayInformation.h"
#include "vtkPVDataInformation.h"
#include "vtkPVDataSetAttributesInformation.h"

#include <QObject>

QString pqVesselTouchDatasetSummary::describe(pqPipelineSource* source)
{
  vtkPVDataInformation* data = source ? source->getOutputPort(0)->getDataInformation() : nullptr;
  if (!data || data->GetDataSetType() == -1)
  {
    return QString();
  }
  QString summary = QString::fromLatin1(data->GetPrettyDataTypeString());
  if (data->GetDataSetType() == VTK_IMAGE_DATA)
  {
    const int* e = data->GetExtent();
    summary += QObject::tr(", %1 x %2 x %3 voxels")
                 .arg(e[1] - e[0] + 1)
                 .arg(e[3] - e[2] + 1)
                 .arg(e[5] - e[4] + 1);
  }
  else
  {
    summary += QObject::tr(", %1 points").arg(data->GetNumberOfPoints());
  }
  vtkPVArrayInformation* scalars =
    data->GetPointDataInformation()->GetAttributeInformation(vtkDataSetAttributes::SCALARS);
  if (scalars && scalars->GetName())
  {
    double range[2];
    scalars->GetComponentRange(0, range);
    summary += QObject::tr(", %1 in [%2, %3]").arg(scalars->GetName()).arg(range[0]).arg(range[1]);
  }
  return summary;
}

#include "pqVesselTouchVolumeCheck.h"

#include "pqOutputPort.h"
#include "pqPipelineSource.h"

#include "vtkDataSetAttributes.h"
#include "vtkPVArrayInformation.h"
#include "vtkPVDataInformation.h"
#include "vtkPVDataSetAttributesInformation.h"
#include "vtkType.h"

#include <QCoreApplication>

namespace
{
/// Voxels a volume needs along every axis (one slice is a 2D image).
constexpr int kMinimumVoxelsPerAxis = 2;

vtkPVDataInformation* information(pqPipelineSource* source)
{
  if (!source || source->getNumberOfOutputPorts() < 1)
  {
    return nullptr;
  }
  pqOutputPort* port = source->getOutputPort(0);
  return port ? port->getDataInformation() : nullptr;
}

QString tr(const char* text)
{
  return QCoreApplication::translate("pqVesselTouchVolumeCheck", text);
}
} // namespace

bool pqVesselTouchVolumeCheck::isImage(pqPipelineSource* source)
{
  vtkPVDataInformation* info = information(source);
  return info && info->GetDataSetType() == VTK_IMAGE_DATA;
}

QString pqVesselTouchVolumeCheck::problem(pqPipelineSource* source)
{
  if (!source)
  {
    return tr("No volume: open a 3D image (File > Open) or create a VesselPhantom.");
  }
  const QString name = source->getSMName();
  vtkPVDataInformation* info = information(source);
  if (!info || info->GetDataSetType() == -1)
  {
    return tr("%1 has no data yet (press Apply in the Properties panel).").arg(name);
  }
  if (info->GetDataSetType() != VTK_IMAGE_DATA)
  {
    return tr("%1 is not an image (it is %2): VesselTouch needs a 3D volume.")
      .arg(name, QString::fromUtf8(info->GetDataSetTypeAsString()));
  }
  const int* extent = info->GetExtent();
  int dimensions[3];
  int flat = 0;
  for (int i = 0; i < 3; ++i)
  {
    dimensions[i] = extent[2 * i + 1] - extent[2 * i] + 1;
    flat += dimensions[i] < kMinimumVoxelsPerAxis ? 1 : 0;
  }
  if (info->GetNumberOfPoints() <= 0 || dimensions[0] <= 0 || dimensions[1] <= 0 ||
      dimensions[2] <= 0)
  {
    return tr("%1 is an empty image (see Output Messages for the reader's error).").arg(name);
  }
  if (flat > 0)
  {
    return tr("%1 is a %2D image (%3 x %4 x %5 voxels): VesselTouch needs a 3D volume with at "
              "least %6 voxels along each axis.")
      .arg(name)
      .arg(3 - flat)
      .arg(dimensions[0])
      .arg(dimensions[1])
      .arg(dimensions[2])
      .arg(kMinimumVoxelsPerAxis);
  }
  vtkPVArrayInformation* scalars =
    info->GetPointDataInformation()->GetAttributeInformation(vtkDataSetAttributes::SCALARS);
  if (!scalars || !scalars->GetName())
  {
    return tr("%1 has no point scalars (voxel intensities).").arg(name);
  }
  if (scalars->GetNumberOfComponents() != 1)
  {
    return tr("%1 has %2-component voxels (colour?): VesselTouch needs one intensity per voxel.")
      .arg(name)
      .arg(scalars->GetNumberOfComponents());
  }
  return QString();
}

#include "pqVesselTouchDockPanel.h"

#include "qVesselTouchInfoWidget.h"

#include "pqActiveObjects.h"
#include "pqOutputPort.h"
#include "pqPipelineSource.h"

#include "vtkDataSetAttributes.h"
#include "vtkPVArrayInformation.h"
#include "vtkPVDataInformation.h"
#include "vtkPVDataSetAttributesInformation.h"
#include "vtkPVVersion.h"
#include "vtkVesselTouchVersion.h"

#include <QFile>
#include <QJsonDocument>
#include <QJsonObject>
#include <QScrollArea>
#include <QTimer>
#include <QtDebug>

pqVesselTouchDockPanel::pqVesselTouchDockPanel(QWidget* parentObject)
  : QDockWidget(tr("VesselTouch"), parentObject)
{
  this->Info = new qVesselTouchInfoWidget(this);
  this->Info->setObjectName("VesselTouchInfo");
  this->Info->setVersion("VesselTouch", vtkVesselTouchVersion::GetVesselTouchVersion());
  this->Info->setVersion("ParaView", PARAVIEW_VERSION_FULL);
  this->Info->setVersion("VTK", vtkVesselTouchVersion::GetVTKVersion());
  this->Info->setVersion("ITK", vtkVesselTouchVersion::GetITKVersion());
  this->Info->setVersion("hidapi", vtkVesselTouchVersion::GetHIDAPIVersion());

  auto* scroll = new QScrollArea(this);
  scroll->setObjectName("VesselTouchScroll");
  scroll->setWidgetResizable(true);
  scroll->setWidget(this->Info);
  this->setWidget(scroll);

  QObject::connect(&pqActiveObjects::instance(),
    &pqActiveObjects::sourceChanged,
    this,
    &pqVesselTouchDockPanel::setActiveSource);
  this->setActiveSource(pqActiveObjects::instance().activeSource());

  // ParaView adds plugin docks hidden and restores its saved window state after start-up, so the
  // panel shows itself the first time a dataset becomes active (the user may close it afterwards
  // like any other panel).
  QTimer::singleShot(0, this, &pqVesselTouchDockPanel::revealOnce);
}

void pqVesselTouchDockPanel::revealOnce()
{
  if (this->Revealed)
  {
    return;
  }
  if (this->Source)
  {
    this->Revealed = true;
  }
  this->show();
  this->raise();
}

void pqVesselTouchDockPanel::showEvent(QShowEvent* event)
{
  this->QDockWidget::showEvent(event);
  this->writeReportIfRequested();
}

pqVesselTouchDockPanel::~pqVesselTouchDockPanel() = default;

void pqVesselTouchDockPanel::setActiveSource(pqPipelineSource* source)
{
  if (this->Source)
  {
    QObject::disconnect(this->Source, nullptr, this, nullptr);
  }
  this->Source = source;
  if (source && !this->Revealed)
  {
    QTimer::singleShot(0, this, &pqVesselTouchDockPanel::revealOnce);
  }
  if (source)
  {
    QObject::connect(
      source, SIGNAL(dataUpdated(pqPipelineSource*)), this, SLOT(updateDatasetInformation()));
    QObject::connect(source,
      SIGNAL(nameChanged(pqServerManagerModelItem*)),
      this,
      SLOT(updateDatasetInformation()));
  }
  this->updateDatasetInformation();
}

void pqVesselTouchDockPanel::updateDatasetInformation()
{
  if (!this->Source)
  {
    this->Info->setDatasetName(QString());
    this->Info->setDatasetSummary(QString());
    this->writeReportIfRequested();
    return;
  }
  this->Info->setDatasetName(this->Source->getSMName());
  QString summary;
  vtkPVDataInformation* info = this->Source->getOutputPort(0)->getDataInformation();
  if (info && info->GetDataSetType() != -1)
  {
    summary = QString::fromLatin1(info->GetPrettyDataTypeString());
    if (info->GetDataSetType() == VTK_IMAGE_DATA)
    {
      const int* e = info->GetExtent();
      summary +=
        tr(", %1 x %2 x %3 voxels").arg(e[1] - e[0] + 1).arg(e[3] - e[2] + 1).arg(e[5] - e[4] + 1);
    }
    else
    {
      summary += tr(", %1 points").arg(info->GetNumberOfPoints());
    }
    vtkPVArrayInformation* scalars =
      info->GetPointDataInformation()->GetAttributeInformation(vtkDataSetAttributes::SCALARS);
    if (scalars && scalars->GetName())
    {
      double range[2];
      scalars->GetComponentRange(0, range);
      summary += tr(", %1 in [%2, %3]").arg(scalars->GetName()).arg(range[0]).arg(range[1]);
    }
  }
  this->Info->setDatasetSummary(summary);
  this->writeReportIfRequested();
}

void pqVesselTouchDockPanel::writeReportIfRequested() const
{
  const QString path = qEnvironmentVariable("VESSELTOUCH_GUI_REPORT");
  if (path.isEmpty())
  {
    return;
  }
  QJsonObject versions;
  for (const QString& component : this->Info->versionComponents())
  {
    versions.insert(component, this->Info->version(component));
  }
  QJsonObject report;
  report.insert("panel", this->objectName());
  report.insert("title", this->windowTitle());
  report.insert("visible", this->isVisible());
  report.insert("dataset", this->Info->datasetName());
  report.insert("summary", this->Info->datasetSummary());
  report.insert("versions", versions);
  QFile file(path);
  if (!file.open(QIODevice::WriteOnly | QIODevice::Truncate))
  {
    qWarning() << "VesselTouch: cannot write the GUI report" << path;
    return;
  }
  file.write(QJsonDocument(report).toJson());
}

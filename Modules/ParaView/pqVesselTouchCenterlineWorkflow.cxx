#include "pqVesselTouchCenterlineWorkflow.h"
#include "ui_pqVesselTouchDockPanel.h"

#include "pqVesselTouchCenterlineExtraction.h"
#include "pqVesselTouchSeedPicker.h"
#include "pqVesselTouchVolumeChooser.h"

#include "pqActiveObjects.h"
#include "pqOutputPort.h"
#include "pqPipelineSource.h"
#include "pqRenderView.h"

#include "vtkDataSetAttributes.h"
#include "vtkPVArrayInformation.h"
#include "vtkPVDataInformation.h"
#include "vtkPVDataSetAttributesInformation.h"

#include <QSignalBlocker>

#include <algorithm>

namespace
{
pqRenderView* activeRenderView()
{
  return qobject_cast<pqRenderView*>(pqActiveObjects::instance().activeView());
}
} // namespace

pqVesselTouchCenterlineWorkflow::pqVesselTouchCenterlineWorkflow(Ui::pqVesselTouchDockPanel& ui,
  QObject* parentObject)
  : QObject(parentObject)
  , Ui(ui)
  , Volumes(new pqVesselTouchVolumeChooser(ui.volumeCombo, this))
  , Picker(new pqVesselTouchSeedPicker(this))
  , Extraction(new pqVesselTouchCenterlineExtraction(this))
{
  QObject::connect(this->Volumes,
    &pqVesselTouchVolumeChooser::currentVolumeChanged,
    this,
    &pqVesselTouchCenterlineWorkflow::onVolumeChanged);
  QObject::connect(this->Ui.pickSeedButton,
    &QPushButton::toggled,
    this,
    &pqVesselTouchCenterlineWorkflow::onPickSeedToggled);
  QObject::connect(this->Picker,
    &pqVesselTouchSeedPicker::seedPicked,
    this,
    &pqVesselTouchCenterlineWorkflow::onSeedPicked);
  QObject::connect(this->Picker,
    &pqVesselTouchSeedPicker::pickFailed,
    this,
    [this](const QString& why)
    {
      const QSignalBlocker blocker(this->Ui.pickSeedButton);
      this->Ui.pickSeedButton->setChecked(false);
      Q_EMIT this->message(why);
    });
  QObject::connect(
    this->Ui.extractButton, &QPushButton::clicked, this, &pqVesselTouchCenterlineWorkflow::extract);
  QObject::connect(this->Extraction,
    &pqVesselTouchCenterlineExtraction::progress,
    this->Ui.extractProgress,
    &QProgressBar::setValue);
  QObject::connect(this->Extraction,
    &pqVesselTouchCenterlineExtraction::failed,
    this,
    &pqVesselTouchCenterlineWorkflow::message);
  QObject::connect(this->Extraction,
    &pqVesselTouchCenterlineExtraction::finished,
    this,
    &pqVesselTouchCenterlineWorkflow::centerlineReady);
  this->onVolumeChanged(this->Volumes->currentVolume());
}

pqVesselTouchCenterlineWorkflow::~pqVesselTouchCenterlineWorkflow() = default;

pqPipelineSource* pqVesselTouchCenterlineWorkflow::currentVolume() const
{
  return this->Volumes->currentVolume();
}

bool pqVesselTouchCenterlineWorkflow::seed(double seed_mm[3]) const
{
  std::copy(this->Seed_mm, this->Seed_mm + 3, seed_mm);
  return this->HasSeed;
}

double pqVesselTouchCenterlineWorkflow::lowerThreshold() const
{
  return this->Ui.lowerThreshold->value();
}

double pqVesselTouchCenterlineWorkflow::upperThreshold() const
{
  return this->Ui.upperThreshold->value();
}

pqPipelineSource* pqVesselTouchCenterlineWorkflow::centerline() const
{
  return this->Extraction->centerline();
}

void pqVesselTouchCenterlineWorkflow::onPickSeedToggled(bool armed)
{
  if (armed)
  {
    this->Picker->arm(activeRenderView(), this->Volumes->currentVolume());
  }
  else
  {
    this->Picker->disarm();
  }
}

bool pqVesselTouchCenterlineWorkflow::pickSeedAt(const QPoint& position)
{
  return this->Picker->pickAt(activeRenderView(), this->Volumes->currentVolume(), position);
}

void pqVesselTouchCenterlineWorkflow::onSeedPicked(double x_mm,
  double y_mm,
  double z_mm,
  double value)
{
  this->HasSeed = true;
  this->Seed_mm[0] = x_mm;
  this->Seed_mm[1] = y_mm;
  this->Seed_mm[2] = z_mm;
  this->Ui.seedLabel->setText(tr("(%1, %2, %3) mm, value %4")
                                .arg(x_mm, 0, 'f', 2)
                                .arg(y_mm, 0, 'f', 2)
                                .arg(z_mm, 0, 'f', 2)
                                .arg(value));
  const QSignalBlocker blocker(this->Ui.pickSeedButton);
  this->Ui.pickSeedButton->setChecked(false);
  Q_EMIT this->message(QString());
}

void pqVesselTouchCenterlineWorkflow::onVolumeChanged(pqPipelineSource* volume)
{
  vtkPVDataInformation* data = volume ? volume->getOutputPort(0)->getDataInformation() : nullptr;
  vtkPVArrayInformation* scalars =
    data ? data->GetPointDataInformation()->GetAttributeInformation(vtkDataSetAttributes::SCALARS)
         : nullptr;
  if (volume && !scalars)
  {
    // No data yet (a source created a moment ago): try again when it has updated.
    QObject::connect(volume,
      QOverload<pqPipelineSource*>::of(&pqPipelineSource::dataUpdated),
      this,
      &pqVesselTouchCenterlineWorkflow::onVolumeDataUpdated,
      Qt::UniqueConnection);
    return;
  }
  if (!scalars)
  {
    return;
  }
  double range[2];
  scalars->GetComponentRange(0, range);
  if (range[0] <= range[1])
  {
    this->Ui.lowerThreshold->setValue(0.5 * (range[0] + range[1]));
    this->Ui.upperThreshold->setValue(range[1]);
  }
}

void pqVesselTouchCenterlineWorkflow::onVolumeDataUpdated(pqPipelineSource* volume)
{
  QObject::disconnect(volume, nullptr, this, nullptr);
  if (volume == this->Volumes->currentVolume())
  {
    this->onVolumeChanged(volume);
  }
}

void pqVesselTouchCenterlineWorkflow::extract()
{
  if (!this->HasSeed)
  {
    Q_EMIT this->message(tr("Extract centerlines: pick a seed first."));
    return;
  }
  this->Ui.extractButton->setEnabled(false);
  this->Extraction->extract(this->Volumes->currentVolume(),
    this->Seed_mm,
    this->Ui.lowerThreshold->value(),
    this->Ui.upperThreshold->value());
  this->Ui.extractButton->setEnabled(true);
}

#include "pqVesselTouchVolumeChooser.h"

#include "pqActiveObjects.h"
#include "pqApplicationCore.h"
#include "pqOutputPort.h"
#include "pqPipelineSource.h"
#include "pqServerManagerModel.h"

#include "vtkPVDataInformation.h"
#include "vtkType.h"

#include <QComboBox>
#include <QSignalBlocker>
#include <QTimer>

Q_DECLARE_METATYPE(pqPipelineSource*)

pqVesselTouchVolumeChooser::pqVesselTouchVolumeChooser(QComboBox* combo, QObject* parentObject)
  : QObject(parentObject)
  , Combo(combo)
{
  pqServerManagerModel* model = pqApplicationCore::instance()->getServerManagerModel();
  QObject::connect(
    model, &pqServerManagerModel::sourceAdded, this, &pqVesselTouchVolumeChooser::onSourceAdded);
  QObject::connect(model,
    &pqServerManagerModel::sourceRemoved,
    this,
    [this]() { QTimer::singleShot(0, this, &pqVesselTouchVolumeChooser::refresh); });
  QObject::connect(
    model, &pqServerManagerModel::nameChanged, this, &pqVesselTouchVolumeChooser::refresh);
  QObject::connect(&pqActiveObjects::instance(),
    &pqActiveObjects::sourceChanged,
    this,
    &pqVesselTouchVolumeChooser::onActiveSourceChanged);
  QObject::connect(combo,
    QOverload<int>::of(&QComboBox::currentIndexChanged),
    this,
    [this]() { Q_EMIT this->currentVolumeChanged(this->currentVolume()); });
  for (pqPipelineSource* source : model->findItems<pqPipelineSource*>())
  {
    this->onSourceAdded(source);
  }
  this->refresh();
  this->onActiveSourceChanged(pqActiveObjects::instance().activeSource());
}

pqVesselTouchVolumeChooser::~pqVesselTouchVolumeChooser() = default;

bool pqVesselTouchVolumeChooser::isVolume(pqPipelineSource* source)
{
  if (!source || source->getNumberOfOutputPorts() < 1)
  {
    return false;
  }
  vtkPVDataInformation* info = source->getOutputPort(0)->getDataInformation();
  return info && info->GetDataSetType() == VTK_IMAGE_DATA;
}

pqPipelineSource* pqVesselTouchVolumeChooser::currentVolume() const
{
  return this->Combo ? this->Combo->currentData().value<pqPipelineSource*>() : nullptr;
}

void pqVesselTouchVolumeChooser::setCurrentVolume(pqPipelineSource* source)
{
  if (!this->Combo || !source)
  {
    return;
  }
  const int index = this->Combo->findData(QVariant::fromValue(source));
  if (index >= 0)
  {
    this->Combo->setCurrentIndex(index);
  }
}

void pqVesselTouchVolumeChooser::refresh()
{
  if (!this->Combo)
  {
    return;
  }
  pqPipelineSource* chosen = this->currentVolume();
  {
    const QSignalBlocker blocker(this->Combo);
    this->Combo->clear();
    pqServerManagerModel* model = pqApplicationCore::instance()->getServerManagerModel();
    for (pqPipelineSource* source : model->findItems<pqPipelineSource*>())
    {
      if (isVolume(source))
      {
        this->Combo->addItem(source->getSMName(), QVariant::fromValue(source));
      }
    }
    const int index = this->Combo->findData(QVariant::fromValue(chosen));
    this->Combo->setCurrentIndex(index >= 0 ? index : (this->Combo->count() > 0 ? 0 : -1));
  }
  if (this->currentVolume() != chosen)
  {
    Q_EMIT this->currentVolumeChanged(this->currentVolume());
  }
}

void pqVesselTouchVolumeChooser::onSourceAdded(pqPipelineSource* source)
{
  // A new source has no data information until it updates.
  QObject::connect(source,
    QOverload<pqPipelineSource*>::of(&pqPipelineSource::dataUpdated),
    this,
    &pqVesselTouchVolumeChooser::refresh,
    Qt::UniqueConnection);
}

void pqVesselTouchVolumeChooser::onActiveSourceChanged(pqPipelineSource* source)
{
  if (isVolume(source))
  {
    this->refresh();
    this->setCurrentVolume(source);
  }
}

#include "pqVesselTouchVolumeChooser.h"

#include "pqVesselTouchVolumeCheck.h"

#include "pqActiveObjects.h"
#include "pqApplicationCore.h"
#include "pqPipelineSource.h"
#include "pqServerManagerModel.h"

#include "vtkSMProxy.h"

#include <QComboBox>
#include <QSignalBlocker>
#include <QTimer>

namespace
{
pqServerManagerModel* serverManagerModel()
{
  return pqApplicationCore::instance()->getServerManagerModel();
}

QVariant idOf(pqPipelineSource* source)
{
  return source ? QVariant(static_cast<uint>(source->getProxy()->GetGlobalID())) : QVariant();
}
} // namespace

pqVesselTouchVolumeChooser::pqVesselTouchVolumeChooser(QComboBox* combo, QObject* parentObject)
  : QObject(parentObject)
  , Combo(combo)
{
  pqServerManagerModel* model = serverManagerModel();
  QObject::connect(
    model, &pqServerManagerModel::sourceAdded, this, &pqVesselTouchVolumeChooser::onSourceAdded);
  // The item goes before the source is freed; the rest of the list is rebuilt afterwards.
  QObject::connect(model,
    &pqServerManagerModel::preSourceRemoved,
    this,
    &pqVesselTouchVolumeChooser::onSourceAboutToBeRemoved);
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

pqPipelineSource* pqVesselTouchVolumeChooser::currentVolume() const
{
  if (!this->Combo || this->Combo->currentIndex() < 0)
  {
    return nullptr;
  }
  const QVariant id = this->Combo->currentData();
  return id.isValid() ? serverManagerModel()->findItem<pqPipelineSource*>(
                          static_cast<vtkTypeUInt32>(id.toUInt()))
                      : nullptr;
}

void pqVesselTouchVolumeChooser::setCurrentVolume(pqPipelineSource* source)
{
  if (!this->Combo || !source)
  {
    return;
  }
  const int index = this->Combo->findData(idOf(source));
  if (index >= 0)
  {
    this->Combo->setCurrentIndex(index);
  }
}

QString pqVesselTouchVolumeChooser::problem() const
{
  return this->Problem;
}

void pqVesselTouchVolumeChooser::refresh()
{
  if (!this->Combo)
  {
    return;
  }
  const QVariant chosenId = this->Combo->currentData();
  pqPipelineSource* chosen = this->currentVolume();
  {
    const QSignalBlocker blocker(this->Combo);
    this->Combo->clear();
    for (pqPipelineSource* source : serverManagerModel()->findItems<pqPipelineSource*>())
    {
      if (pqVesselTouchVolumeCheck::problem(source).isEmpty())
      {
        this->Combo->addItem(source->getSMName(), idOf(source));
      }
    }
    const int index = chosenId.isValid() ? this->Combo->findData(chosenId) : -1;
    this->Combo->setCurrentIndex(index >= 0 ? index : (this->Combo->count() > 0 ? 0 : -1));
  }
  if (this->currentVolume() != chosen || this->Combo->currentData() != chosenId)
  {
    Q_EMIT this->currentVolumeChanged(this->currentVolume());
  }
  this->updateProblem();
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

void pqVesselTouchVolumeChooser::onSourceAboutToBeRemoved(pqPipelineSource* source)
{
  if (!this->Combo || !source)
  {
    return;
  }
  QObject::disconnect(source, nullptr, this, nullptr);
  const int index = this->Combo->findData(idOf(source));
  if (index < 0)
  {
    return;
  }
  const bool wasCurrent = index == this->Combo->currentIndex();
  {
    const QSignalBlocker blocker(this->Combo);
    this->Combo->removeItem(index);
    if (wasCurrent)
    {
      this->Combo->setCurrentIndex(-1);
    }
  }
  if (wasCurrent)
  {
    // The panel lets go of everything it derived from this volume now; refresh() (queued by
    // sourceRemoved) then picks another volume if there is one.
    Q_EMIT this->currentVolumeChanged(nullptr);
  }
}

void pqVesselTouchVolumeChooser::onActiveSourceChanged(pqPipelineSource* source)
{
  if (source && pqVesselTouchVolumeCheck::problem(source).isEmpty())
  {
    this->refresh();
    this->setCurrentVolume(source);
  }
  this->updateProblem();
}

void pqVesselTouchVolumeChooser::updateProblem()
{
  QString problem;
  pqPipelineSource* active = pqActiveObjects::instance().activeSource();
  if (active && pqVesselTouchVolumeCheck::isImage(active))
  {
    problem = pqVesselTouchVolumeCheck::problem(active);
  }
  if (problem.isEmpty() && this->Combo && this->Combo->count() == 0)
  {
    // No usable volume: the reason of an image that was left out, else how to get one.
    for (pqPipelineSource* source : serverManagerModel()->findItems<pqPipelineSource*>())
    {
      if (pqVesselTouchVolumeCheck::isImage(source))
      {
        problem = pqVesselTouchVolumeCheck::problem(source);
        break;
      }
    }
    if (problem.isEmpty())
    {
      problem = pqVesselTouchVolumeCheck::problem(nullptr);
    }
  }
  if (problem != this->Problem)
  {
    this->Problem = problem;
    Q_EMIT this->problemChanged(problem);
  }
}

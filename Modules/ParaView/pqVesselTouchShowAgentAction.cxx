#include "pqVesselTouchShowAgentAction.h"

#include "pqVesselTouchAgentDisplay.h"

#include "pqActiveObjects.h"
#include "pqApplicationCore.h"
#include "pqPipelineSource.h"
#include "pqRenderView.h"
#include "pqServerManagerModel.h"

#include "vtkSMProxy.h"

#include <QTimer>

pqVesselTouchShowAgentAction::pqVesselTouchShowAgentAction(QObject* parentObject)
  : QAction(tr("Agent"), parentObject)
{
  this->setObjectName("actionVesselTouchShowAgent");
  this->setCheckable(true);
  this->setToolTip(tr("Draw the haptic session's tracing agent over the MIP in the active view"));
  this->Display = new pqVesselTouchAgentDisplay(this);
  QObject::connect(this, &QAction::toggled, this, &pqVesselTouchShowAgentAction::rebind);
  QObject::connect(&pqActiveObjects::instance(),
    &pqActiveObjects::viewChanged,
    this,
    &pqVesselTouchShowAgentAction::rebind);
  pqServerManagerModel* model = pqApplicationCore::instance()->getServerManagerModel();
  QObject::connect(model,
    &pqServerManagerModel::sourceAdded,
    this,
    [this](pqPipelineSource*)
    { QTimer::singleShot(0, this, &pqVesselTouchShowAgentAction::rebind); });
  QObject::connect(model,
    &pqServerManagerModel::preSourceRemoved,
    this,
    &pqVesselTouchShowAgentAction::onSourceRemoved);
}

pqVesselTouchShowAgentAction::~pqVesselTouchShowAgentAction() = default;

vtkSMProxy* pqVesselTouchShowAgentAction::findSession()
{
  pqServerManagerModel* model = pqApplicationCore::instance()->getServerManagerModel();
  if (auto* named = model->findItem<pqPipelineSource*>(QString("VesselTouchSession")))
  {
    return named->getProxy();
  }
  for (pqPipelineSource* source : model->findItems<pqPipelineSource*>())
  {
    if (QString(source->getProxy()->GetXMLName()) == "VesselTouchHapticSession")
    {
      return source->getProxy();
    }
  }
  return nullptr;
}

void pqVesselTouchShowAgentAction::rebind()
{
  if (!this->isChecked())
  {
    this->Display->setEnabled(false);
    return;
  }
  this->Display->setView(qobject_cast<pqRenderView*>(pqActiveObjects::instance().activeView()));
  this->Display->setSession(findSession());
  this->Display->setEnabled(true);
}

void pqVesselTouchShowAgentAction::onSourceRemoved(pqPipelineSource* source)
{
  if (source && source->getProxy() == this->Display->session())
  {
    this->Display->setSession(nullptr);
    QTimer::singleShot(0, this, &pqVesselTouchShowAgentAction::rebind);
  }
}

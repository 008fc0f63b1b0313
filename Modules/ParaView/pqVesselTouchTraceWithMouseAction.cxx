#include "pqVesselTouchTraceWithMouseAction.h"

#include "pqVesselTouchPointerInteraction.h"
#include "pqVesselTouchShowAgentAction.h"

#include "pqActiveObjects.h"
#include "pqApplicationCore.h"
#include "pqPipelineSource.h"
#include "pqRenderView.h"
#include "pqServerManagerModel.h"

#include "vtkSMProxy.h"

#include <QTimer>

pqVesselTouchTraceWithMouseAction::pqVesselTouchTraceWithMouseAction(QObject* parentObject)
  : QAction(tr("Trace with mouse"), parentObject)
{
  this->setObjectName("actionVesselTouchTraceWithMouse");
  this->setCheckable(true);
  this->setToolTip(tr("Feel the vessels with the mouse (pseudo-haptics): the mouse drives the "
                      "haptic session's pointer device; a left click returns to exploring; "
                      "Ctrl + left drag rotates the view while tracing"));
  this->Interaction = new pqVesselTouchPointerInteraction(this);
  QObject::connect(this, &QAction::toggled, this, &pqVesselTouchTraceWithMouseAction::rebind);
  QObject::connect(&pqActiveObjects::instance(),
    &pqActiveObjects::viewChanged,
    this,
    &pqVesselTouchTraceWithMouseAction::rebind);
  QObject::connect(pqApplicationCore::instance()->getServerManagerModel(),
    &pqServerManagerModel::preSourceRemoved,
    this,
    &pqVesselTouchTraceWithMouseAction::onSourceRemoved);
  // A session created while checked (e.g. by a script) is picked up.
  QObject::connect(pqApplicationCore::instance()->getServerManagerModel(),
    &pqServerManagerModel::sourceAdded,
    this,
    [this](pqPipelineSource*)
    { QTimer::singleShot(0, this, &pqVesselTouchTraceWithMouseAction::rebind); });
}

pqVesselTouchTraceWithMouseAction::~pqVesselTouchTraceWithMouseAction() = default;

void pqVesselTouchTraceWithMouseAction::rebind()
{
  if (!this->isChecked())
  {
    this->Interaction->setEnabled(false);
    return;
  }
  this->Interaction->setView(qobject_cast<pqRenderView*>(pqActiveObjects::instance().activeView()));
  this->Interaction->setSession(pqVesselTouchShowAgentAction::findSession());
  this->Interaction->setEnabled(true);
}

void pqVesselTouchTraceWithMouseAction::onSourceRemoved(pqPipelineSource* source)
{
  if (source && source->getProxy() == pqVesselTouchShowAgentAction::findSession())
  {
    this->Interaction->setSession(nullptr);
    this->setChecked(false);
  }
}

#include "pqVesselTouchToolBar.h"

#include "pqVesselTouchShowAgentAction.h"
#include "pqVesselTouchShowMIPReaction.h"
#include "pqVesselTouchTraceWithMouseAction.h"

#include <QAction>

pqVesselTouchToolBar::pqVesselTouchToolBar(QWidget* parentObject)
  : QToolBar(tr("VesselTouch"), parentObject)
{
  this->setObjectName("VesselTouchToolBar");
  QAction* mip = this->addAction(tr("MIP"));
  mip->setObjectName("actionVesselTouchShowMIP");
  mip->setToolTip(tr("Show the active image as a maximum-intensity projection"));
  new pqVesselTouchShowMIPReaction(mip);
  this->ShowAgent = new pqVesselTouchShowAgentAction(this);
  this->addAction(this->ShowAgent);
  this->TraceWithMouse = new pqVesselTouchTraceWithMouseAction(this);
  this->addAction(this->TraceWithMouse);
}

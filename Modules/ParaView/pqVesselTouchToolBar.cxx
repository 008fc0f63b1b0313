#include "pqVesselTouchToolBar.h"

#include "pqVesselTouchShowAgentAction.h"
#include "pqVesselTouchShowMIPReaction.h"
#include "pqVesselTouchTraceWithMouseAction.h"

#include <QAction>
#include <QIcon>

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
  // Icons, the name and purpose in each tooltip: the three buttons fit beside ParaView's toolbars
  // (text labels pushed "Trace with mouse" into the overflow menu). A missing icon falls back to
  // the text, which a tool button shows when it has no icon.
  mip->setIcon(QIcon(":/VesselTouch/Icons/MIP.svg"));
  this->ShowAgent->setIcon(QIcon(":/VesselTouch/Icons/Agent.svg"));
  this->TraceWithMouse->setIcon(QIcon(":/VesselTouch/Icons/TraceMouse.svg"));
}

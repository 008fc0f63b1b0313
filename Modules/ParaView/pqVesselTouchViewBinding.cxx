#include "pqVesselTouchViewBinding.h"

#include "pqVesselTouchDockPanel.h"
#include "pqVesselTouchShowAgentAction.h"
#include "pqVesselTouchTraceWithMouseAction.h"

#include "pqCoreUtilities.h"
#include "vtkSMPropertyHelper.h"
#include "vtkSMProxy.h"
#include "vtkVesselTouchHapticSession.h"

#include <QWidget>

namespace
{
template<typename Action>
Action* findToolBarAction()
{
  QWidget* mainWindow = pqCoreUtilities::mainWidget();
  return mainWindow ? mainWindow->findChild<Action*>() : nullptr;
}
}

pqVesselTouchViewBinding::pqVesselTouchViewBinding(pqVesselTouchDockPanel* panel)
  : QObject(panel)
{
  QObject::connect(panel,
    &pqVesselTouchDockPanel::sessionProxyChanged,
    this,
    &pqVesselTouchViewBinding::setSession);
  QObject::connect(
    panel, &pqVesselTouchDockPanel::runningChanged, this, &pqVesselTouchViewBinding::setRunning);
}

pqVesselTouchViewBinding::~pqVesselTouchViewBinding() = default;

void pqVesselTouchViewBinding::setSession(vtkSMProxy* session)
{
  this->Session = session;
}

bool pqVesselTouchViewBinding::sessionUsesPointer() const
{
  return this->Session && this->Session->GetProperty("DeviceType") &&
         vtkSMPropertyHelper(this->Session, "DeviceType").GetAsInt() ==
           vtkVesselTouchHapticSession::POINTER;
}

void pqVesselTouchViewBinding::setRunning(bool running)
{
  // The agent is drawn while the session runs; after Stop (or a fault) the cone would show a
  // hand that no longer acts, so it goes with the session.
  if (auto* agent = findToolBarAction<pqVesselTouchShowAgentAction>())
  {
    agent->setChecked(running);
  }
  auto* mouse = findToolBarAction<pqVesselTouchTraceWithMouseAction>();
  if (!mouse)
  {
    return;
  }
  if (running && this->sessionUsesPointer())
  {
    mouse->setChecked(true); // the session already runs with the pointer: no restart
  }
  else if (!running && mouse->isChecked())
  {
    mouse->setChecked(false);
  }
}

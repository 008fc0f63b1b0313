#include "pqVesselTouchSessionStatus.h"

#include "vtkVesselTouchHapticSession.h"

#include "vtouchAgentStateLayout.h"

#include "vtkSMPropertyHelper.h"
#include "vtkSMProxy.h"

#include <QObject>

#include <algorithm>
#include <cmath>

namespace
{
// Indices in AgentStateInfo: the layout of vtouchAgentStateLayout.h.
constexpr unsigned kAgentState = vtouch::AgentFieldState;
constexpr unsigned kAgentPath = vtouch::AgentFieldPath;
constexpr unsigned kAgentPoint = vtouch::AgentFieldPoint;
constexpr unsigned kAgentPositionX = vtouch::AgentFieldPosition_World_mm;
constexpr unsigned kAgentForceX = vtouch::AgentFieldForce_N;

QString stringInfo(vtkSMProxy* session, const char* name)
{
  const char* text = vtkSMPropertyHelper(session, name).GetAsString();
  return text ? QString::fromUtf8(text) : QString();
}
} // namespace

pqVesselTouchSessionStatus pqVesselTouchSessionStatus::read(vtkSMProxy* session)
{
  pqVesselTouchSessionStatus status;
  if (!session)
  {
    return status;
  }
  session->UpdatePropertyInformation();
  vtkSMPropertyHelper sessionInfo(session, "SessionStatusInfo");
  status.running = sessionInfo.GetAsInt(0) != 0;
  status.faultCode = sessionInfo.GetAsInt(1);
  status.skeletonPaths = sessionInfo.GetAsInt(4);
  status.skeletonPoints = sessionInfo.GetAsInt(5);
  status.faultText = stringInfo(session, "FaultInfo");
  status.lastError = stringInfo(session, "LastErrorInfo");
  status.schedulerNotice = stringInfo(session, "SchedulerNoticeInfo");

  vtkSMPropertyHelper stats(session, "StatisticsInfo");
  qVesselTouchLoopStats& loop = status.loop;
  loop.running = status.running;
  loop.nominalRate_Hz = stats.GetAsDouble(0);
  loop.achievedRate_Hz = stats.GetAsDouble(1);
  loop.ticks = static_cast<quint64>(std::max(0.0, stats.GetAsDouble(2)));
  loop.overruns = static_cast<quint64>(std::max(0.0, stats.GetAsDouble(3)));
  loop.periodErrorP50_us = stats.GetAsDouble(5);
  loop.periodErrorP99_us = stats.GetAsDouble(6);
  loop.periodErrorMax_us = stats.GetAsDouble(8);
  loop.tickCostP50_us = stats.GetAsDouble(9);
  loop.tickCostMax_us = stats.GetAsDouble(11);
  loop.realtimeScheduling = vtkSMPropertyHelper(session, "RealTimeSchedulingInfo").GetAsInt() != 0;

  vtkSMPropertyHelper agent(session, "AgentStateInfo");
  loop.tracing = agent.GetAsDouble(kAgentState) > 0.5;
  loop.pathId = loop.tracing ? static_cast<int>(agent.GetAsDouble(kAgentPath)) : -1;
  loop.pointIndex = loop.tracing ? static_cast<int>(agent.GetAsDouble(kAgentPoint)) : -1;
  for (unsigned i = 0; i < 3; ++i)
  {
    status.agentPosition_mm[i] = agent.GetAsDouble(kAgentPositionX + i);
  }
  status.agentForce_N[0] = agent.GetAsDouble(kAgentForceX);
  status.agentForce_N[1] = agent.GetAsDouble(kAgentForceX + 1);

  vtkSMPropertyHelper force(session, "DeviceForceInfo");
  for (unsigned i = 0; i < 3; ++i)
  {
    status.deviceForce_N[i] = force.GetAsDouble(i);
  }

  vtkSMPropertyHelper caps(session, "DeviceCapabilitiesInfo");
  status.deviceOpen = caps.GetAsDouble(0) > 0.5;
  if (status.deviceOpen)
  {
    qVesselTouchDeviceCapabilities& c = status.deviceCapabilities;
    c.name = stringInfo(session, "DeviceNameInfo");
    c.sensedDof = static_cast<int>(caps.GetAsDouble(1));
    c.actuatedDof = static_cast<int>(caps.GetAsDouble(2));
    c.workspaceX_mm = caps.GetAsDouble(3);
    c.workspaceY_mm = caps.GetAsDouble(4);
    c.workspaceZ_mm = caps.GetAsDouble(5);
    c.maxContinuousForce_N = caps.GetAsDouble(6);
    c.maxStiffness_N_per_m = caps.GetAsDouble(7);
    c.maxUpdateRate_Hz = caps.GetAsDouble(8);
    c.hasPressure = caps.GetAsDouble(9) > 0.5;
    c.buttonCount = static_cast<int>(caps.GetAsDouble(11));

    vtkSMPropertyHelper calibration(session, "DeviceCalibrationInfo");
    const int axes = std::min(
      static_cast<int>(calibration.GetAsDouble(0)), qVesselTouchDeviceCalibration::kAxisCount);
    status.deviceHasCalibration = axes > 0;
    for (int i = 0; i < axes; ++i)
    {
      qVesselTouchDeviceCalibration::Axis& axis = status.deviceCalibration.axes[i];
      const unsigned first = 1 + 4 * static_cast<unsigned>(i);
      axis.rawMinimum = calibration.GetAsDouble(first);
      axis.rawMaximum = calibration.GetAsDouble(first + 1);
      axis.minimum_mm = calibration.GetAsDouble(first + 2);
      axis.maximum_mm = calibration.GetAsDouble(first + 3);
    }
  }
  return status;
}

QString pqVesselTouchSessionStatus::summary() const
{
  if (!this->running)
  {
    return QObject::tr("Stopped");
  }
  if (this->loop.tracing)
  {
    return QObject::tr("Running: tracing path %1, point %2")
      .arg(this->loop.pathId)
      .arg(this->loop.pointIndex);
  }
  return QObject::tr("Running: exploring");
}

double pqVesselTouchSessionStatus::deviceForceMagnitude_N() const
{
  return std::sqrt(this->deviceForce_N[0] * this->deviceForce_N[0] +
                   this->deviceForce_N[1] * this->deviceForce_N[1] +
                   this->deviceForce_N[2] * this->deviceForce_N[2]);
}

bool pqVesselTouchSessionStatus::deviceFault() const
{
  return this->faultCode != 0 &&
    this->faultCode != vtkVesselTouchHapticSession::CONNECTION_LOST_FAULT;
}

#include "qVesselTouchDeviceCapabilities.h"

#include <QVariantList>

qVesselTouchDeviceCapabilities qVesselTouchDeviceCapabilities::fromVariantMap(
  const QVariantMap& map)
{
  qVesselTouchDeviceCapabilities c;
  const auto number = [&map](const char* key, double fallback)
  {
    const QVariant v = map.value(QString::fromLatin1(key));
    return v.isValid() ? v.toDouble() : fallback;
  };
  c.name = map.value(QStringLiteral("name"), c.name).toString();
  c.sensedDof = int(number("sensedDof", c.sensedDof));
  c.actuatedDof = int(number("actuatedDof", c.actuatedDof));
  const QVariantList workspace = map.value(QStringLiteral("workspace_mm")).toList();
  if (workspace.size() == 3)
  {
    c.workspaceX_mm = workspace[0].toDouble();
    c.workspaceY_mm = workspace[1].toDouble();
    c.workspaceZ_mm = workspace[2].toDouble();
  }
  c.workspaceX_mm = number("workspaceX_mm", c.workspaceX_mm);
  c.workspaceY_mm = number("workspaceY_mm", c.workspaceY_mm);
  c.workspaceZ_mm = number("workspaceZ_mm", c.workspaceZ_mm);
  c.maxContinuousForce_N = number("maxContinuousForce_N", c.maxContinuousForce_N);
  c.maxStiffness_N_per_m = number("maxStiffness_N_per_m", c.maxStiffness_N_per_m);
  c.maxUpdateRate_Hz = number("maxUpdateRate_Hz", c.maxUpdateRate_Hz);
  c.hasPressure = map.value(QStringLiteral("hasPressure"), c.hasPressure).toBool();
  c.buttonCount = int(number("buttonCount", c.buttonCount));
  return c;
}

QVariantMap qVesselTouchDeviceCapabilities::toVariantMap() const
{
  return {
    { QStringLiteral("name"), this->name },
    { QStringLiteral("sensedDof"), this->sensedDof },
    { QStringLiteral("actuatedDof"), this->actuatedDof },
    { QStringLiteral("workspaceX_mm"), this->workspaceX_mm },
    { QStringLiteral("workspaceY_mm"), this->workspaceY_mm },
    { QStringLiteral("workspaceZ_mm"), this->workspaceZ_mm },
    { QStringLiteral("maxContinuousForce_N"), this->maxContinuousForce_N },
    { QStringLiteral("maxStiffness_N_per_m"), this->maxStiffness_N_per_m },
    { QStringLiteral("maxUpdateRate_Hz"), this->maxUpdateRate_Hz },
    { QStringLiteral("hasPressure"), this->hasPressure },
    { QStringLiteral("buttonCount"), this->buttonCount },
  };
}

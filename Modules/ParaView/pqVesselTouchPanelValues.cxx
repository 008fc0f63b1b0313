#include "pqVesselTouchPanelValues.h"

#include "vtkSMProperty.h"
#include "vtkSMPropertyHelper.h"
#include "vtkSMProxy.h"

#include <QSettings>

namespace
{
constexpr int kLdgf = 0;
constexpr int kChangeOfHeight = 1;
constexpr int kLateralGradient = 2;
const QString kPrefix = QStringLiteral("VesselTouch/");
/// The session properties writeToProxy() sets (HidPath aside).
const char* const kProxyProperties[] = { "ForceLaw",
  "LdgfLambda",
  "ChangeOfHeightLambda",
  "ChangeOfHeightZMax",
  "ChangeOfHeightForgetTime",
  "LateralProbe",
  "ProxyStiffness",
  "ProxyDamping",
  "ProxyTangentDrag",
  "ProxyTangentThreshold",
  "ProxySnapDrag",
  "ProxySnapThreshold",
  "ZoneGain",
  "ZoneZeroBelow",
  "ZoneSaturateAbove",
  "Zoom",
  "DeviceType",
  "ProxyKappaLow",
  "ProxyKappaHigh",
  "TracerRule",
  "TracerMovementThreshold",
  "TracerJunctionWindow",
  "TracerJunctionMargin",
  "ContactDwell",
  "ContactApproachAtStart",
  "SlopeForceBudget",
  "ForceInterpolationPerAxis",
  "ChangeOfHeightZMaxPerResolution",
  "ProxyTangentSnap",
  "ProxyNormalUnilateral",
  "ProxyThresholdFromData",
  "ProxyFriction",
  "ProxyTickSpacing",
  "ProxyTickForce",
  "ProxyTickAtBifurcations",
  "ProxyFieldForce",
  "IdleRadius",
  "IdleDwell",
  "IdleRamp" };

/// The tick options' session properties (int properties hold the bools and the rule).
struct TickProperty
{
  const char* name;
  double qVesselTouchTickOptions::*value;
  bool qVesselTouchTickOptions::*flag;
};
const TickProperty kTickProperties[] = {
  { "TracerMovementThreshold", &qVesselTouchTickOptions::tracerMovementThreshold_px, nullptr },
  { "TracerJunctionWindow", &qVesselTouchTickOptions::tracerJunctionWindow_px, nullptr },
  { "TracerJunctionMargin", &qVesselTouchTickOptions::tracerJunctionMargin_px, nullptr },
  { "ContactDwell", &qVesselTouchTickOptions::contactDwell_s, nullptr },
  { "ContactApproachAtStart", nullptr, &qVesselTouchTickOptions::contactApproachAtStart },
  { "SlopeForceBudget", &qVesselTouchTickOptions::slopeForceBudget, nullptr },
  { "ForceInterpolationPerAxis", nullptr, &qVesselTouchTickOptions::forceInterpolationPerAxis },
  { "ChangeOfHeightZMaxPerResolution", &qVesselTouchTickOptions::cohZMaxPerResolution, nullptr },
  { "ProxyTangentSnap", nullptr, &qVesselTouchTickOptions::proxyTangentSnap },
  { "ProxyNormalUnilateral", nullptr, &qVesselTouchTickOptions::proxyNormalUnilateral },
  { "ProxyThresholdFromData", nullptr, &qVesselTouchTickOptions::proxyThresholdFromData },
  { "ProxyFriction", &qVesselTouchTickOptions::proxyFriction, nullptr },
  { "ProxyTickSpacing", &qVesselTouchTickOptions::proxyTickSpacing_mm, nullptr },
  { "ProxyTickForce", &qVesselTouchTickOptions::proxyTickForce_N, nullptr },
  { "ProxyTickAtBifurcations", nullptr, &qVesselTouchTickOptions::proxyTickAtBifurcations },
  { "ProxyFieldForce", nullptr, &qVesselTouchTickOptions::proxyFieldForce },
  { "IdleRadius", &qVesselTouchTickOptions::idleRadius_mm, nullptr },
  { "IdleDwell", &qVesselTouchTickOptions::idleDwell_s, nullptr },
  { "IdleRamp", &qVesselTouchTickOptions::idleRamp_s, nullptr },
};

template<typename T>
void loadValue(const QSettings& settings, const char* key, T& value)
{
  const QVariant stored = settings.value(kPrefix + QLatin1String(key));
  if (stored.isValid() && stored.canConvert<T>())
  {
    value = stored.value<T>();
  }
}
} // namespace

double pqVesselTouchPanelValues::activeGain_N(double fallback_N) const
{
  switch (this->forceLaw)
  {
    case kLdgf:
      return this->law.ldgfGain_N;
    case kChangeOfHeight:
      return this->law.cohGain_N;
    case kLateralGradient:
      return this->law.lateralGain_N;
    default:
      return fallback_N;
  }
}

void pqVesselTouchPanelValues::setActiveGain_N(double gain_N)
{
  switch (this->forceLaw)
  {
    case kLdgf:
      this->law.ldgfGain_N = gain_N;
      break;
    case kChangeOfHeight:
      this->law.cohGain_N = gain_N;
      break;
    case kLateralGradient:
      this->law.lateralGain_N = gain_N;
      break;
    default:
      break;
  }
}

void pqVesselTouchPanelValues::writeToProxy(vtkSMProxy* session, double zoneGain_N) const
{
  if (!session)
  {
    return;
  }
  vtkSMPropertyHelper(session, "ForceLaw").Set(this->forceLaw);
  vtkSMPropertyHelper(session, "LdgfLambda").Set(this->law.ldgfLambda_mm);
  vtkSMPropertyHelper(session, "ChangeOfHeightLambda").Set(this->law.cohLambda_mm);
  vtkSMPropertyHelper(session, "ChangeOfHeightZMax").Set(this->law.cohZMax_mm);
  vtkSMPropertyHelper(session, "ChangeOfHeightForgetTime").Set(this->law.cohForgetTime_s);
  vtkSMPropertyHelper(session, "LateralProbe").Set(this->law.lateralProbe_px);
  vtkSMPropertyHelper(session, "ProxyStiffness").Set(this->law.proxyStiffness_N_per_m);
  vtkSMPropertyHelper(session, "ProxyDamping").Set(this->law.proxyDamping_N_s_per_m);
  vtkSMPropertyHelper(session, "ProxyTangentDrag").Set(this->law.proxyTangentDrag ? 1 : 0);
  vtkSMPropertyHelper(session, "ProxyTangentThreshold").Set(this->law.proxyTangentThreshold_N);
  vtkSMPropertyHelper(session, "ProxySnapDrag").Set(this->law.proxySnapDrag ? 1 : 0);
  vtkSMPropertyHelper(session, "ProxySnapThreshold").Set(this->law.proxySnapThreshold_N);
  vtkSMPropertyHelper(session, "ProxyKappaLow").Set(this->law.proxyKappaLow);
  vtkSMPropertyHelper(session, "ProxyKappaHigh").Set(this->law.proxyKappaHigh);
  vtkSMPropertyHelper(session, "TracerRule").Set(this->tick.tracerRule);
  for (const TickProperty& p : kTickProperties)
  {
    if (p.value)
    {
      vtkSMPropertyHelper(session, p.name).Set(this->tick.*(p.value));
    }
    else
    {
      vtkSMPropertyHelper(session, p.name).Set(this->tick.*(p.flag) ? 1 : 0);
    }
  }
  vtkSMPropertyHelper(session, "ZoneGain").Set(zoneGain_N);
  vtkSMPropertyHelper(session, "ZoneZeroBelow").Set(this->zoneZeroBelow);
  vtkSMPropertyHelper(session, "ZoneSaturateAbove").Set(this->zoneSaturateAbove);
  vtkSMPropertyHelper(session, "Zoom").Set(this->zoom);
  vtkSMPropertyHelper(session, "DeviceType").Set(deviceType(this->deviceId));
  const QString path = hidPath(this->deviceId);
  if (!path.isEmpty())
  {
    vtkSMPropertyHelper(session, "HidPath").Set(path.toUtf8().constData());
  }
}

double pqVesselTouchPanelValues::readFromProxy(vtkSMProxy* session)
{
  if (!session)
  {
    return this->activeGain_N(1.0);
  }
  this->forceLaw = vtkSMPropertyHelper(session, "ForceLaw").GetAsInt();
  this->law.ldgfLambda_mm = vtkSMPropertyHelper(session, "LdgfLambda").GetAsDouble();
  this->law.cohLambda_mm = vtkSMPropertyHelper(session, "ChangeOfHeightLambda").GetAsDouble();
  this->law.cohZMax_mm = vtkSMPropertyHelper(session, "ChangeOfHeightZMax").GetAsDouble();
  this->law.cohForgetTime_s =
    vtkSMPropertyHelper(session, "ChangeOfHeightForgetTime").GetAsDouble();
  this->law.lateralProbe_px = vtkSMPropertyHelper(session, "LateralProbe").GetAsDouble();
  this->law.proxyStiffness_N_per_m = vtkSMPropertyHelper(session, "ProxyStiffness").GetAsDouble();
  this->law.proxyDamping_N_s_per_m = vtkSMPropertyHelper(session, "ProxyDamping").GetAsDouble();
  this->law.proxyTangentDrag = vtkSMPropertyHelper(session, "ProxyTangentDrag").GetAsInt() != 0;
  this->law.proxyTangentThreshold_N =
    vtkSMPropertyHelper(session, "ProxyTangentThreshold").GetAsDouble();
  this->law.proxySnapDrag = vtkSMPropertyHelper(session, "ProxySnapDrag").GetAsInt() != 0;
  this->law.proxySnapThreshold_N = vtkSMPropertyHelper(session, "ProxySnapThreshold").GetAsDouble();
  this->law.proxyKappaLow = vtkSMPropertyHelper(session, "ProxyKappaLow").GetAsDouble();
  this->law.proxyKappaHigh = vtkSMPropertyHelper(session, "ProxyKappaHigh").GetAsDouble();
  this->tick.tracerRule = vtkSMPropertyHelper(session, "TracerRule").GetAsInt();
  for (const TickProperty& p : kTickProperties)
  {
    if (p.value)
    {
      this->tick.*(p.value) = vtkSMPropertyHelper(session, p.name).GetAsDouble();
    }
    else
    {
      this->tick.*(p.flag) = vtkSMPropertyHelper(session, p.name).GetAsInt() != 0;
    }
  }
  const double zoneGain_N = vtkSMPropertyHelper(session, "ZoneGain").GetAsDouble();
  this->setActiveGain_N(zoneGain_N);
  this->zoneZeroBelow = vtkSMPropertyHelper(session, "ZoneZeroBelow").GetAsDouble();
  this->zoneSaturateAbove = vtkSMPropertyHelper(session, "ZoneSaturateAbove").GetAsDouble();
  this->zoom = vtkSMPropertyHelper(session, "Zoom").GetAsDouble();
  switch (vtkSMPropertyHelper(session, "DeviceType").GetAsInt())
  {
    case 1:
      this->deviceId = QStringLiteral("pointer");
      break;
    case 2:
      this->deviceId = QStringLiteral("replay");
      break;
    case 3:
      this->deviceId = QStringLiteral("hid:") +
                       QString::fromUtf8(vtkSMPropertyHelper(session, "HidPath").GetAsString());
      break;
    default:
      this->deviceId = QStringLiteral("simulated");
      break;
  }
  return zoneGain_N;
}

void pqVesselTouchPanelValues::save(QSettings& settings) const
{
  settings.setValue(kPrefix + "ForceLaw", this->forceLaw);
  settings.setValue(kPrefix + "LdgfGain_N", this->law.ldgfGain_N);
  settings.setValue(kPrefix + "LdgfLambda_mm", this->law.ldgfLambda_mm);
  settings.setValue(kPrefix + "CohGain_N", this->law.cohGain_N);
  settings.setValue(kPrefix + "CohLambda_mm", this->law.cohLambda_mm);
  settings.setValue(kPrefix + "CohZMax_mm", this->law.cohZMax_mm);
  settings.setValue(kPrefix + "CohForgetTime_s", this->law.cohForgetTime_s);
  settings.setValue(kPrefix + "LateralGain_N", this->law.lateralGain_N);
  settings.setValue(kPrefix + "LateralProbe_px", this->law.lateralProbe_px);
  settings.setValue(kPrefix + "ProxyStiffness_N_per_m", this->law.proxyStiffness_N_per_m);
  settings.setValue(kPrefix + "ProxyDamping_N_s_per_m", this->law.proxyDamping_N_s_per_m);
  settings.setValue(kPrefix + "ProxyTangentDrag", this->law.proxyTangentDrag);
  settings.setValue(kPrefix + "ProxyTangentThreshold_N", this->law.proxyTangentThreshold_N);
  settings.setValue(kPrefix + "ProxySnapDrag", this->law.proxySnapDrag);
  settings.setValue(kPrefix + "ProxySnapThreshold_N", this->law.proxySnapThreshold_N);
  settings.setValue(kPrefix + "Zoom", this->zoom);
  settings.setValue(kPrefix + "ZoneZeroBelow", this->zoneZeroBelow);
  settings.setValue(kPrefix + "ZoneSaturateAbove", this->zoneSaturateAbove);
  settings.setValue(kPrefix + "Device", this->deviceId);
  settings.setValue(kPrefix + "ProxyKappaLow", this->law.proxyKappaLow);
  settings.setValue(kPrefix + "ProxyKappaHigh", this->law.proxyKappaHigh);
  settings.setValue(kPrefix + "TracerRule", this->tick.tracerRule);
  for (const TickProperty& p : kTickProperties)
  {
    settings.setValue(
      kPrefix + p.name, p.value ? QVariant(this->tick.*(p.value)) : QVariant(this->tick.*(p.flag)));
  }
}

void pqVesselTouchPanelValues::load(const QSettings& settings)
{
  loadValue(settings, "ForceLaw", this->forceLaw);
  loadValue(settings, "LdgfGain_N", this->law.ldgfGain_N);
  loadValue(settings, "LdgfLambda_mm", this->law.ldgfLambda_mm);
  loadValue(settings, "CohGain_N", this->law.cohGain_N);
  loadValue(settings, "CohLambda_mm", this->law.cohLambda_mm);
  loadValue(settings, "CohZMax_mm", this->law.cohZMax_mm);
  loadValue(settings, "CohForgetTime_s", this->law.cohForgetTime_s);
  loadValue(settings, "LateralGain_N", this->law.lateralGain_N);
  loadValue(settings, "LateralProbe_px", this->law.lateralProbe_px);
  loadValue(settings, "ProxyStiffness_N_per_m", this->law.proxyStiffness_N_per_m);
  loadValue(settings, "ProxyDamping_N_s_per_m", this->law.proxyDamping_N_s_per_m);
  loadValue(settings, "ProxyTangentDrag", this->law.proxyTangentDrag);
  loadValue(settings, "ProxyTangentThreshold_N", this->law.proxyTangentThreshold_N);
  loadValue(settings, "ProxySnapDrag", this->law.proxySnapDrag);
  loadValue(settings, "ProxySnapThreshold_N", this->law.proxySnapThreshold_N);
  loadValue(settings, "Zoom", this->zoom);
  loadValue(settings, "ZoneZeroBelow", this->zoneZeroBelow);
  loadValue(settings, "ZoneSaturateAbove", this->zoneSaturateAbove);
  loadValue(settings, "Device", this->deviceId);
  loadValue(settings, "ProxyKappaLow", this->law.proxyKappaLow);
  loadValue(settings, "ProxyKappaHigh", this->law.proxyKappaHigh);
  loadValue(settings, "TracerRule", this->tick.tracerRule);
  for (const TickProperty& p : kTickProperties)
  {
    if (p.value)
    {
      loadValue(settings, p.name, this->tick.*(p.value));
    }
    else
    {
      loadValue(settings, p.name, this->tick.*(p.flag));
    }
  }
}

bool pqVesselTouchPanelValues::proxyHasDefaults(vtkSMProxy* session)
{
  if (!session)
  {
    return false;
  }
  for (const char* name : kProxyProperties)
  {
    vtkSMProperty* property = session->GetProperty(name);
    if (property && !property->IsValueDefault())
    {
      return false;
    }
  }
  return true;
}

int pqVesselTouchPanelValues::deviceType(const QString& deviceId)
{
  if (deviceId == QLatin1String("pointer"))
  {
    return 1;
  }
  if (deviceId == QLatin1String("replay"))
  {
    return 2;
  }
  if (deviceId.startsWith(QLatin1String("hid")))
  {
    return 3;
  }
  return 0;
}

QString pqVesselTouchPanelValues::hidPath(const QString& deviceId)
{
  return deviceId.startsWith(QLatin1String("hid:")) ? deviceId.mid(4) : QString();
}

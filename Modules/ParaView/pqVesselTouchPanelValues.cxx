#include "pqVesselTouchPanelValues.h"

#include "vtkSMProperty.h"
#include "vtkSMPropertyHelper.h"
#include "vtkSMProxy.h"

#include <QSettings>

#include <limits>

namespace
{
using vtouch::HapticParameterDescriptor;
constexpr int kLdgf = 0;
constexpr int kChangeOfHeight = 1;
constexpr int kLateralGradient = 2;
const QString kPrefix = QStringLiteral("VesselTouch/");
/// The per-law gains under their settings keys (the session has one gain, ZoneGain).
struct GainKey
{
  const char* Key;
  double qVesselTouchForceLawParameters::*Gain;
};
const GainKey kGainKeys[] = { { "LdgfGain_N", &qVesselTouchForceLawParameters::ldgfGain_N },
  { "CohGain_N", &qVesselTouchForceLawParameters::cohGain_N },
  { "LateralGain_N", &qVesselTouchForceLawParameters::lateralGain_N } };

/// A stored value of `key`, or NaN when there is none.
double storedValue(const QSettings& settings, const QString& key)
{
  bool ok = false;
  const double value = settings.value(kPrefix + key).toDouble(&ok);
  return ok ? value : std::numeric_limits<double>::quiet_NaN();
}
} // namespace

int pqVesselTouchPanelValues::forceLaw() const
{
  return static_cast<int>(this->law.haptic.forceLaw);
}

double pqVesselTouchPanelValues::activeGain_N(double fallback_N) const
{
  switch (this->forceLaw())
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
  switch (this->forceLaw())
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
  vtouch::HapticParameters haptic = this->law.haptic;
  haptic.zoneGain_N = zoneGain_N;
  for (const HapticParameterDescriptor& d : vtouch::kHapticParameterDescriptors)
  {
    if (d.kind == vtouch::HapticParameterKind::Real)
    {
      vtkSMPropertyHelper(session, d.name).Set(d.get(haptic));
    }
    else
    {
      vtkSMPropertyHelper(session, d.name).Set(static_cast<int>(d.get(haptic)));
    }
  }
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
    return this->activeGain_N(qVesselTouchForceLawParameters::defaultGain_N());
  }
  for (const HapticParameterDescriptor& d : vtouch::kHapticParameterDescriptors)
  {
    const double value = vtkSMPropertyHelper(session, d.name).GetAsDouble();
    if (vtouch::checkHapticParameter(d, value).empty())
    {
      d.set(this->law.haptic, value);
    }
  }
  const double zoneGain_N = this->law.haptic.zoneGain_N;
  this->setActiveGain_N(zoneGain_N);
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
  for (const HapticParameterDescriptor& d : vtouch::kHapticParameterDescriptors)
  {
    settings.setValue(kPrefix + QLatin1String(d.name), d.get(this->law.haptic));
  }
  for (const GainKey& gain : kGainKeys)
  {
    settings.setValue(kPrefix + QLatin1String(gain.Key), this->law.*(gain.Gain));
  }
  settings.setValue(kPrefix + "Device", this->deviceId);
}

void pqVesselTouchPanelValues::load(const QSettings& settings)
{
  for (const HapticParameterDescriptor& d : vtouch::kHapticParameterDescriptors)
  {
    const double value = storedValue(settings, QLatin1String(d.name));
    if (vtouch::checkHapticParameter(d, value).empty())
    {
      d.set(this->law.haptic, value);
    }
  }
  const HapticParameterDescriptor& gainRow =
    vtouch::hapticParameter(vtouch::HapticParameterId::ZoneGain);
  for (const GainKey& gain : kGainKeys)
  {
    const double value = storedValue(settings, QLatin1String(gain.Key));
    if (vtouch::checkHapticParameter(gainRow, value).empty())
    {
      this->law.*(gain.Gain) = value;
    }
  }
  const QVariant device = settings.value(kPrefix + "Device");
  if (device.isValid())
  {
    this->deviceId = device.toString();
  }
}

bool pqVesselTouchPanelValues::proxyHasDefaults(vtkSMProxy* session)
{
  if (!session)
  {
    return false;
  }
  for (const HapticParameterDescriptor& d : vtouch::kHapticParameterDescriptors)
  {
    vtkSMProperty* property = session->GetProperty(d.name);
    if (property && !property->IsValueDefault())
    {
      return false;
    }
  }
  vtkSMProperty* device = session->GetProperty("DeviceType");
  return !device || device->IsValueDefault();
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

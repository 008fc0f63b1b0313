// One entry of the device list the module offers (pointer, simulated, replay, each HID device).
#ifndef qVesselTouchDeviceEntry_h
#define qVesselTouchDeviceEntry_h

#include <QString>
#include <QVariantMap>

struct qVesselTouchDeviceEntry
{
  /// Stable identifier the module understands, e.g. "pointer", "simulated", "hid:/dev/hidraw3".
  QString id;
  /// What the user reads in the list, e.g. "OpenFFBoard (2 axes)". Empty shows the id.
  QString label;
  /// Device family: "pointer", "simulated", "replay" or "hid" (free text; shown as a hint).
  QString kind;

  /// From a map with the keys "id", "label" and "kind" (what Python or settings hand over).
  static qVesselTouchDeviceEntry fromVariantMap(const QVariantMap& map)
  {
    return { map.value(QStringLiteral("id")).toString(),
      map.value(QStringLiteral("label")).toString(),
      map.value(QStringLiteral("kind")).toString() };
  }
  QVariantMap toVariantMap() const
  {
    return { { QStringLiteral("id"), this->id },
      { QStringLiteral("label"), this->label },
      { QStringLiteral("kind"), this->kind } };
  }
  bool operator==(const qVesselTouchDeviceEntry& o) const
  {
    return this->id == o.id && this->label == o.label && this->kind == o.kind;
  }
};

#endif

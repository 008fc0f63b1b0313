// Picks the haptic device (pointer, simulated, replay, each HID device found), shows its status,
// capabilities and calibration, and a clear red fault message when it fails.
// Pure Qt: the module glue fills the list, feeds status/capabilities/calibration/faults from the
// device layer and acts on deviceSelected(). Capabilities and calibration show for HID devices
// only; the calibration is a read-only display of what the open device applies (its preset), and
// shows only once the host gave it.
#ifndef qVesselTouchDeviceWidget_h
#define qVesselTouchDeviceWidget_h

#include "qVesselTouchDeviceCalibration.h"
#include "qVesselTouchDeviceCapabilities.h"
#include "qVesselTouchDeviceEntry.h"

#include <QList>
#include <QScopedPointer>
#include <QVariantList>
#include <QWidget>

class qVesselTouchDeviceWidgetPrivate;

class qVesselTouchDeviceWidget : public QWidget
{
  Q_OBJECT
  Q_PROPERTY(
    QString currentDeviceId READ currentDeviceId WRITE setCurrentDeviceId NOTIFY deviceSelected)
  Q_PROPERTY(QString statusText READ statusText WRITE setStatusText)
  Q_PROPERTY(QString faultMessage READ faultMessage WRITE setFault RESET clearFault)
public:
  explicit qVesselTouchDeviceWidget(QWidget* parent = nullptr);
  ~qVesselTouchDeviceWidget() override;

  /// Replaces the device list. The current device stays selected if its id is still listed;
  /// otherwise the first entry is selected (or none for an empty list) and deviceSelected() is
  /// emitted. Default: empty list.
  void setAvailableDevices(const QList<qVesselTouchDeviceEntry>& devices);
  /// Same, from a list of maps with the keys "id", "label", "kind".
  void setAvailableDeviceMaps(const QVariantList& devices);
  QList<qVesselTouchDeviceEntry> availableDevices() const;

  /// Id of the selected device, empty when the list is empty.
  QString currentDeviceId() const;

  /// One line of status from the device layer, e.g. "connected, 1000 Hz". Default "not connected".
  QString statusText() const;

  /// Capabilities shown in the form. Default: a default-constructed struct (shown as unknown).
  void setCapabilities(const qVesselTouchDeviceCapabilities& capabilities);
  /// Same, from a map (see qVesselTouchDeviceCapabilities::fromVariantMap).
  void setCapabilityMap(const QVariantMap& capabilities);
  qVesselTouchDeviceCapabilities capabilities() const;
  /// Empties the capability form ("-"), e.g. while no device is open.
  void clearCapabilities();

  /// The open device's raw-to-millimetre calibration per axis, shown read-only (HID devices only).
  void setCalibration(const qVesselTouchDeviceCalibration& calibration);
  /// No calibration known (no device open, or one without): the group hides. The default.
  void clearCalibration();
  qVesselTouchDeviceCalibration calibration() const;
  bool hasCalibration() const;

  /// The fault shown in red, empty when none.
  QString faultMessage() const;
  bool hasFault() const;

public slots:
  /// Selects a listed device; emits deviceSelected() when the selection changes. Unknown ids are
  /// ignored (with a warning).
  void setCurrentDeviceId(const QString& id);
  void setStatusText(const QString& text);
  /// Shows `message` in red above everything else (an empty message clears the fault).
  void setFault(const QString& message);
  /// Hides the fault message.
  void clearFault();

signals:
  /// The user (or setCurrentDeviceId / a list change) selected another device.
  void deviceSelected(const QString& id);
  /// A fault was shown (true) or cleared (false).
  void faultChanged(bool hasFault);

private:
  QScopedPointer<qVesselTouchDeviceWidgetPrivate> d_ptr;
  Q_DECLARE_PRIVATE(qVesselTouchDeviceWidget);
  Q_DISABLE_COPY(qVesselTouchDeviceWidget);
};

#endif

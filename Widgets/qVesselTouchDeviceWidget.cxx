#include "qVesselTouchDeviceWidget.h"

#include "ui_qVesselTouchDeviceWidget.h"

#include <QDoubleSpinBox>
#include <QSignalBlocker>

namespace
{
// The spin boxes of one calibration axis, in the order of qVesselTouchDeviceCalibration::Axis.
struct AxisBoxes
{
  QDoubleSpinBox* RawMinimum;
  QDoubleSpinBox* RawMaximum;
  QDoubleSpinBox* Minimum;
  QDoubleSpinBox* Maximum;
};

QString number(double value, int decimals)
{
  return QString::number(value, 'f', decimals);
}
} // namespace

class qVesselTouchDeviceWidgetPrivate
{
public:
  Ui::qVesselTouchDeviceWidget Ui;
  QList<qVesselTouchDeviceEntry> Devices;
  QString CurrentId;
  QString FaultMessage; // empty when no fault is shown
  qVesselTouchDeviceCapabilities Capabilities;
  qVesselTouchDeviceCalibration Calibration;
  /// The host gave the open device's calibration (setCalibration): the group may show.
  bool HasCalibration = false;
  AxisBoxes Axes[qVesselTouchDeviceCalibration::kAxisCount];

  void showCalibration();
  void readCalibration();
  bool isHardware() const;
  void showCapabilities(bool known);
  void showKind();
};

void qVesselTouchDeviceWidgetPrivate::showCalibration()
{
  for (int i = 0; i < qVesselTouchDeviceCalibration::kAxisCount; ++i)
  {
    const qVesselTouchDeviceCalibration::Axis& axis = this->Calibration.axes[i];
    const AxisBoxes& boxes = this->Axes[i];
    for (QDoubleSpinBox* box : { boxes.RawMinimum, boxes.RawMaximum, boxes.Minimum, boxes.Maximum })
    {
      box->blockSignals(true);
    }
    boxes.RawMinimum->setValue(axis.rawMinimum);
    boxes.RawMaximum->setValue(axis.rawMaximum);
    boxes.Minimum->setValue(axis.minimum_mm);
    boxes.Maximum->setValue(axis.maximum_mm);
    for (QDoubleSpinBox* box : { boxes.RawMinimum, boxes.RawMaximum, boxes.Minimum, boxes.Maximum })
    {
      box->blockSignals(false);
    }
  }
}

void qVesselTouchDeviceWidgetPrivate::readCalibration()
{
  for (int i = 0; i < qVesselTouchDeviceCalibration::kAxisCount; ++i)
  {
    qVesselTouchDeviceCalibration::Axis& axis = this->Calibration.axes[i];
    const AxisBoxes& boxes = this->Axes[i];
    axis.rawMinimum = boxes.RawMinimum->value();
    axis.rawMaximum = boxes.RawMaximum->value();
    axis.minimum_mm = boxes.Minimum->value();
    axis.maximum_mm = boxes.Maximum->value();
  }
}

void qVesselTouchDeviceWidgetPrivate::showCapabilities(bool known)
{
  const qVesselTouchDeviceCapabilities& c = this->Capabilities;
  const QString unknown = QStringLiteral("-");
  const auto orUnknown = [&](double value, int decimals, const QString& unit)
  { return known && value > 0.0 ? number(value, decimals) + unit : unknown; };
  Ui::qVesselTouchDeviceWidget& ui = this->Ui;
  ui.nameValue->setText(known && !c.name.isEmpty() ? c.name : unknown);
  ui.dofValue->setText(
    known ? QObject::tr("%1 sensed, %2 actuated").arg(c.sensedDof).arg(c.actuatedDof) : unknown);
  ui.workspaceValue->setText(
    known
      ? QStringLiteral("%1 × %2 × %3 mm")
          .arg(number(c.workspaceX_mm, 0), number(c.workspaceY_mm, 0), number(c.workspaceZ_mm, 0))
      : unknown);
  ui.maxForceValue->setText(orUnknown(c.maxContinuousForce_N, 2, QStringLiteral(" N")));
  ui.maxStiffnessValue->setText(orUnknown(c.maxStiffness_N_per_m, 0, QStringLiteral(" N/m")));
  ui.rateValue->setText(orUnknown(c.maxUpdateRate_Hz, 0, QStringLiteral(" Hz")));
  ui.pressureValue->setText(
    known ? (c.hasPressure ? QObject::tr("yes") : QObject::tr("no")) : unknown);
  ui.buttonsValue->setText(known ? QString::number(c.buttonCount) : unknown);
  // The z calibration row matters only for devices that sense z.
  const bool hasZ = known && c.sensedDof >= 3;
  const AxisBoxes& z = this->Axes[2];
  for (QWidget* w : { static_cast<QWidget*>(ui.zAxisLabel),
         static_cast<QWidget*>(z.RawMinimum),
         static_cast<QWidget*>(z.RawMaximum),
         static_cast<QWidget*>(z.Minimum),
         static_cast<QWidget*>(z.Maximum) })
  {
    w->setVisible(hasZ);
  }
}

bool qVesselTouchDeviceWidgetPrivate::isHardware() const
{
  for (const qVesselTouchDeviceEntry& entry : this->Devices)
  {
    if (entry.id == this->CurrentId)
    {
      return entry.kind == QLatin1String("hid");
    }
  }
  return false;
}

void qVesselTouchDeviceWidgetPrivate::showKind()
{
  QString kind;
  for (const qVesselTouchDeviceEntry& entry : this->Devices)
  {
    if (entry.id == this->CurrentId)
    {
      kind = entry.kind;
      break;
    }
  }
  this->Ui.kindValue->setText(kind.isEmpty() ? QStringLiteral("-") : kind);
  // The raw axis calibration and the reported capabilities belong to a hardware device; for the
  // mouse, the simulated handle or a replay they mean nothing and only take room. The
  // calibration shows only when the host gave the open device's own (it is read-only: what the
  // device applies, from its preset, not a setting).
  const bool hardware = this->isHardware();
  this->Ui.capabilitiesGroup->setVisible(hardware);
  this->Ui.calibrationGroup->setVisible(hardware && this->HasCalibration);
}

qVesselTouchDeviceWidget::qVesselTouchDeviceWidget(QWidget* parent)
  : QWidget(parent)
  , d_ptr(new qVesselTouchDeviceWidgetPrivate)
{
  Q_D(qVesselTouchDeviceWidget);
  d->Ui.setupUi(this);
  d->Ui.faultLabel->hide();
  const Ui::qVesselTouchDeviceWidget& ui = d->Ui;
  d->Axes[0] = {
    ui.xRawMinimumSpinBox, ui.xRawMaximumSpinBox, ui.xMinimumSpinBox, ui.xMaximumSpinBox
  };
  d->Axes[1] = {
    ui.yRawMinimumSpinBox, ui.yRawMaximumSpinBox, ui.yMinimumSpinBox, ui.yMaximumSpinBox
  };
  d->Axes[2] = {
    ui.zRawMinimumSpinBox, ui.zRawMaximumSpinBox, ui.zMinimumSpinBox, ui.zMaximumSpinBox
  };
  d->showCalibration();
  d->showCapabilities(false);

  // Read-only: the calibration shown is the open device's, applied by the device layer.
  for (const AxisBoxes& boxes : d->Axes)
  {
    for (QDoubleSpinBox* box : { boxes.RawMinimum, boxes.RawMaximum, boxes.Minimum, boxes.Maximum })
    {
      box->setReadOnly(true);
      box->setButtonSymbols(QAbstractSpinBox::NoButtons);
      box->setFocusPolicy(Qt::NoFocus);
    }
  }
  connect(d->Ui.deviceComboBox,
    QOverload<int>::of(&QComboBox::currentIndexChanged),
    this,
    [this](int index)
    {
      Q_D(qVesselTouchDeviceWidget);
      this->setCurrentDeviceId(d->Ui.deviceComboBox->itemData(index).toString());
    });
}

qVesselTouchDeviceWidget::~qVesselTouchDeviceWidget() = default;

void qVesselTouchDeviceWidget::setAvailableDevices(const QList<qVesselTouchDeviceEntry>& devices)
{
  Q_D(qVesselTouchDeviceWidget);
  d->Devices = devices;
  QString keep;
  {
    const QSignalBlocker blocker(d->Ui.deviceComboBox);
    d->Ui.deviceComboBox->clear();
    for (const qVesselTouchDeviceEntry& entry : devices)
    {
      d->Ui.deviceComboBox->addItem(entry.label.isEmpty() ? entry.id : entry.label, entry.id);
      if (entry.id == d->CurrentId)
      {
        keep = entry.id;
      }
    }
    if (keep.isEmpty() && !devices.isEmpty())
    {
      keep = devices.first().id;
    }
    d->Ui.deviceComboBox->setCurrentIndex(d->Ui.deviceComboBox->findData(keep));
  }
  const bool changed = keep != d->CurrentId;
  d->CurrentId = keep;
  d->showKind();
  if (changed)
  {
    emit this->deviceSelected(keep);
  }
}

void qVesselTouchDeviceWidget::setAvailableDeviceMaps(const QVariantList& devices)
{
  QList<qVesselTouchDeviceEntry> entries;
  for (const QVariant& device : devices)
  {
    entries << qVesselTouchDeviceEntry::fromVariantMap(device.toMap());
  }
  this->setAvailableDevices(entries);
}

QList<qVesselTouchDeviceEntry> qVesselTouchDeviceWidget::availableDevices() const
{
  Q_D(const qVesselTouchDeviceWidget);
  return d->Devices;
}

QString qVesselTouchDeviceWidget::currentDeviceId() const
{
  Q_D(const qVesselTouchDeviceWidget);
  return d->CurrentId;
}

void qVesselTouchDeviceWidget::setCurrentDeviceId(const QString& id)
{
  Q_D(qVesselTouchDeviceWidget);
  const int index = d->Ui.deviceComboBox->findData(id);
  if (index < 0)
  {
    qWarning("qVesselTouchDeviceWidget: no device with id '%s'", qPrintable(id));
    return;
  }
  if (id == d->CurrentId)
  {
    return;
  }
  {
    const QSignalBlocker blocker(d->Ui.deviceComboBox);
    d->Ui.deviceComboBox->setCurrentIndex(index);
  }
  d->CurrentId = id;
  d->showKind();
  emit this->deviceSelected(id);
}

QString qVesselTouchDeviceWidget::statusText() const
{
  Q_D(const qVesselTouchDeviceWidget);
  return d->Ui.statusValue->text();
}

void qVesselTouchDeviceWidget::setStatusText(const QString& text)
{
  Q_D(qVesselTouchDeviceWidget);
  d->Ui.statusValue->setText(text.isEmpty() ? tr("not connected") : text);
}

void qVesselTouchDeviceWidget::setCapabilities(const qVesselTouchDeviceCapabilities& capabilities)
{
  Q_D(qVesselTouchDeviceWidget);
  d->Capabilities = capabilities;
  d->showCapabilities(true);
}

void qVesselTouchDeviceWidget::setCapabilityMap(const QVariantMap& capabilities)
{
  this->setCapabilities(qVesselTouchDeviceCapabilities::fromVariantMap(capabilities));
}

qVesselTouchDeviceCapabilities qVesselTouchDeviceWidget::capabilities() const
{
  Q_D(const qVesselTouchDeviceWidget);
  return d->Capabilities;
}

void qVesselTouchDeviceWidget::clearCapabilities()
{
  Q_D(qVesselTouchDeviceWidget);
  d->Capabilities = qVesselTouchDeviceCapabilities();
  d->showCapabilities(false);
}

void qVesselTouchDeviceWidget::setCalibration(const qVesselTouchDeviceCalibration& calibration)
{
  Q_D(qVesselTouchDeviceWidget);
  d->Calibration = calibration;
  d->HasCalibration = true;
  d->showCalibration();
  d->readCalibration(); // keep what the spin boxes could hold (their ranges and decimals)
  d->showKind();
}

void qVesselTouchDeviceWidget::clearCalibration()
{
  Q_D(qVesselTouchDeviceWidget);
  d->Calibration = qVesselTouchDeviceCalibration();
  d->HasCalibration = false;
  d->showCalibration();
  d->showKind();
}

bool qVesselTouchDeviceWidget::hasCalibration() const
{
  Q_D(const qVesselTouchDeviceWidget);
  return d->HasCalibration;
}

qVesselTouchDeviceCalibration qVesselTouchDeviceWidget::calibration() const
{
  Q_D(const qVesselTouchDeviceWidget);
  return d->Calibration;
}

QString qVesselTouchDeviceWidget::faultMessage() const
{
  Q_D(const qVesselTouchDeviceWidget);
  return d->FaultMessage;
}

bool qVesselTouchDeviceWidget::hasFault() const
{
  Q_D(const qVesselTouchDeviceWidget);
  return !d->FaultMessage.isEmpty();
}

void qVesselTouchDeviceWidget::setFault(const QString& message)
{
  Q_D(qVesselTouchDeviceWidget);
  if (message.isEmpty())
  {
    this->clearFault();
    return;
  }
  const bool was = this->hasFault();
  d->FaultMessage = message;
  d->Ui.faultLabel->setText(tr("Device fault: %1").arg(message));
  d->Ui.faultLabel->show();
  if (!was)
  {
    emit this->faultChanged(true);
  }
}

void qVesselTouchDeviceWidget::clearFault()
{
  Q_D(qVesselTouchDeviceWidget);
  if (!this->hasFault())
  {
    return;
  }
  d->FaultMessage.clear();
  d->Ui.faultLabel->clear();
  d->Ui.faultLabel->hide();
  emit this->faultChanged(false);
}

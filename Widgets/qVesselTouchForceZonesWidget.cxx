#include "qVesselTouchForceZonesWidget.h"

#include "qVesselTouchForceZonesPlot.h"
#include "ui_qVesselTouchForceZonesWidget.h"

#include <QSignalBlocker>

#include <algorithm>
#include <cmath>

namespace
{
// Spin boxes show three decimals; the stored values match what the user sees.
double roundToThousandth(double value)
{
  return std::round(value * 1000.0) / 1000.0;
}
} // namespace

class qVesselTouchForceZonesWidgetPrivate
{
public:
  Ui::qVesselTouchForceZonesWidget Ui;
  double ZeroBelow = vtouch::hapticParameter(vtouch::HapticParameterId::ZoneZeroBelow).defaultValue;
  double SaturateAbove =
    vtouch::hapticParameter(vtouch::HapticParameterId::ZoneSaturateAbove).defaultValue;
  double Gain_N = vtouch::hapticParameter(vtouch::HapticParameterId::ZoneGain).defaultValue;
  double LivePressure = -1.0;

  void updateViews();
  void updateLiveLabel();
};

void qVesselTouchForceZonesWidgetPrivate::updateViews()
{
  const QSignalBlocker b0(this->Ui.zeroBelowSpinBox);
  const QSignalBlocker b1(this->Ui.saturateAboveSpinBox);
  const QSignalBlocker b2(this->Ui.gainSpinBox);
  this->Ui.zeroBelowSpinBox->setValue(this->ZeroBelow);
  this->Ui.saturateAboveSpinBox->setValue(this->SaturateAbove);
  this->Ui.gainSpinBox->setValue(this->Gain_N);
  this->Ui.zonesPlot->setZones(this->ZeroBelow, this->SaturateAbove, this->Gain_N);
  this->updateLiveLabel();
}

void qVesselTouchForceZonesWidgetPrivate::updateLiveLabel()
{
  if (this->LivePressure < 0.0)
  {
    this->Ui.liveValue->setText(QObject::tr("no pressure input"));
    return;
  }
  const double k = qVesselTouchForceZonesWidget::zoneGain(
    this->LivePressure, this->ZeroBelow, this->SaturateAbove, this->Gain_N);
  this->Ui.liveValue->setText(
    QObject::tr("P = %1, k(P) = %2 N").arg(this->LivePressure, 0, 'f', 2).arg(k, 0, 'f', 2));
}

qVesselTouchForceZonesWidget::qVesselTouchForceZonesWidget(QWidget* parent)
  : QWidget(parent)
  , d_ptr(new qVesselTouchForceZonesWidgetPrivate)
{
  Q_D(qVesselTouchForceZonesWidget);
  d->Ui.setupUi(this);
  d->Ui.gainSpinBox->setMaximum(kMaximumGain_N);
  d->updateViews();

  connect(d->Ui.zonesPlot,
    &qVesselTouchForceZonesPlot::thresholdsEdited,
    this,
    &qVesselTouchForceZonesWidget::setThresholds);
  connect(d->Ui.zeroBelowSpinBox,
    QOverload<double>::of(&QDoubleSpinBox::valueChanged),
    this,
    &qVesselTouchForceZonesWidget::setZeroBelow);
  connect(d->Ui.saturateAboveSpinBox,
    QOverload<double>::of(&QDoubleSpinBox::valueChanged),
    this,
    &qVesselTouchForceZonesWidget::setSaturateAbove);
  connect(d->Ui.gainSpinBox,
    QOverload<double>::of(&QDoubleSpinBox::valueChanged),
    this,
    &qVesselTouchForceZonesWidget::setGain_N);
}

qVesselTouchForceZonesWidget::~qVesselTouchForceZonesWidget() = default;

double qVesselTouchForceZonesWidget::zoneGain(double pressure,
  double zeroBelow,
  double saturateAbove,
  double gain_N)
{
  if (!std::isfinite(pressure) || !std::isfinite(gain_N))
  {
    return 0.0;
  }
  const double p = std::clamp(pressure, 0.0, 1.0);
  if (p < zeroBelow)
  {
    return 0.0;
  }
  if (p >= saturateAbove || saturateAbove <= zeroBelow)
  {
    return gain_N;
  }
  return gain_N * (p - zeroBelow) / (saturateAbove - zeroBelow);
}

double qVesselTouchForceZonesWidget::zeroBelow() const
{
  Q_D(const qVesselTouchForceZonesWidget);
  return d->ZeroBelow;
}

double qVesselTouchForceZonesWidget::saturateAbove() const
{
  Q_D(const qVesselTouchForceZonesWidget);
  return d->SaturateAbove;
}

void qVesselTouchForceZonesWidget::setThresholds(double zeroBelow, double saturateAbove)
{
  Q_D(qVesselTouchForceZonesWidget);
  if (!std::isfinite(zeroBelow) || !std::isfinite(saturateAbove))
  {
    qWarning("qVesselTouchForceZonesWidget: ignoring non-finite thresholds");
    return;
  }
  double z = roundToThousandth(std::clamp(zeroBelow, 0.0, 1.0 - kMinimumGap));
  double s = roundToThousandth(std::clamp(saturateAbove, kMinimumGap, 1.0));
  if (s - z < kMinimumGap - 1e-9)
  {
    // Keep the threshold that moved; push the other one out of the way.
    if (z != d->ZeroBelow)
    {
      s = roundToThousandth(z + kMinimumGap);
    }
    else
    {
      z = roundToThousandth(s - kMinimumGap);
    }
  }
  if (z == d->ZeroBelow && s == d->SaturateAbove)
  {
    d->updateViews(); // a spin box may show a value we refused: show the kept one again
    return;
  }
  d->ZeroBelow = z;
  d->SaturateAbove = s;
  d->updateViews();
  emit this->thresholdsChanged(z, s);
  emit this->parametersChanged();
}

void qVesselTouchForceZonesWidget::setZeroBelow(double zeroBelow)
{
  Q_D(qVesselTouchForceZonesWidget);
  this->setThresholds(zeroBelow, d->SaturateAbove);
}

void qVesselTouchForceZonesWidget::setSaturateAbove(double saturateAbove)
{
  Q_D(qVesselTouchForceZonesWidget);
  this->setThresholds(d->ZeroBelow, saturateAbove);
}

double qVesselTouchForceZonesWidget::gain_N() const
{
  Q_D(const qVesselTouchForceZonesWidget);
  return d->Gain_N;
}

void qVesselTouchForceZonesWidget::setGain_N(double gain_N)
{
  Q_D(qVesselTouchForceZonesWidget);
  if (!std::isfinite(gain_N))
  {
    qWarning("qVesselTouchForceZonesWidget: ignoring a non-finite gain");
    return;
  }
  const double g = roundToThousandth(std::clamp(gain_N, 0.0, kMaximumGain_N));
  if (g == d->Gain_N)
  {
    d->updateViews();
    return;
  }
  d->Gain_N = g;
  d->updateViews();
  emit this->gainChanged(g);
  emit this->parametersChanged();
}

double qVesselTouchForceZonesWidget::livePressure() const
{
  Q_D(const qVesselTouchForceZonesWidget);
  return d->LivePressure;
}

double qVesselTouchForceZonesWidget::liveGain_N() const
{
  Q_D(const qVesselTouchForceZonesWidget);
  return d->LivePressure < 0.0
           ? 0.0
           : zoneGain(d->LivePressure, d->ZeroBelow, d->SaturateAbove, d->Gain_N);
}

void qVesselTouchForceZonesWidget::setLivePressure(double pressure)
{
  Q_D(qVesselTouchForceZonesWidget);
  d->LivePressure = std::isfinite(pressure) && pressure >= 0.0 ? std::min(pressure, 1.0) : -1.0;
  d->Ui.zonesPlot->setLivePressure(d->LivePressure);
  d->updateLiveLabel();
}

void qVesselTouchForceZonesWidget::clearLivePressure()
{
  this->setLivePressure(-1.0);
}

qVesselTouchForceZonesPlot* qVesselTouchForceZonesWidget::plot() const
{
  Q_D(const qVesselTouchForceZonesWidget);
  return d->Ui.zonesPlot;
}

void qVesselTouchForceZonesWidget::setGainEditable(bool editable)
{
  Q_D(qVesselTouchForceZonesWidget);
  d->Ui.gainLabel->setVisible(editable);
  d->Ui.gainSpinBox->setVisible(editable);
}

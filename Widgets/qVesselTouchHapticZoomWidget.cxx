#include "qVesselTouchHapticZoomWidget.h"

#include "ui_qVesselTouchHapticZoomWidget.h"

#include <QSignalBlocker>

#include <algorithm>
#include <cmath>

namespace
{
// The spin box shows three decimals; the stored ratio is exactly what it shows.
double canonicalRatio(double ratio)
{
  const double clamped = std::clamp(ratio,
    qVesselTouchHapticZoomWidget::kMinimumRatio,
    qVesselTouchHapticZoomWidget::kMaximumRatio);
  return std::round(clamped * 1000.0) / 1000.0;
}
} // namespace

class qVesselTouchHapticZoomWidgetPrivate
{
public:
  Ui::qVesselTouchHapticZoomWidget Ui;
  double Ratio = vtouch::hapticParameter(vtouch::HapticParameterId::Zoom).defaultValue;

  // Shows Ratio on the controls without letting either echo back. The slider is left alone while
  // it is the source: its position maps to a rounded r whose own position may differ by one step.
  void updateViews(bool updateSlider)
  {
    const QSignalBlocker sliderBlocker(this->Ui.ratioSlider);
    const QSignalBlocker spinBlocker(this->Ui.ratioSpinBox);
    if (updateSlider)
    {
      this->Ui.ratioSlider->setValue(
        qVesselTouchHapticZoomWidget::ratioToSliderPosition(this->Ratio));
    }
    this->Ui.ratioSpinBox->setValue(this->Ratio);
  }

  // Stores r; true when it changed.
  bool store(double ratio)
  {
    const double r = canonicalRatio(ratio);
    const bool changed = r != this->Ratio;
    this->Ratio = r;
    return changed;
  }
};

qVesselTouchHapticZoomWidget::qVesselTouchHapticZoomWidget(QWidget* parent)
  : QWidget(parent)
  , d_ptr(new qVesselTouchHapticZoomWidgetPrivate)
{
  Q_D(qVesselTouchHapticZoomWidget);
  d->Ui.setupUi(this);
  d->Ui.ratioSlider->setRange(0, kSliderSteps);
  d->Ui.ratioSlider->setSingleStep(kSliderSteps / 100);
  d->Ui.ratioSlider->setPageStep(kSliderSteps / 10);
  d->Ui.ratioSpinBox->setRange(kMinimumRatio, kMaximumRatio);
  d->updateViews(true);

  connect(d->Ui.ratioSlider,
    &QSlider::valueChanged,
    this,
    [this](int position)
    {
      Q_D(qVesselTouchHapticZoomWidget);
      const bool changed = d->store(sliderPositionToRatio(position));
      d->updateViews(false);
      if (changed)
      {
        emit this->ratioChanged(d->Ratio);
      }
    });
  connect(d->Ui.ratioSpinBox,
    QOverload<double>::of(&QDoubleSpinBox::valueChanged),
    this,
    &qVesselTouchHapticZoomWidget::setRatio);
  connect(
    d->Ui.resetButton, &QAbstractButton::clicked, this, &qVesselTouchHapticZoomWidget::resetRatio);
}

qVesselTouchHapticZoomWidget::~qVesselTouchHapticZoomWidget() = default;

double qVesselTouchHapticZoomWidget::sliderPositionToRatio(int position)
{
  const double t = double(std::clamp(position, 0, kSliderSteps)) / double(kSliderSteps);
  return std::pow(10.0, 2.0 * t - 1.0);
}

int qVesselTouchHapticZoomWidget::ratioToSliderPosition(double ratio)
{
  if (std::isnan(ratio))
  {
    return kSliderSteps / 2;
  }
  const double t = (std::log10(std::clamp(ratio, kMinimumRatio, kMaximumRatio)) + 1.0) / 2.0;
  return std::clamp(int(std::lround(t * kSliderSteps)), 0, kSliderSteps);
}

double qVesselTouchHapticZoomWidget::ratio() const
{
  Q_D(const qVesselTouchHapticZoomWidget);
  return d->Ratio;
}

void qVesselTouchHapticZoomWidget::setRatio(double ratio)
{
  Q_D(qVesselTouchHapticZoomWidget);
  if (!std::isfinite(ratio))
  {
    qWarning("qVesselTouchHapticZoomWidget: ignoring a non-finite ratio");
    return;
  }
  const bool changed = d->store(ratio);
  d->updateViews(true); // also re-shows a clamped value the spin box may still display
  if (changed)
  {
    emit this->ratioChanged(d->Ratio);
  }
}

void qVesselTouchHapticZoomWidget::resetRatio()
{
  this->setRatio(vtouch::hapticParameter(vtouch::HapticParameterId::Zoom).defaultValue);
}

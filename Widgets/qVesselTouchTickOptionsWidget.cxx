#include "qVesselTouchTickOptionsWidget.h"

#include "ui_qVesselTouchTickOptionsWidget.h"

#include <QSignalBlocker>
#include <QVector>

#include <algorithm>
#include <cmath>

using Options = qVesselTouchTickOptions;

bool qVesselTouchTickOptions::operator==(const Options& o) const
{
  return tracerRule == o.tracerRule && tracerMovementThreshold_px == o.tracerMovementThreshold_px &&
         tracerJunctionWindow_px == o.tracerJunctionWindow_px &&
         tracerJunctionMargin_px == o.tracerJunctionMargin_px &&
         contactDwell_s == o.contactDwell_s && contactApproachAtStart == o.contactApproachAtStart &&
         slopeForceBudget == o.slopeForceBudget &&
         forceInterpolationPerAxis == o.forceInterpolationPerAxis &&
         cohZMaxPerResolution == o.cohZMaxPerResolution && proxyTangentSnap == o.proxyTangentSnap &&
         proxyNormalUnilateral == o.proxyNormalUnilateral &&
         proxyThresholdFromData == o.proxyThresholdFromData && proxyFriction == o.proxyFriction &&
         proxyTickSpacing_mm == o.proxyTickSpacing_mm && proxyTickForce_N == o.proxyTickForce_N &&
         proxyTickAtBifurcations == o.proxyTickAtBifurcations &&
         proxyFieldForce == o.proxyFieldForce && idleRadius_mm == o.idleRadius_mm &&
         idleDwell_s == o.idleDwell_s && idleRamp_s == o.idleRamp_s;
}

class qVesselTouchTickOptionsWidgetPrivate
{
public:
  struct DoubleBinding
  {
    QDoubleSpinBox* SpinBox;
    double Options::*Field;
  };
  struct BoolBinding
  {
    QCheckBox* CheckBox;
    bool Options::*Field;
  };
  Ui::qVesselTouchTickOptionsWidget Ui;
  QVector<DoubleBinding> Doubles;
  QVector<BoolBinding> Bools;
  Options Values;

  void setupBindings()
  {
    const auto& ui = this->Ui;
    this->Doubles = {
      { ui.movementThresholdSpinBox, &Options::tracerMovementThreshold_px },
      { ui.junctionWindowSpinBox, &Options::tracerJunctionWindow_px },
      { ui.junctionMarginSpinBox, &Options::tracerJunctionMargin_px },
      { ui.contactDwellSpinBox, &Options::contactDwell_s },
      { ui.slopeBudgetSpinBox, &Options::slopeForceBudget },
      { ui.zMaxCountsSpinBox, &Options::cohZMaxPerResolution },
      { ui.frictionSpinBox, &Options::proxyFriction },
      { ui.tickSpacingSpinBox, &Options::proxyTickSpacing_mm },
      { ui.tickForceSpinBox, &Options::proxyTickForce_N },
      { ui.idleRadiusSpinBox, &Options::idleRadius_mm },
      { ui.idleDwellSpinBox, &Options::idleDwell_s },
      { ui.idleRampSpinBox, &Options::idleRamp_s },
    };
    this->Bools = {
      { ui.contactApproachCheckBox, &Options::contactApproachAtStart },
      { ui.perAxisCheckBox, &Options::forceInterpolationPerAxis },
      { ui.tangentSnapCheckBox, &Options::proxyTangentSnap },
      { ui.normalUnilateralCheckBox, &Options::proxyNormalUnilateral },
      { ui.thresholdFromDataCheckBox, &Options::proxyThresholdFromData },
      { ui.tickAtBifurcationsCheckBox, &Options::proxyTickAtBifurcations },
      { ui.fieldForceCheckBox, &Options::proxyFieldForce },
    };
  }

  // Each spin box carries its range and decimals: the stored values are exactly what they show.
  Options clamped(Options o) const
  {
    for (const DoubleBinding& binding : this->Doubles)
    {
      double& value = o.*(binding.Field);
      const QDoubleSpinBox* box = binding.SpinBox;
      const double scale = std::pow(10.0, box->decimals());
      value = std::isfinite(value) ? value : box->minimum();
      value = std::clamp(std::round(value * scale) / scale, box->minimum(), box->maximum());
    }
    o.tracerRule = std::clamp(o.tracerRule, 0, 1);
    return o;
  }

  void updateViews()
  {
    for (const DoubleBinding& binding : this->Doubles)
    {
      const QSignalBlocker blocker(binding.SpinBox);
      binding.SpinBox->setValue(this->Values.*(binding.Field));
    }
    for (const BoolBinding& binding : this->Bools)
    {
      const QSignalBlocker blocker(binding.CheckBox);
      binding.CheckBox->setChecked(this->Values.*(binding.Field));
    }
    const QSignalBlocker blocker(this->Ui.tracerRuleComboBox);
    this->Ui.tracerRuleComboBox->setCurrentIndex(this->Values.tracerRule);
    // The movement threshold matters for the movement rule only; the tick force with tick marks.
    this->Ui.movementThresholdSpinBox->setEnabled(this->Values.tracerRule == 1);
    this->Ui.junctionMarginSpinBox->setEnabled(this->Values.tracerJunctionWindow_px > 0.0);
    this->Ui.tickForceSpinBox->setEnabled(
      this->Values.proxyTickSpacing_mm > 0.0 || this->Values.proxyTickAtBifurcations);
  }
};

qVesselTouchTickOptionsWidget::qVesselTouchTickOptionsWidget(QWidget* parent)
  : QWidget(parent)
  , d_ptr(new qVesselTouchTickOptionsWidgetPrivate)
{
  Q_D(qVesselTouchTickOptionsWidget);
  d->Ui.setupUi(this);
  d->setupBindings();
  d->updateViews();
  for (const auto& binding : d->Doubles)
  {
    auto field = binding.Field;
    connect(binding.SpinBox,
      QOverload<double>::of(&QDoubleSpinBox::valueChanged),
      this,
      [this, field](double value)
      {
        Q_D(qVesselTouchTickOptionsWidget);
        Options o = d->Values;
        o.*field = value;
        this->setOptions(o);
      });
  }
  for (const auto& binding : d->Bools)
  {
    auto field = binding.Field;
    connect(binding.CheckBox,
      &QCheckBox::toggled,
      this,
      [this, field](bool value)
      {
        Q_D(qVesselTouchTickOptionsWidget);
        Options o = d->Values;
        o.*field = value;
        this->setOptions(o);
      });
  }
  connect(d->Ui.tracerRuleComboBox,
    QOverload<int>::of(&QComboBox::currentIndexChanged),
    this,
    [this](int index)
    {
      Q_D(qVesselTouchTickOptionsWidget);
      Options o = d->Values;
      o.tracerRule = index;
      this->setOptions(o);
    });
}

qVesselTouchTickOptionsWidget::~qVesselTouchTickOptionsWidget() = default;

qVesselTouchTickOptions qVesselTouchTickOptionsWidget::options() const
{
  Q_D(const qVesselTouchTickOptionsWidget);
  return d->Values;
}

void qVesselTouchTickOptionsWidget::setOptions(const qVesselTouchTickOptions& options)
{
  Q_D(qVesselTouchTickOptionsWidget);
  const Options o = d->clamped(options);
  const bool changed = o != d->Values;
  d->Values = o;
  d->updateViews();
  if (changed)
  {
    emit this->optionsChanged();
  }
}

#include "qVesselTouchForceLawWidget.h"

#include "ui_qVesselTouchForceLawWidget.h"

#include <QComboBox>
#include <QDoubleSpinBox>
#include <QSignalBlocker>
#include <QVector>

#include <algorithm>
#include <cmath>

namespace
{
using Parameters = qVesselTouchForceLawParameters;
using ForceLaw = qVesselTouchForceLawWidget::ForceLaw;

// Upper ends of the coupler spin boxes when the device sets no bound.
constexpr double kStiffnessRangeMax_N_per_m = 5000.0;
constexpr double kDampingRangeMax_N_s_per_m = 10.0;

// One spin box bound to one field of the parameter struct.
struct DoubleBinding
{
  QDoubleSpinBox* SpinBox;
  double Parameters::*Field;
  ForceLaw Law;
};

const char* const kPresetNames[] = { QT_TRANSLATE_NOOP("qVesselTouchForceLawWidget", "Gentle"),
  QT_TRANSLATE_NOOP("qVesselTouchForceLawWidget", "Default"),
  QT_TRANSLATE_NOOP("qVesselTouchForceLawWidget", "Firm") };
constexpr int kPresetCount = 3;

// Per law and preset (gentle, default, firm). Defaults equal Logic/Haptics' defaults; gentle
// halves the force and widens the regularization, firm doubles the force.
void writePreset(ForceLaw law, int preset, Parameters& p)
{
  const auto pick = [preset](double gentle, double normal, double firm)
  { return preset == 0 ? gentle : (preset == 1 ? normal : firm); };
  switch (law)
  {
    case ForceLaw::Ldgf:
      p.ldgfGain_N = pick(0.5, 1.0, 2.0);
      p.ldgfLambda_mm = pick(0.05, 0.01, 0.005);
      break;
    case ForceLaw::ChangeOfHeight:
      p.cohGain_N = pick(0.5, 1.0, 2.0);
      p.cohLambda_mm = pick(0.05, 0.01, 0.005);
      p.cohZMax_mm = 0.0; // from the device's resolution (App. A), whatever the feel
      p.cohForgetTime_s = pick(0.2, 0.1, 0.05);
      break;
    case ForceLaw::LateralGradient:
      p.lateralGain_N = pick(0.5, 1.0, 2.0);
      p.lateralProbe_px = pick(3.0, 2.0, 1.0);
      break;
    case ForceLaw::ConstraintProxy:
      p.proxyStiffness_N_per_m = pick(150.0, 300.0, 500.0);
      p.proxyDamping_N_s_per_m = pick(0.05, 0.1, 0.2);
      p.proxyTangentThreshold_N = pick(0.15, 0.3, 0.6);
      p.proxySnapThreshold_N = pick(0.8, 1.5, 3.0);
      p.proxyKappaLow = 0.15;
      p.proxyKappaHigh = 0.5;
      break;
  }
}
} // namespace

class qVesselTouchForceLawWidgetPrivate
{
public:
  explicit qVesselTouchForceLawWidgetPrivate(qVesselTouchForceLawWidget& object)
    : q_ptr(&object)
  {
  }

  qVesselTouchForceLawWidget* q_ptr;
  Q_DECLARE_PUBLIC(qVesselTouchForceLawWidget);

  Ui::qVesselTouchForceLawWidget Ui;
  QVector<DoubleBinding> Bindings;
  Parameters Values;
  ForceLaw Law = ForceLaw::Ldgf;
  double MaxStiffness_N_per_m = 0.0;
  double MaxDamping_N_s_per_m = 0.0;

  void setupBindings();
  void applyDeviceRanges();
  Parameters clamped(Parameters p) const;
  // Shows Values and Law on every control, with their signals blocked.
  void updateViews();
  void updatePresetCombo();
  void updateRuleDependentControls();
  // Stores p (clamped); emits parametersChanged() when it differs. Refreshes the views either way.
  void store(const Parameters& p);
};

void qVesselTouchForceLawWidgetPrivate::setupBindings()
{
  const auto& ui = this->Ui;
  this->Bindings = {
    { ui.ldgfGainSpinBox, &Parameters::ldgfGain_N, ForceLaw::Ldgf },
    { ui.ldgfLambdaSpinBox, &Parameters::ldgfLambda_mm, ForceLaw::Ldgf },
    { ui.cohGainSpinBox, &Parameters::cohGain_N, ForceLaw::ChangeOfHeight },
    { ui.cohLambdaSpinBox, &Parameters::cohLambda_mm, ForceLaw::ChangeOfHeight },
    { ui.cohZMaxSpinBox, &Parameters::cohZMax_mm, ForceLaw::ChangeOfHeight },
    { ui.cohForgetTimeSpinBox, &Parameters::cohForgetTime_s, ForceLaw::ChangeOfHeight },
    { ui.lateralGainSpinBox, &Parameters::lateralGain_N, ForceLaw::LateralGradient },
    { ui.lateralProbeSpinBox, &Parameters::lateralProbe_px, ForceLaw::LateralGradient },
    { ui.proxyStiffnessSpinBox, &Parameters::proxyStiffness_N_per_m, ForceLaw::ConstraintProxy },
    { ui.proxyDampingSpinBox, &Parameters::proxyDamping_N_s_per_m, ForceLaw::ConstraintProxy },
    { ui.proxyTangentThresholdSpinBox,
      &Parameters::proxyTangentThreshold_N,
      ForceLaw::ConstraintProxy },
    { ui.proxySnapThresholdSpinBox, &Parameters::proxySnapThreshold_N, ForceLaw::ConstraintProxy },
    { ui.proxyKappaLowSpinBox, &Parameters::proxyKappaLow, ForceLaw::ConstraintProxy },
    { ui.proxyKappaHighSpinBox, &Parameters::proxyKappaHigh, ForceLaw::ConstraintProxy },
  };
}

void qVesselTouchForceLawWidgetPrivate::applyDeviceRanges()
{
  const QSignalBlocker b0(this->Ui.proxyStiffnessSpinBox);
  const QSignalBlocker b1(this->Ui.proxyDampingSpinBox);
  this->Ui.proxyStiffnessSpinBox->setMaximum(
    this->MaxStiffness_N_per_m > 0.0
      ? std::min(this->MaxStiffness_N_per_m, kStiffnessRangeMax_N_per_m)
      : kStiffnessRangeMax_N_per_m);
  this->Ui.proxyDampingSpinBox->setMaximum(
    this->MaxDamping_N_s_per_m > 0.0
      ? std::min(this->MaxDamping_N_s_per_m, kDampingRangeMax_N_s_per_m)
      : kDampingRangeMax_N_s_per_m);
  QStringList bounds;
  if (this->MaxStiffness_N_per_m > 0.0)
  {
    bounds << QObject::tr("k_c ≤ %1 N/m").arg(this->MaxStiffness_N_per_m, 0, 'f', 1);
  }
  if (this->MaxDamping_N_s_per_m > 0.0)
  {
    bounds << QObject::tr("b_c ≤ %1 N·s/m").arg(this->MaxDamping_N_s_per_m, 0, 'f', 3);
  }
  this->Ui.deviceLimitLabel->setText(
    bounds.isEmpty() ? QObject::tr("No device limits on the coupler.")
                     : QObject::tr("Device limits: %1").arg(bounds.join(QStringLiteral(", "))));
}

Parameters qVesselTouchForceLawWidgetPrivate::clamped(Parameters p) const
{
  // The spin boxes carry each range (including the device bounds) and round to their decimals.
  for (const DoubleBinding& binding : this->Bindings)
  {
    double& value = p.*(binding.Field);
    const QDoubleSpinBox* box = binding.SpinBox;
    const double scale = std::pow(10.0, box->decimals());
    value = std::isfinite(value) ? value : box->minimum();
    value = std::clamp(std::round(value * scale) / scale, box->minimum(), box->maximum());
  }
  // The knees of kappa stay ordered: s0 < s1.
  if (p.proxyKappaLow >= p.proxyKappaHigh)
  {
    p.proxyKappaHigh = std::min(1.0, p.proxyKappaLow + 0.01);
    p.proxyKappaLow = std::min(p.proxyKappaLow, p.proxyKappaHigh - 0.01);
  }
  return p;
}

void qVesselTouchForceLawWidgetPrivate::updateViews()
{
  for (const DoubleBinding& binding : this->Bindings)
  {
    const QSignalBlocker blocker(binding.SpinBox);
    binding.SpinBox->setValue(this->Values.*(binding.Field));
  }
  {
    const QSignalBlocker b0(this->Ui.proxyTangentRuleComboBox);
    const QSignalBlocker b1(this->Ui.proxySnapRuleComboBox);
    const QSignalBlocker b2(this->Ui.lawComboBox);
    this->Ui.proxyTangentRuleComboBox->setCurrentIndex(this->Values.proxyTangentDrag ? 1 : 0);
    this->Ui.proxySnapRuleComboBox->setCurrentIndex(this->Values.proxySnapDrag ? 1 : 0);
    this->Ui.lawComboBox->setCurrentIndex(int(this->Law));
  }
  this->Ui.lawPages->setCurrentIndex(int(this->Law));
  this->updateRuleDependentControls();
  this->updatePresetCombo();
}

void qVesselTouchForceLawWidgetPrivate::updateRuleDependentControls()
{
  this->Ui.proxyTangentThresholdSpinBox->setEnabled(this->Values.proxyTangentDrag);
  this->Ui.proxySnapThresholdSpinBox->setEnabled(this->Values.proxySnapDrag);
}

void qVesselTouchForceLawWidgetPrivate::updatePresetCombo()
{
  Q_Q(qVesselTouchForceLawWidget);
  const QSignalBlocker blocker(this->Ui.presetComboBox);
  const QString name = q->presetName();
  int index = this->Ui.presetComboBox->findText(name);
  if (index < 0)
  {
    index = this->Ui.presetComboBox->count() - 1; // "Custom"
  }
  this->Ui.presetComboBox->setCurrentIndex(index);
}

void qVesselTouchForceLawWidgetPrivate::store(const Parameters& p)
{
  Q_Q(qVesselTouchForceLawWidget);
  const Parameters value = this->clamped(p);
  const bool changed = value != this->Values;
  this->Values = value;
  this->updateViews();
  if (changed)
  {
    emit q->parametersChanged();
  }
}

qVesselTouchForceLawWidget::qVesselTouchForceLawWidget(QWidget* parent)
  : QWidget(parent)
  , d_ptr(new qVesselTouchForceLawWidgetPrivate(*this))
{
  Q_D(qVesselTouchForceLawWidget);
  d->Ui.setupUi(this);
  for (const char* name : kPresetNames)
  {
    d->Ui.presetComboBox->addItem(tr(name), QString::fromLatin1(name));
  }
  d->Ui.presetComboBox->addItem(tr("Custom"), QStringLiteral("Custom"));
  d->setupBindings();
  d->applyDeviceRanges();
  d->Values = d->clamped(Parameters());
  d->updateViews();

  for (const DoubleBinding& binding : d->Bindings)
  {
    double Parameters::*field = binding.Field;
    connect(binding.SpinBox,
      QOverload<double>::of(&QDoubleSpinBox::valueChanged),
      this,
      [this, field](double value)
      {
        Q_D(qVesselTouchForceLawWidget);
        Parameters p = d->Values;
        p.*field = value;
        d->store(p);
      });
  }
  connect(d->Ui.proxyTangentRuleComboBox,
    QOverload<int>::of(&QComboBox::currentIndexChanged),
    this,
    [this](int index)
    {
      Q_D(qVesselTouchForceLawWidget);
      Parameters p = d->Values;
      p.proxyTangentDrag = index == 1;
      d->store(p);
    });
  connect(d->Ui.proxySnapRuleComboBox,
    QOverload<int>::of(&QComboBox::currentIndexChanged),
    this,
    [this](int index)
    {
      Q_D(qVesselTouchForceLawWidget);
      Parameters p = d->Values;
      p.proxySnapDrag = index == 1;
      d->store(p);
    });
  connect(d->Ui.lawComboBox,
    QOverload<int>::of(&QComboBox::currentIndexChanged),
    this,
    QOverload<int>::of(&qVesselTouchForceLawWidget::setForceLaw));
  connect(d->Ui.presetComboBox,
    QOverload<int>::of(&QComboBox::activated),
    this,
    [this](int index)
    {
      Q_D(qVesselTouchForceLawWidget);
      this->applyPreset(d->Ui.presetComboBox->itemData(index).toString());
    });
}

qVesselTouchForceLawWidget::~qVesselTouchForceLawWidget() = default;

qVesselTouchForceLawWidget::ForceLaw qVesselTouchForceLawWidget::forceLaw() const
{
  Q_D(const qVesselTouchForceLawWidget);
  return d->Law;
}

void qVesselTouchForceLawWidget::setForceLaw(ForceLaw law)
{
  Q_D(qVesselTouchForceLawWidget);
  if (law == d->Law)
  {
    return;
  }
  d->Law = law;
  d->updateViews();
  emit this->forceLawChanged(int(law));
}

void qVesselTouchForceLawWidget::setForceLaw(int law)
{
  if (law < 0 || law >= kForceLawCount)
  {
    qWarning("qVesselTouchForceLawWidget: ignoring unknown force law %d", law);
    return;
  }
  this->setForceLaw(ForceLaw(law));
}

qVesselTouchForceLawParameters qVesselTouchForceLawWidget::parameters() const
{
  Q_D(const qVesselTouchForceLawWidget);
  return d->Values;
}

void qVesselTouchForceLawWidget::setParameters(const qVesselTouchForceLawParameters& parameters)
{
  Q_D(qVesselTouchForceLawWidget);
  d->store(parameters);
}

void qVesselTouchForceLawWidget::setDeviceLimits(double maxStiffness_N_per_m,
  double maxDamping_N_s_per_m)
{
  Q_D(qVesselTouchForceLawWidget);
  const auto bound = [](double v) { return std::isfinite(v) && v > 0.0 ? v : 0.0; };
  d->MaxStiffness_N_per_m = bound(maxStiffness_N_per_m);
  d->MaxDamping_N_s_per_m = bound(maxDamping_N_s_per_m);
  d->applyDeviceRanges();
  d->store(d->Values); // lowers k_c / b_c to the new bounds, emits when they moved
}

double qVesselTouchForceLawWidget::maxStiffness_N_per_m() const
{
  Q_D(const qVesselTouchForceLawWidget);
  return d->MaxStiffness_N_per_m;
}

double qVesselTouchForceLawWidget::maxDamping_N_s_per_m() const
{
  Q_D(const qVesselTouchForceLawWidget);
  return d->MaxDamping_N_s_per_m;
}

QStringList qVesselTouchForceLawWidget::presetNames()
{
  QStringList names;
  for (const char* name : kPresetNames)
  {
    names << QString::fromLatin1(name);
  }
  return names;
}

bool qVesselTouchForceLawWidget::presetParameters(ForceLaw law,
  const QString& name,
  qVesselTouchForceLawParameters& parameters)
{
  const int preset = presetNames().indexOf(name);
  if (preset < 0 || preset >= kPresetCount || int(law) < 0 || int(law) >= kForceLawCount)
  {
    return false;
  }
  writePreset(law, preset, parameters);
  return true;
}

QString qVesselTouchForceLawWidget::presetName() const
{
  Q_D(const qVesselTouchForceLawWidget);
  for (const QString& name : presetNames())
  {
    Parameters candidate = d->Values;
    presetParameters(d->Law, name, candidate);
    if (d->clamped(candidate) == d->Values)
    {
      return name;
    }
  }
  return QStringLiteral("Custom");
}

QString qVesselTouchForceLawWidget::forceLawLabel(ForceLaw law)
{
  switch (law)
  {
    case Ldgf:
      return tr("LDGF (lateral depth gradient)");
    case ChangeOfHeight:
      return tr("Change of height");
    case LateralGradient:
      return tr("Lateral surface gradient");
    case ConstraintProxy:
      return tr("Constraint proxy");
  }
  return QString();
}

bool qVesselTouchForceLawWidget::applyPreset(const QString& name)
{
  Q_D(qVesselTouchForceLawWidget);
  Parameters p = d->Values;
  if (!presetParameters(d->Law, name, p))
  {
    if (name != QLatin1String("Custom"))
    {
      qWarning("qVesselTouchForceLawWidget: unknown preset '%s'", qPrintable(name));
    }
    d->updatePresetCombo();
    return false;
  }
  d->store(p);
  return true;
}

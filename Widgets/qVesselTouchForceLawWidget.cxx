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
using Id = vtouch::HapticParameterId;

const vtouch::HapticParameterDescriptor& row(Id id)
{
  return vtouch::hapticParameter(id);
}

// One spin box bound to one value: a row of the haptic parameter table (its range and default
// are the table's), or a per-law gain (ZoneGain's range).
struct DoubleBinding
{
  QDoubleSpinBox* SpinBox;
  Id Row;
  double Parameters::*Gain; // nullptr: the table row itself
  ForceLaw Law;

  double get(const Parameters& p) const { return Gain ? p.*Gain : row(Row).get(p.haptic); }
  void set(Parameters& p, double value) const
  {
    if (Gain)
    {
      p.*Gain = value;
    }
    else
    {
      row(Row).set(p.haptic, value);
    }
  }
};

const char* const kPresetNames[] = { QT_TRANSLATE_NOOP("qVesselTouchForceLawWidget", "Gentle"),
  QT_TRANSLATE_NOOP("qVesselTouchForceLawWidget", "Default"),
  QT_TRANSLATE_NOOP("qVesselTouchForceLawWidget", "Firm") };
constexpr int kPresetCount = 3;

// Per law and preset (gentle, default, firm). "Default" is the table's defaults; gentle halves
// the force and widens the regularization, firm doubles the force.
void writePreset(ForceLaw law, int preset, Parameters& p)
{
  const auto scaled = [preset](Id id, double gentle, double firm)
  {
    const double d = row(id).defaultValue;
    return preset == 0 ? gentle * d : (preset == 1 ? d : firm * d);
  };
  vtouch::HapticParameters& h = p.haptic;
  const double gain_N = scaled(Id::ZoneGain, 0.5, 2.0);
  switch (law)
  {
    case ForceLaw::Ldgf:
      p.ldgfGain_N = gain_N;
      h.ldgfLambda_mm = scaled(Id::LdgfLambda, 5.0, 0.5);
      break;
    case ForceLaw::ChangeOfHeight:
      p.cohGain_N = gain_N;
      h.cohLambda_mm = scaled(Id::ChangeOfHeightLambda, 5.0, 0.5);
      // z_max: the table's default 0 sets it from the device's resolution (Hayward & Yi App. A),
      // whatever the feel.
      h.cohZMax_mm = row(Id::ChangeOfHeightZMax).defaultValue;
      break;
    case ForceLaw::LateralGradient:
      p.lateralGain_N = gain_N;
      h.lateralProbe_px = scaled(Id::LateralProbe, 1.5, 0.5);
      break;
    case ForceLaw::ConstraintProxy:
      h.proxyStiffness_N_per_m = scaled(Id::ProxyStiffness, 0.5, 2.0);
      h.proxyDamping_N_s_per_m = scaled(Id::ProxyDamping, 0.5, 2.0);
      h.proxyTangentThreshold_N = scaled(Id::ProxyTangentThreshold, 0.5, 2.0);
      h.proxySnapThreshold_N = scaled(Id::ProxySnapThreshold, 0.5, 2.0);
      h.proxyKappaLow = row(Id::ProxyKappaLow).defaultValue;
      h.proxyKappaHigh = row(Id::ProxyKappaHigh).defaultValue;
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
    { ui.ldgfGainSpinBox, Id::ZoneGain, &Parameters::ldgfGain_N, ForceLaw::Ldgf },
    { ui.ldgfLambdaSpinBox, Id::LdgfLambda, nullptr, ForceLaw::Ldgf },
    { ui.cohGainSpinBox, Id::ZoneGain, &Parameters::cohGain_N, ForceLaw::ChangeOfHeight },
    { ui.cohLambdaSpinBox, Id::ChangeOfHeightLambda, nullptr, ForceLaw::ChangeOfHeight },
    { ui.cohZMaxSpinBox, Id::ChangeOfHeightZMax, nullptr, ForceLaw::ChangeOfHeight },
    { ui.lateralGainSpinBox, Id::ZoneGain, &Parameters::lateralGain_N, ForceLaw::LateralGradient },
    { ui.lateralProbeSpinBox, Id::LateralProbe, nullptr, ForceLaw::LateralGradient },
    { ui.proxyStiffnessSpinBox, Id::ProxyStiffness, nullptr, ForceLaw::ConstraintProxy },
    { ui.proxyDampingSpinBox, Id::ProxyDamping, nullptr, ForceLaw::ConstraintProxy },
    { ui.proxyTangentThresholdSpinBox,
      Id::ProxyTangentThreshold,
      nullptr,
      ForceLaw::ConstraintProxy },
    { ui.proxySnapThresholdSpinBox, Id::ProxySnapThreshold, nullptr, ForceLaw::ConstraintProxy },
    { ui.proxyKappaLowSpinBox, Id::ProxyKappaLow, nullptr, ForceLaw::ConstraintProxy },
    { ui.proxyKappaHighSpinBox, Id::ProxyKappaHigh, nullptr, ForceLaw::ConstraintProxy },
  };
  // Ranges and meanings from the table: the spin boxes cannot offer what the session refuses.
  for (const DoubleBinding& binding : this->Bindings)
  {
    const vtouch::HapticParameterDescriptor& d = row(binding.Row);
    const QSignalBlocker blocker(binding.SpinBox);
    binding.SpinBox->setRange(d.minimum, d.maximum);
    binding.SpinBox->setToolTip(QString::fromUtf8(d.meaning));
  }
}

void qVesselTouchForceLawWidgetPrivate::applyDeviceRanges()
{
  const double stiffnessMax_N_per_m = row(Id::ProxyStiffness).maximum;
  const double dampingMax_N_s_per_m = row(Id::ProxyDamping).maximum;
  const QSignalBlocker b0(this->Ui.proxyStiffnessSpinBox);
  const QSignalBlocker b1(this->Ui.proxyDampingSpinBox);
  this->Ui.proxyStiffnessSpinBox->setMaximum(
    this->MaxStiffness_N_per_m > 0.0 ? std::min(this->MaxStiffness_N_per_m, stiffnessMax_N_per_m)
                                     : stiffnessMax_N_per_m);
  this->Ui.proxyDampingSpinBox->setMaximum(
    this->MaxDamping_N_s_per_m > 0.0 ? std::min(this->MaxDamping_N_s_per_m, dampingMax_N_s_per_m)
                                     : dampingMax_N_s_per_m);
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
    double value = binding.get(p);
    const QDoubleSpinBox* box = binding.SpinBox;
    const double scale = std::pow(10.0, box->decimals());
    value = std::isfinite(value) ? value : box->minimum();
    binding.set(p, std::clamp(std::round(value * scale) / scale, box->minimum(), box->maximum()));
  }
  // The knees of kappa stay ordered: s0 < s1.
  vtouch::HapticParameters& h = p.haptic;
  if (h.proxyKappaLow >= h.proxyKappaHigh)
  {
    h.proxyKappaHigh = std::min(row(Id::ProxyKappaHigh).maximum, h.proxyKappaLow + 0.01);
    h.proxyKappaLow = std::min(h.proxyKappaLow, h.proxyKappaHigh - 0.01);
  }
  return p;
}

void qVesselTouchForceLawWidgetPrivate::updateViews()
{
  for (const DoubleBinding& binding : this->Bindings)
  {
    const QSignalBlocker blocker(binding.SpinBox);
    binding.SpinBox->setValue(binding.get(this->Values));
  }
  {
    const QSignalBlocker b0(this->Ui.proxyTangentRuleComboBox);
    const QSignalBlocker b1(this->Ui.proxySnapRuleComboBox);
    const QSignalBlocker b2(this->Ui.lawComboBox);
    this->Ui.proxyTangentRuleComboBox->setCurrentIndex(
      this->Values.haptic.proxyTangentDrag ? 1 : 0);
    this->Ui.proxySnapRuleComboBox->setCurrentIndex(this->Values.haptic.proxySnapDrag ? 1 : 0);
    this->Ui.lawComboBox->setCurrentIndex(int(this->Law));
  }
  this->Ui.lawPages->setCurrentIndex(int(this->Law));
  this->updateRuleDependentControls();
  this->updatePresetCombo();
}

void qVesselTouchForceLawWidgetPrivate::updateRuleDependentControls()
{
  this->Ui.proxyTangentThresholdSpinBox->setEnabled(this->Values.haptic.proxyTangentDrag);
  this->Ui.proxySnapThresholdSpinBox->setEnabled(this->Values.haptic.proxySnapDrag);
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
  // z_max 0 (its default) is sized from the device's position resolution.
  d->Ui.cohZMaxSpinBox->setSpecialValueText(tr("from the device"));
  d->applyDeviceRanges();
  d->Values = d->clamped(Parameters());
  d->updateViews();

  for (const DoubleBinding& binding : d->Bindings)
  {
    connect(binding.SpinBox,
      QOverload<double>::of(&QDoubleSpinBox::valueChanged),
      this,
      [this, binding](double value)
      {
        Q_D(qVesselTouchForceLawWidget);
        Parameters p = d->Values;
        binding.set(p, value);
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
      p.haptic.proxyTangentDrag = index == 1;
      d->store(p);
    });
  connect(d->Ui.proxySnapRuleComboBox,
    QOverload<int>::of(&QComboBox::currentIndexChanged),
    this,
    [this](int index)
    {
      Q_D(qVesselTouchForceLawWidget);
      Parameters p = d->Values;
      p.haptic.proxySnapDrag = index == 1;
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

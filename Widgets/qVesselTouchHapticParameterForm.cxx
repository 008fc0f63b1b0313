#include "qVesselTouchHapticParameterForm.h"

#include "vtouchHapticParameterTable.h"

#include <QCheckBox>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QLabel>
#include <QSignalBlocker>
#include <QSpinBox>
#include <QVector>
#include <QtDebug>

#include <algorithm>
#include <cmath>

namespace
{
using vtouch::HapticParameterDescriptor;
using vtouch::HapticParameterKind;

/// Decimals that show the row's default and range exactly (2 to 4).
int decimalsFor(const HapticParameterDescriptor& d)
{
  for (int decimals = 2; decimals < 4; ++decimals)
  {
    const double scale = std::pow(10.0, decimals);
    const auto exact = [scale](double v)
    { return std::abs(std::round(v * scale) - v * scale) < 1e-6; };
    if (exact(d.defaultValue) && exact(d.minimum) && exact(d.maximum))
    {
      return decimals;
    }
  }
  return 4;
}

QString withUnit(double value, const char* unit)
{
  const QString text = QString::number(value);
  return *unit ? QStringLiteral("%1 %2").arg(text, QString::fromUtf8(unit)) : text;
}

/// The meaning, with the default and range (all from the table).
QString toolTipFor(const HapticParameterDescriptor& d)
{
  QString tip = QString::fromUtf8(d.meaning);
  if (d.kind == HapticParameterKind::Real || d.kind == HapticParameterKind::Integer)
  {
    tip += QObject::tr(" Default %1, range [%2, %3].")
             .arg(withUnit(d.defaultValue, d.unit),
               QString::number(d.minimum),
               withUnit(d.maximum, d.unit));
  }
  if (*d.forceLaws)
  {
    tip += QObject::tr(" Acts on: %1.")
             .arg(QString::fromUtf8(d.forceLaws).replace(QLatin1Char('|'), QStringLiteral(", ")));
  }
  return tip + QStringLiteral(" (%1)").arg(QString::fromUtf8(d.name));
}

/// Whether the row acts on force law `law`: its "laws" names the law's label among the ForceLaw
/// row's choices, or is empty (every law).
bool actsOn(const HapticParameterDescriptor& d, int law)
{
  if (!*d.forceLaws)
  {
    return true;
  }
  const HapticParameterDescriptor& forceLaw =
    vtouch::hapticParameter(vtouch::HapticParameterId::ForceLaw);
  const QStringList labels = QString::fromUtf8(forceLaw.choices).split(QLatin1Char('|'));
  const int index = law - static_cast<int>(forceLaw.minimum);
  return index >= 0 && index < labels.size() &&
         QString::fromUtf8(d.forceLaws).split(QLatin1Char('|')).contains(labels[index]);
}
} // namespace

class qVesselTouchHapticParameterFormPrivate
{
public:
  struct Row
  {
    const HapticParameterDescriptor* Descriptor;
    QWidget* Editor;
    QLabel* Label;
  };

  vtouch::HapticParameters Parameters;
  int ForceLaw = 0;
  QVector<Row> Rows;
  QFormLayout* Layout = nullptr;

  /// The value a row's control shows.
  static double shown(const Row& row)
  {
    switch (row.Descriptor->kind)
    {
      case HapticParameterKind::Real:
        return static_cast<QDoubleSpinBox*>(row.Editor)->value();
      case HapticParameterKind::Integer:
        return static_cast<QSpinBox*>(row.Editor)->value();
      case HapticParameterKind::Boolean:
        return static_cast<QCheckBox*>(row.Editor)->isChecked() ? 1.0 : 0.0;
      case HapticParameterKind::Choice:
        return static_cast<QComboBox*>(row.Editor)->currentData().toDouble();
    }
    return 0.0;
  }

  /// Shows `value` in a row's control (clamped to the range; NaN: the minimum). No signal.
  static void show(const Row& row, double value)
  {
    const HapticParameterDescriptor& d = *row.Descriptor;
    value = std::isfinite(value) ? std::clamp(value, d.minimum, d.maximum) : d.minimum;
    const QSignalBlocker blocker(row.Editor);
    switch (d.kind)
    {
      case HapticParameterKind::Real:
        static_cast<QDoubleSpinBox*>(row.Editor)->setValue(value);
        break;
      case HapticParameterKind::Integer:
        static_cast<QSpinBox*>(row.Editor)->setValue(static_cast<int>(std::lround(value)));
        break;
      case HapticParameterKind::Boolean:
        static_cast<QCheckBox*>(row.Editor)->setChecked(value != 0.0);
        break;
      case HapticParameterKind::Choice:
      {
        auto* combo = static_cast<QComboBox*>(row.Editor);
        combo->setCurrentIndex(std::max(0, combo->findData(static_cast<int>(std::lround(value)))));
        break;
      }
    }
  }

  void enableForLaw()
  {
    for (const Row& row : this->Rows)
    {
      const bool enabled = actsOn(*row.Descriptor, this->ForceLaw);
      row.Editor->setEnabled(enabled);
      row.Label->setEnabled(enabled);
    }
  }

  QWidget* makeEditor(const HapticParameterDescriptor& d, QWidget* parent)
  {
    const QString unit = QString::fromUtf8(d.unit);
    switch (d.kind)
    {
      case HapticParameterKind::Real:
      {
        auto* spin = new QDoubleSpinBox(parent);
        spin->setDecimals(decimalsFor(d));
        spin->setRange(d.minimum, d.maximum);
        const double span = d.maximum - d.minimum;
        const double step = span > 0.0 ? std::pow(10.0, std::floor(std::log10(span)) - 2.0) : 1.0;
        spin->setSingleStep(std::max(step, std::pow(10.0, -spin->decimals())));
        spin->setKeyboardTracking(false);
        if (!unit.isEmpty())
        {
          spin->setSuffix(QLatin1Char(' ') + unit);
        }
        return spin;
      }
      case HapticParameterKind::Integer:
      {
        auto* spin = new QSpinBox(parent);
        spin->setRange(static_cast<int>(d.minimum), static_cast<int>(d.maximum));
        spin->setKeyboardTracking(false);
        if (!unit.isEmpty())
        {
          spin->setSuffix(QLatin1Char(' ') + unit);
        }
        return spin;
      }
      case HapticParameterKind::Boolean:
        return new QCheckBox(parent);
      case HapticParameterKind::Choice:
      {
        auto* combo = new QComboBox(parent);
        const QStringList labels = QString::fromUtf8(d.choices).split(QLatin1Char('|'));
        for (int i = 0; i < labels.size(); ++i)
        {
          combo->addItem(labels[i], static_cast<int>(d.minimum) + i);
        }
        return combo;
      }
    }
    return nullptr;
  }
};

qVesselTouchHapticParameterForm::qVesselTouchHapticParameterForm(QWidget* parent)
  : QWidget(parent)
  , d_ptr(new qVesselTouchHapticParameterFormPrivate)
{
  Q_D(qVesselTouchHapticParameterForm);
  d->Layout = new QFormLayout(this);
  d->Layout->setContentsMargins(0, 0, 0, 0);
  d->Layout->setFieldGrowthPolicy(QFormLayout::AllNonFixedFieldsGrow);
}

qVesselTouchHapticParameterForm::~qVesselTouchHapticParameterForm() = default;

void qVesselTouchHapticParameterForm::setParameterNames(const QStringList& names)
{
  Q_D(qVesselTouchHapticParameterForm);
  for (const auto& row : d->Rows)
  {
    d->Layout->removeRow(row.Editor);
  }
  d->Rows.clear();
  for (const QString& name : names)
  {
    const HapticParameterDescriptor* descriptor =
      vtouch::findHapticParameter(name.toUtf8().constData());
    if (!descriptor)
    {
      qWarning() << "qVesselTouchHapticParameterForm: no haptic parameter" << name;
      continue;
    }
    qVesselTouchHapticParameterFormPrivate::Row row{ descriptor,
      d->makeEditor(*descriptor, this),
      new QLabel(QString::fromUtf8(descriptor->label), this) };
    row.Editor->setObjectName(name);
    row.Label->setObjectName(name + QStringLiteral("Label"));
    row.Label->setBuddy(row.Editor);
    const QString tip = toolTipFor(*descriptor);
    row.Editor->setToolTip(tip);
    row.Label->setToolTip(tip);
    d->Layout->addRow(row.Label, row.Editor);
    qVesselTouchHapticParameterFormPrivate::show(row, descriptor->get(d->Parameters));
    const auto changed = [this] { emit this->parametersChanged(); };
    if (auto* spin = qobject_cast<QDoubleSpinBox*>(row.Editor))
    {
      connect(spin, QOverload<double>::of(&QDoubleSpinBox::valueChanged), this, changed);
    }
    else if (auto* ispin = qobject_cast<QSpinBox*>(row.Editor))
    {
      connect(ispin, QOverload<int>::of(&QSpinBox::valueChanged), this, changed);
    }
    else if (auto* check = qobject_cast<QCheckBox*>(row.Editor))
    {
      connect(check, &QCheckBox::toggled, this, changed);
    }
    else if (auto* combo = qobject_cast<QComboBox*>(row.Editor))
    {
      connect(combo, QOverload<int>::of(&QComboBox::currentIndexChanged), this, changed);
    }
    d->Rows.push_back(row);
  }
  d->enableForLaw();
}

int qVesselTouchHapticParameterForm::forceLaw() const
{
  Q_D(const qVesselTouchHapticParameterForm);
  return d->ForceLaw;
}

void qVesselTouchHapticParameterForm::setForceLaw(int law)
{
  Q_D(qVesselTouchHapticParameterForm);
  d->ForceLaw = law;
  d->enableForLaw();
}

QStringList qVesselTouchHapticParameterForm::parameterNames() const
{
  Q_D(const qVesselTouchHapticParameterForm);
  QStringList names;
  for (const auto& row : d->Rows)
  {
    names << QString::fromUtf8(row.Descriptor->name);
  }
  return names;
}

vtouch::HapticParameters qVesselTouchHapticParameterForm::parameters() const
{
  Q_D(const qVesselTouchHapticParameterForm);
  vtouch::HapticParameters p = d->Parameters;
  this->writeTo(p);
  return p;
}

void qVesselTouchHapticParameterForm::writeTo(vtouch::HapticParameters& p) const
{
  Q_D(const qVesselTouchHapticParameterForm);
  for (const auto& row : d->Rows)
  {
    row.Descriptor->set(p, qVesselTouchHapticParameterFormPrivate::shown(row));
  }
}

QWidget* qVesselTouchHapticParameterForm::editor(const QString& name) const
{
  Q_D(const qVesselTouchHapticParameterForm);
  for (const auto& row : d->Rows)
  {
    if (name == QLatin1String(row.Descriptor->name))
    {
      return row.Editor;
    }
  }
  return nullptr;
}

void qVesselTouchHapticParameterForm::setParameters(const vtouch::HapticParameters& p)
{
  Q_D(qVesselTouchHapticParameterForm);
  d->Parameters = p;
  bool changed = false;
  for (const auto& row : d->Rows)
  {
    const double before = qVesselTouchHapticParameterFormPrivate::shown(row);
    qVesselTouchHapticParameterFormPrivate::show(row, row.Descriptor->get(p));
    changed = changed || qVesselTouchHapticParameterFormPrivate::shown(row) != before;
  }
  if (changed)
  {
    emit this->parametersChanged();
  }
}

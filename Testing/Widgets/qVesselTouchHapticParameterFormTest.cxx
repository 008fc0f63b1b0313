// The table-driven form of haptic parameters (the panel's Advanced section): one row per name
// with the table's label, range, unit and meaning, the table's defaults, a round trip through
// vtouch::HapticParameters, clamping, and one parametersChanged() per change.
#include "qVesselTouchHapticParameterForm.h"

#include "vtouchHapticParameterTable.h"

#include <QCheckBox>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QLabel>
#include <QSignalSpy>
#include <QSpinBox>
#include <QTest>

#include <limits>

namespace
{
QStringList everyName()
{
  QStringList names;
  for (const vtouch::HapticParameterDescriptor& d : vtouch::kHapticParameterDescriptors)
  {
    names << QString::fromLatin1(d.name);
  }
  return names;
}
} // namespace

class qVesselTouchHapticParameterFormTest : public QObject
{
  Q_OBJECT

private slots:
  void rowsAreBuiltFromTheTable()
  {
    qVesselTouchHapticParameterForm w;
    w.setParameterNames(everyName() << QStringLiteral("NoSuchParameter"));
    QCOMPARE(w.parameterNames(), everyName());
    for (const vtouch::HapticParameterDescriptor& d : vtouch::kHapticParameterDescriptors)
    {
      const QString name = QString::fromLatin1(d.name);
      QWidget* editor = w.editor(name);
      QVERIFY2(editor, d.name);
      QVERIFY(editor->toolTip().contains(QString::fromUtf8(d.meaning)));
      auto* label = w.findChild<QLabel*>(name + QStringLiteral("Label"));
      QVERIFY(label);
      QCOMPARE(label->text(), QString::fromUtf8(d.label));
      switch (d.kind)
      {
        case vtouch::HapticParameterKind::Real:
        {
          auto* spin = qobject_cast<QDoubleSpinBox*>(editor);
          QVERIFY2(spin, d.name);
          QCOMPARE(spin->minimum(), d.minimum);
          QCOMPARE(spin->maximum(), d.maximum);
          QCOMPARE(spin->value(), d.defaultValue);
          QVERIFY(spin->suffix().contains(QString::fromUtf8(d.unit)));
          break;
        }
        case vtouch::HapticParameterKind::Integer:
        {
          auto* spin = qobject_cast<QSpinBox*>(editor);
          QVERIFY2(spin, d.name);
          QCOMPARE(spin->minimum(), static_cast<int>(d.minimum));
          QCOMPARE(spin->maximum(), static_cast<int>(d.maximum));
          QCOMPARE(spin->value(), static_cast<int>(d.defaultValue));
          break;
        }
        case vtouch::HapticParameterKind::Boolean:
        {
          auto* check = qobject_cast<QCheckBox*>(editor);
          QVERIFY2(check, d.name);
          QCOMPARE(check->isChecked(), d.defaultValue != 0.0);
          break;
        }
        case vtouch::HapticParameterKind::Choice:
        {
          auto* combo = qobject_cast<QComboBox*>(editor);
          QVERIFY2(combo, d.name);
          QCOMPARE(combo->count(), static_cast<int>(d.maximum - d.minimum) + 1);
          QCOMPARE(combo->currentData().toDouble(), d.defaultValue);
          QCOMPARE(combo->itemText(0), QString::fromUtf8(d.choices).section('|', 0, 0));
          break;
        }
      }
    }
    // The defaults are the table's: the form's parameters are a default HapticParameters.
    const vtouch::HapticParameters shown = w.parameters();
    for (const vtouch::HapticParameterDescriptor& d : vtouch::kHapticParameterDescriptors)
    {
      QCOMPARE(d.get(shown), d.defaultValue);
    }
  }

  void roundTripsEveryRowAndClamps()
  {
    qVesselTouchHapticParameterForm w;
    w.setParameterNames(everyName());
    QSignalSpy spy(&w, &qVesselTouchHapticParameterForm::parametersChanged);
    // Every row to its maximum (a value the table accepts, other than the default).
    vtouch::HapticParameters p;
    for (const vtouch::HapticParameterDescriptor& d : vtouch::kHapticParameterDescriptors)
    {
      d.set(p, d.maximum);
    }
    w.setParameters(p);
    QCOMPARE(spy.count(), 1);
    vtouch::HapticParameters read;
    w.writeTo(read);
    for (const vtouch::HapticParameterDescriptor& d : vtouch::kHapticParameterDescriptors)
    {
      QCOMPARE(d.get(read), d.get(p));
    }
    w.setParameters(p); // unchanged: no signal
    QCOMPARE(spy.count(), 1);
    // Out of range or not a number: clamped to the table's range.
    vtouch::HapticParameters wild;
    wild.slopeForceBudget = 7.0;
    wild.proxyTickForce_N = std::numeric_limits<double>::quiet_NaN();
    wild.tracerRule = 5;
    w.setParameters(wild);
    const auto& budget = vtouch::hapticParameter(vtouch::HapticParameterId::SlopeForceBudget);
    const auto& tick = vtouch::hapticParameter(vtouch::HapticParameterId::ProxyTickForce);
    const auto& rule = vtouch::hapticParameter(vtouch::HapticParameterId::TracerRule);
    QCOMPARE(w.parameters().slopeForceBudget, budget.maximum);
    QCOMPARE(w.parameters().proxyTickForce_N, tick.minimum);
    QCOMPARE(static_cast<double>(w.parameters().tracerRule), rule.maximum);
  }

  void onlyItsRowsAreWritten()
  {
    qVesselTouchHapticParameterForm w;
    w.setParameterNames({ QStringLiteral("TracerJunctionWindow") });
    vtouch::HapticParameters p;
    p.zoom = 3.0;
    p.tracerJunctionWindow_px = 12.0;
    w.setParameters(p);
    vtouch::HapticParameters other;
    w.writeTo(other);
    QCOMPARE(other.tracerJunctionWindow_px, 12.0);
    QCOMPARE(other.zoom, vtouch::HapticParameters{}.zoom); // not a row: untouched
    QCOMPARE(w.parameters().zoom, 3.0);                    // carried along
  }

  void everyControlEmitsOnce()
  {
    qVesselTouchHapticParameterForm w;
    w.setParameterNames({ QStringLiteral("TracerRule"),
      QStringLiteral("TracerJunctionWindow"),
      QStringLiteral("ContactApproachAtStart"),
      QStringLiteral("ReindexButtonMask") });
    QSignalSpy spy(&w, &qVesselTouchHapticParameterForm::parametersChanged);
    qobject_cast<QComboBox*>(w.editor(QStringLiteral("TracerRule")))->setCurrentIndex(1);
    qobject_cast<QDoubleSpinBox*>(w.editor(QStringLiteral("TracerJunctionWindow")))->setValue(12.0);
    qobject_cast<QCheckBox*>(w.editor(QStringLiteral("ContactApproachAtStart")))->setChecked(false);
    qobject_cast<QSpinBox*>(w.editor(QStringLiteral("ReindexButtonMask")))->setValue(4);
    QCOMPARE(spy.count(), 4);
    const vtouch::HapticParameters p = w.parameters();
    QCOMPARE(p.tracerRule, 1);
    QCOMPARE(p.tracerJunctionWindow_px, 12.0);
    QCOMPARE(p.contactApproachAtStart, false);
    QCOMPARE(p.reindexButtonMask, 4u);
  }

  void rowsNotActingOnTheForceLawAreGreyedOut()
  {
    // The table's "laws" column: ProxyFriction acts on the constraint proxy only,
    // SlopeForceBudget on LDGF and change of height, ContactDwell on every law.
    qVesselTouchHapticParameterForm w;
    w.setParameterNames({ QStringLiteral("ProxyFriction"),
      QStringLiteral("SlopeForceBudget"),
      QStringLiteral("ContactDwell") });
    const auto enabled = [&w](const char* name)
    { return w.editor(QString::fromLatin1(name))->isEnabled(); };
    QCOMPARE(w.forceLaw(), 0); // LDGF
    QVERIFY(!enabled("ProxyFriction"));
    QVERIFY(enabled("SlopeForceBudget"));
    QVERIFY(enabled("ContactDwell"));
    QVERIFY(w.editor(QStringLiteral("ProxyFriction"))->toolTip().contains("Constraint proxy"));

    w.setForceLaw(static_cast<int>(vtouch::ForceLawId::ConstraintProxy));
    QVERIFY(enabled("ProxyFriction"));
    QVERIFY(!enabled("SlopeForceBudget"));
    QVERIFY(enabled("ContactDwell"));

    w.setForceLaw(static_cast<int>(vtouch::ForceLawId::None));
    QVERIFY(!enabled("ProxyFriction"));
    QVERIFY(!enabled("SlopeForceBudget"));
    QVERIFY(enabled("ContactDwell"));
    // Greyed out, the value is kept and still written.
    vtouch::HapticParameters p;
    p.proxyFriction = 0.3;
    w.setParameters(p);
    QCOMPARE(w.parameters().proxyFriction, 0.3);
  }
};

QTEST_MAIN(qVesselTouchHapticParameterFormTest)
#include "qVesselTouchHapticParameterFormTest.moc"

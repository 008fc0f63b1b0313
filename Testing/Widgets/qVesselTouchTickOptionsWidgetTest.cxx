// The tick options of the panel's Advanced section: Logic's defaults, every control edits its
// field (one signal per change), setOptions() round-trips and clamps, dependent controls.
#include "qVesselTouchTickOptionsWidget.h"

#include <QCheckBox>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QSignalSpy>
#include <QTest>

#include <limits>

class qVesselTouchTickOptionsWidgetTest : public QObject
{
  Q_OBJECT

private:
  template<typename T>
  static T* child(qVesselTouchTickOptionsWidget& w, const char* name)
  {
    T* c = w.findChild<T*>(QString::fromLatin1(name));
    if (!c)
    {
      qFatal("no control %s", name);
    }
    return c;
  }

private slots:
  void defaultsAreLogics()
  {
    qVesselTouchTickOptionsWidget w;
    const qVesselTouchTickOptions o = w.options();
    QVERIFY(o == qVesselTouchTickOptions{});
    QCOMPARE(o.tracerRule, 0);
    QCOMPARE(o.tracerJunctionWindow_px, 24.0);
    QCOMPARE(o.contactDwell_s, 0.05);
    QCOMPARE(o.slopeForceBudget, 0.9);
    QCOMPARE(o.proxyTickForce_N, 0.3);
    QCOMPARE(o.idleDwell_s, 1.5);
    QCOMPARE(child<QDoubleSpinBox>(w, "junctionWindowSpinBox")->value(), 24.0);
    QVERIFY(child<QCheckBox>(w, "contactApproachCheckBox")->isChecked());
    QVERIFY(!child<QDoubleSpinBox>(w, "movementThresholdSpinBox")->isEnabled()); // offset rule
    QVERIFY(!child<QDoubleSpinBox>(w, "tickForceSpinBox")->isEnabled());         // no ticks
  }

  void everyControlEditsItsField()
  {
    qVesselTouchTickOptionsWidget w;
    QSignalSpy spy(&w, &qVesselTouchTickOptionsWidget::optionsChanged);
    child<QComboBox>(w, "tracerRuleComboBox")->setCurrentIndex(1);
    child<QDoubleSpinBox>(w, "movementThresholdSpinBox")->setValue(0.05);
    child<QDoubleSpinBox>(w, "junctionWindowSpinBox")->setValue(12.0);
    child<QDoubleSpinBox>(w, "junctionMarginSpinBox")->setValue(2.0);
    child<QDoubleSpinBox>(w, "contactDwellSpinBox")->setValue(0.02);
    child<QCheckBox>(w, "contactApproachCheckBox")->setChecked(false);
    child<QDoubleSpinBox>(w, "slopeBudgetSpinBox")->setValue(0.5);
    child<QCheckBox>(w, "perAxisCheckBox")->setChecked(true);
    child<QDoubleSpinBox>(w, "zMaxCountsSpinBox")->setValue(3.0);
    child<QCheckBox>(w, "tangentSnapCheckBox")->setChecked(true);
    child<QCheckBox>(w, "normalUnilateralCheckBox")->setChecked(true);
    child<QCheckBox>(w, "thresholdFromDataCheckBox")->setChecked(true);
    child<QDoubleSpinBox>(w, "frictionSpinBox")->setValue(0.2);
    child<QDoubleSpinBox>(w, "tickSpacingSpinBox")->setValue(2.0);
    child<QDoubleSpinBox>(w, "tickForceSpinBox")->setValue(0.4);
    child<QCheckBox>(w, "tickAtBifurcationsCheckBox")->setChecked(true);
    child<QCheckBox>(w, "fieldForceCheckBox")->setChecked(true);
    child<QDoubleSpinBox>(w, "idleRadiusSpinBox")->setValue(0.5);
    child<QDoubleSpinBox>(w, "idleDwellSpinBox")->setValue(2.0);
    child<QDoubleSpinBox>(w, "idleRampSpinBox")->setValue(0.1);
    QCOMPARE(spy.count(), 20);
    const qVesselTouchTickOptions o = w.options();
    QCOMPARE(o.tracerRule, 1);
    QCOMPARE(o.tracerMovementThreshold_px, 0.05);
    QCOMPARE(o.tracerJunctionWindow_px, 12.0);
    QCOMPARE(o.tracerJunctionMargin_px, 2.0);
    QCOMPARE(o.contactDwell_s, 0.02);
    QCOMPARE(o.contactApproachAtStart, false);
    QCOMPARE(o.slopeForceBudget, 0.5);
    QCOMPARE(o.forceInterpolationPerAxis, true);
    QCOMPARE(o.cohZMaxPerResolution, 3.0);
    QCOMPARE(o.proxyTangentSnap, true);
    QCOMPARE(o.proxyNormalUnilateral, true);
    QCOMPARE(o.proxyThresholdFromData, true);
    QCOMPARE(o.proxyFriction, 0.2);
    QCOMPARE(o.proxyTickSpacing_mm, 2.0);
    QCOMPARE(o.proxyTickForce_N, 0.4);
    QCOMPARE(o.proxyTickAtBifurcations, true);
    QCOMPARE(o.proxyFieldForce, true);
    QCOMPARE(o.idleRadius_mm, 0.5);
    QCOMPARE(o.idleDwell_s, 2.0);
    QCOMPARE(o.idleRamp_s, 0.1);
    QVERIFY(child<QDoubleSpinBox>(w, "movementThresholdSpinBox")->isEnabled());
    QVERIFY(child<QDoubleSpinBox>(w, "tickForceSpinBox")->isEnabled());
  }

  void setOptionsRoundTripsAndClamps()
  {
    qVesselTouchTickOptionsWidget w;
    QSignalSpy spy(&w, &qVesselTouchTickOptionsWidget::optionsChanged);
    qVesselTouchTickOptions o;
    o.tracerJunctionWindow_px = 0.0; // off
    o.idleDwell_s = 0.0;             // never
    o.proxyFriction = 0.3;
    w.setOptions(o);
    QCOMPARE(spy.count(), 1);
    QVERIFY(w.options() == o);
    QVERIFY(!child<QDoubleSpinBox>(w, "junctionMarginSpinBox")->isEnabled());
    QCOMPARE(child<QDoubleSpinBox>(w, "junctionWindowSpinBox")->text(), QStringLiteral("off"));
    w.setOptions(o); // unchanged: no signal
    QCOMPARE(spy.count(), 1);
    o.slopeForceBudget = 7.0;                                      // above the range
    o.proxyTickForce_N = std::numeric_limits<double>::quiet_NaN(); // not a number
    o.tracerRule = 5;
    w.setOptions(o);
    QCOMPARE(w.options().slopeForceBudget, 1.0);
    QCOMPARE(w.options().proxyTickForce_N, 0.0);
    QCOMPARE(w.options().tracerRule, 1);
  }
};

QTEST_MAIN(qVesselTouchTickOptionsWidgetTest)
#include "qVesselTouchTickOptionsWidgetTest.moc"

// The force law: switching laws changes the page and emits, presets set the parameters, edits
// emit, device limits clamp the coupler.
#include "qVesselTouchForceLawWidget.h"

#include <QComboBox>
#include <QDoubleSpinBox>
#include <QSignalSpy>
#include <QStackedWidget>
#include <QTest>

class qVesselTouchForceLawWidgetTest : public QObject
{
  Q_OBJECT

private:
  template<typename T>
  static T* child(QWidget& w, const char* name)
  {
    T* found = w.findChild<T*>(QString::fromLatin1(name));
    if (!found)
    {
      qFatal("no child %s", name);
    }
    return found;
  }
  static QString currentPage(qVesselTouchForceLawWidget& w)
  {
    return child<QStackedWidget>(w, "lawPages")->currentWidget()->objectName();
  }

private slots:
  void defaultsMatchTheHapticLogic()
  {
    // Every parameter the widget shows starts at the table's default and offers the table's
    // range (vtouchHapticParameters.def), as the session proxy and Python do.
    qVesselTouchForceLawWidget w;
    QCOMPARE(w.forceLaw(), qVesselTouchForceLawWidget::Ldgf);
    QCOMPARE(currentPage(w), QStringLiteral("ldgfPage"));
    QVERIFY(w.parameters() == qVesselTouchForceLawParameters());
    for (const vtouch::HapticParameterDescriptor& d : vtouch::kHapticParameterDescriptors)
    {
      QCOMPARE(d.get(w.parameters().haptic), d.defaultValue);
    }
    const struct
    {
      const char* SpinBox;
      vtouch::HapticParameterId Row;
    } shown[] = { { "ldgfGainSpinBox", vtouch::HapticParameterId::ZoneGain },
      { "ldgfLambdaSpinBox", vtouch::HapticParameterId::LdgfLambda },
      { "cohLambdaSpinBox", vtouch::HapticParameterId::ChangeOfHeightLambda },
      { "cohZMaxSpinBox", vtouch::HapticParameterId::ChangeOfHeightZMax },
      { "lateralProbeSpinBox", vtouch::HapticParameterId::LateralProbe },
      { "proxyStiffnessSpinBox", vtouch::HapticParameterId::ProxyStiffness },
      { "proxyDampingSpinBox", vtouch::HapticParameterId::ProxyDamping },
      { "proxyKappaLowSpinBox", vtouch::HapticParameterId::ProxyKappaLow },
      { "proxyKappaHighSpinBox", vtouch::HapticParameterId::ProxyKappaHigh } };
    for (const auto& s : shown)
    {
      const vtouch::HapticParameterDescriptor& d = vtouch::hapticParameter(s.Row);
      const QDoubleSpinBox* box = child<QDoubleSpinBox>(w, s.SpinBox);
      QCOMPARE(box->value(), d.defaultValue);
      QCOMPARE(box->minimum(), d.minimum);
      QCOMPARE(box->maximum(), d.maximum);
    }
    QCOMPARE(w.parameters().haptic.ldgfLambda_mm, 0.005);          // the drift of issue 18
    QCOMPARE(w.parameters().haptic.proxyStiffness_N_per_m, 200.0); // is gone
    QCOMPARE(child<QDoubleSpinBox>(w, "proxyStiffnessSpinBox")->suffix(), QStringLiteral(" N/m"));
    QCOMPARE(child<QDoubleSpinBox>(w, "proxyDampingSpinBox")->suffix(), QStringLiteral(" N·s/m"));
    QCOMPARE(w.presetName(), QStringLiteral("Default"));
    QCOMPARE(child<QComboBox>(w, "presetComboBox")->currentText(), QStringLiteral("Default"));
  }

  void choosingALawInTheComboShowsItsPage()
  {
    qVesselTouchForceLawWidget w;
    w.show();
    QSignalSpy spy(&w, &qVesselTouchForceLawWidget::forceLawChanged);
    QComboBox* combo = child<QComboBox>(w, "lawComboBox");
    combo->setFocus();
    QTest::keyClick(combo, Qt::Key_End); // the last law: constraint proxy
    QCOMPARE(spy.count(), 1);
    QCOMPARE(spy.at(0).at(0).toInt(), int(qVesselTouchForceLawWidget::ConstraintProxy));
    QCOMPARE(w.forceLaw(), qVesselTouchForceLawWidget::ConstraintProxy);
    QCOMPARE(currentPage(w), QStringLiteral("proxyPage"));
    QVERIFY(child<QDoubleSpinBox>(w, "proxyStiffnessSpinBox")->isVisible());
    QVERIFY(!child<QDoubleSpinBox>(w, "ldgfLambdaSpinBox")->isVisible());

    QTest::keyClick(combo, Qt::Key_Up);
    QCOMPARE(spy.count(), 2);
    QCOMPARE(currentPage(w), QStringLiteral("lateralPage"));
  }

  void setForceLawUpdatesComboAndPageOnce()
  {
    qVesselTouchForceLawWidget w;
    QSignalSpy spy(&w, &qVesselTouchForceLawWidget::forceLawChanged);
    w.setForceLaw(qVesselTouchForceLawWidget::ChangeOfHeight);
    QCOMPARE(spy.count(), 1);
    QCOMPARE(currentPage(w), QStringLiteral("cohPage"));
    QCOMPARE(child<QComboBox>(w, "lawComboBox")->currentIndex(), 1);
    w.setForceLaw(qVesselTouchForceLawWidget::ChangeOfHeight); // no change, no signal
    w.setForceLaw(7);                                          // unknown, ignored
    QCOMPARE(spy.count(), 1);
    QCOMPARE(w.forceLaw(), qVesselTouchForceLawWidget::ChangeOfHeight);
    QVERIFY(w.setProperty("forceLaw", int(qVesselTouchForceLawWidget::Ldgf)));
    QCOMPARE(spy.count(), 2);
  }

  void presetsSetTheParametersOfTheCurrentLaw()
  {
    qVesselTouchForceLawWidget w;
    QSignalSpy spy(&w, &qVesselTouchForceLawWidget::parametersChanged);
    QVERIFY(w.applyPreset(QStringLiteral("Firm")));
    QCOMPARE(spy.count(), 1);
    QCOMPARE(w.parameters().ldgfGain_N, 2.0);
    QCOMPARE(w.parameters().haptic.ldgfLambda_mm, 0.0025);
    QCOMPARE(child<QDoubleSpinBox>(w, "ldgfGainSpinBox")->value(), 2.0);
    QCOMPARE(w.presetName(), QStringLiteral("Firm"));
    QCOMPARE(child<QComboBox>(w, "presetComboBox")->currentText(), QStringLiteral("Firm"));
    // Other laws keep their values.
    QCOMPARE(w.parameters().cohGain_N, 1.0);
    QVERIFY(!w.applyPreset(QStringLiteral("Bogus")));
    QCOMPARE(spy.count(), 1);
  }

  void presetComboAppliesThePreset()
  {
    qVesselTouchForceLawWidget w;
    w.show();
    w.setForceLaw(qVesselTouchForceLawWidget::ChangeOfHeight);
    QSignalSpy spy(&w, &qVesselTouchForceLawWidget::parametersChanged);
    QComboBox* presets = child<QComboBox>(w, "presetComboBox");
    presets->setFocus();
    QTest::keyClick(presets, Qt::Key_Up); // Default -> Gentle
    QCOMPARE(spy.count(), 1);
    qVesselTouchForceLawParameters gentle;
    QVERIFY(qVesselTouchForceLawWidget::presetParameters(
      qVesselTouchForceLawWidget::ChangeOfHeight, QStringLiteral("Gentle"), gentle));
    QVERIFY(w.parameters() == gentle);
    // z_max is the device's (Hayward & Yi App. A), in every preset.
    QCOMPARE(w.parameters().haptic.cohZMax_mm, 0.0);
    QCOMPARE(child<QDoubleSpinBox>(w, "cohZMaxSpinBox")->text(), QStringLiteral("from the device"));
  }

  void editingAParameterEmitsAndLeavesThePreset()
  {
    qVesselTouchForceLawWidget w;
    QSignalSpy spy(&w, &qVesselTouchForceLawWidget::parametersChanged);
    child<QDoubleSpinBox>(w, "ldgfLambdaSpinBox")->setValue(0.02);
    QCOMPARE(spy.count(), 1);
    QCOMPARE(w.parameters().haptic.ldgfLambda_mm, 0.02);
    QCOMPARE(w.presetName(), QStringLiteral("Custom"));
    QCOMPARE(child<QComboBox>(w, "presetComboBox")->currentText(), QStringLiteral("Custom"));
    // The same parameters again: no signal.
    w.setParameters(w.parameters());
    QCOMPARE(spy.count(), 1);
  }

  void ruleChoiceEnablesItsThreshold()
  {
    qVesselTouchForceLawWidget w;
    w.setForceLaw(qVesselTouchForceLawWidget::ConstraintProxy);
    QDoubleSpinBox* tau = child<QDoubleSpinBox>(w, "proxyTangentThresholdSpinBox");
    QVERIFY(!tau->isEnabled());
    QSignalSpy spy(&w, &qVesselTouchForceLawWidget::parametersChanged);
    child<QComboBox>(w, "proxyTangentRuleComboBox")->setCurrentIndex(1); // Drag
    QCOMPARE(spy.count(), 1);
    QVERIFY(w.parameters().haptic.proxyTangentDrag);
    QVERIFY(tau->isEnabled());
    child<QComboBox>(w, "proxySnapRuleComboBox")->setCurrentIndex(1); // Snap-drag
    QVERIFY(w.parameters().haptic.proxySnapDrag);
    QVERIFY(child<QDoubleSpinBox>(w, "proxySnapThresholdSpinBox")->isEnabled());
  }

  void deviceLimitsClampTheCoupler()
  {
    qVesselTouchForceLawWidget w;
    w.setForceLaw(qVesselTouchForceLawWidget::ConstraintProxy);
    qVesselTouchForceLawParameters p;
    p.haptic.proxyStiffness_N_per_m = 1000.0;
    p.haptic.proxyDamping_N_s_per_m = 0.2;
    w.setParameters(p);
    QCOMPARE(w.parameters().haptic.proxyStiffness_N_per_m, 1000.0);

    QSignalSpy spy(&w, &qVesselTouchForceLawWidget::parametersChanged);
    w.setDeviceLimits(400.0, 0.4);
    QCOMPARE(spy.count(), 1);
    QCOMPARE(w.parameters().haptic.proxyStiffness_N_per_m, 400.0);
    QCOMPARE(w.parameters().haptic.proxyDamping_N_s_per_m, 0.2); // below its bound: untouched
    QCOMPARE(child<QDoubleSpinBox>(w, "proxyStiffnessSpinBox")->maximum(), 400.0);
    QCOMPARE(child<QDoubleSpinBox>(w, "proxyStiffnessSpinBox")->value(), 400.0);
    QCOMPARE(w.maxStiffness_N_per_m(), 400.0);

    // A preset above the bound lands on the bound.
    QVERIFY(w.applyPreset(QStringLiteral("Firm")));
    QCOMPARE(w.parameters().haptic.proxyStiffness_N_per_m, 400.0);
    QCOMPARE(w.presetName(), QStringLiteral("Firm"));

    // Asking for more than the device allows is refused.
    p = w.parameters();
    p.haptic.proxyDamping_N_s_per_m = 5.0;
    w.setParameters(p);
    QCOMPARE(w.parameters().haptic.proxyDamping_N_s_per_m, 0.4);

    // Removing the bounds keeps the values but widens the ranges to the table's.
    w.setDeviceLimits(0.0, 0.0);
    QCOMPARE(w.parameters().haptic.proxyStiffness_N_per_m, 400.0);
    QCOMPARE(child<QDoubleSpinBox>(w, "proxyStiffnessSpinBox")->maximum(),
      vtouch::hapticParameter(vtouch::HapticParameterId::ProxyStiffness).maximum);
  }

  void kappaKneesStayOrdered()
  {
    qVesselTouchForceLawWidget w;
    child<QDoubleSpinBox>(w, "proxyKappaLowSpinBox")->setValue(0.8);
    QCOMPARE(w.parameters().haptic.proxyKappaLow, 0.8);
    QVERIFY(w.parameters().haptic.proxyKappaHigh > w.parameters().haptic.proxyKappaLow);
    QCOMPARE(child<QDoubleSpinBox>(w, "proxyKappaHighSpinBox")->value(),
      w.parameters().haptic.proxyKappaHigh);
  }

  void everyLawHasEveryPreset()
  {
    for (int law = 0; law < qVesselTouchForceLawWidget::kForceLawCount; ++law)
    {
      qVesselTouchForceLawParameters gentle, firm;
      const auto id = qVesselTouchForceLawWidget::ForceLaw(law);
      QVERIFY(qVesselTouchForceLawWidget::presetParameters(id, QStringLiteral("Gentle"), gentle));
      QVERIFY(qVesselTouchForceLawWidget::presetParameters(id, QStringLiteral("Firm"), firm));
      QVERIFY(gentle != firm);
      QVERIFY(!qVesselTouchForceLawWidget::forceLawLabel(id).isEmpty());
    }
  }
};

QTEST_MAIN(qVesselTouchForceLawWidgetTest)
#include "qVesselTouchForceLawWidgetTest.moc"

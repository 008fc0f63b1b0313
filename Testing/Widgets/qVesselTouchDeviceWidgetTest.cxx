// The device panel: the list the module fills, selection, capabilities, calibration, faults.
#include "qVesselTouchDeviceWidget.h"

#include <QComboBox>
#include <QDoubleSpinBox>
#include <QGroupBox>
#include <QLabel>
#include <QSignalSpy>
#include <QTest>

class qVesselTouchDeviceWidgetTest : public QObject
{
  Q_OBJECT

private:
  static QList<qVesselTouchDeviceEntry> threeDevices()
  {
    return {
      { QStringLiteral("pointer"), QStringLiteral("Mouse pointer"), QStringLiteral("pointer") },
      { QStringLiteral("simulated"),
        QStringLiteral("Simulated device"),
        QStringLiteral("simulated") },
      { QStringLiteral("hid:/dev/hidraw3"), QStringLiteral("OpenFFBoard"), QStringLiteral("hid") },
    };
  }
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
  static QString text(QWidget& w, const char* name) { return child<QLabel>(w, name)->text(); }

private slots:
  void fillingTheListSelectsTheFirstDevice()
  {
    qVesselTouchDeviceWidget w;
    QCOMPARE(w.currentDeviceId(), QString());
    QSignalSpy spy(&w, &qVesselTouchDeviceWidget::deviceSelected);
    w.setAvailableDevices(threeDevices());
    QCOMPARE(child<QComboBox>(w, "deviceComboBox")->count(), 3);
    QCOMPARE(child<QComboBox>(w, "deviceComboBox")->itemText(2), QStringLiteral("OpenFFBoard"));
    QCOMPARE(spy.count(), 1);
    QCOMPARE(spy.at(0).at(0).toString(), QStringLiteral("pointer"));
    QCOMPARE(w.currentDeviceId(), QStringLiteral("pointer"));
    QCOMPARE(text(w, "kindValue"), QStringLiteral("pointer"));
  }

  void pickingADeviceEmitsItsId()
  {
    qVesselTouchDeviceWidget w;
    w.show();
    w.setAvailableDevices(threeDevices());
    QSignalSpy spy(&w, &qVesselTouchDeviceWidget::deviceSelected);
    QComboBox* combo = child<QComboBox>(w, "deviceComboBox");
    combo->setFocus();
    QTest::keyClick(combo, Qt::Key_End);
    QCOMPARE(spy.count(), 1);
    QCOMPARE(spy.at(0).at(0).toString(), QStringLiteral("hid:/dev/hidraw3"));
    QCOMPARE(text(w, "kindValue"), QStringLiteral("hid"));

    w.setCurrentDeviceId(QStringLiteral("simulated"));
    QCOMPARE(spy.count(), 2);
    QCOMPARE(combo->currentText(), QStringLiteral("Simulated device"));
    w.setCurrentDeviceId(QStringLiteral("simulated")); // same: no signal
    w.setCurrentDeviceId(QStringLiteral("nope"));      // unknown: ignored
    QCOMPARE(spy.count(), 2);
    QCOMPARE(w.currentDeviceId(), QStringLiteral("simulated"));
  }

  void refreshingTheListKeepsAListedSelection()
  {
    qVesselTouchDeviceWidget w;
    w.setAvailableDevices(threeDevices());
    w.setCurrentDeviceId(QStringLiteral("simulated"));
    QSignalSpy spy(&w, &qVesselTouchDeviceWidget::deviceSelected);
    QVariantList maps;
    for (const qVesselTouchDeviceEntry& entry : threeDevices())
    {
      maps << entry.toVariantMap();
    }
    maps.removeLast(); // the HID device was unplugged
    w.setAvailableDeviceMaps(maps);
    QCOMPARE(spy.count(), 0);
    QCOMPARE(w.currentDeviceId(), QStringLiteral("simulated"));
    QCOMPARE(w.availableDevices().size(), 2);

    w.setAvailableDevices({ threeDevices().at(2) }); // the selection disappears
    QCOMPARE(spy.count(), 1);
    QCOMPARE(w.currentDeviceId(), QStringLiteral("hid:/dev/hidraw3"));
    w.setAvailableDevices({});
    QCOMPARE(spy.count(), 2);
    QCOMPARE(w.currentDeviceId(), QString());
  }

  void faultShowsARedMessageUntilCleared()
  {
    qVesselTouchDeviceWidget w;
    w.show();
    QLabel* fault = child<QLabel>(w, "faultLabel");
    QVERIFY(!fault->isVisible());
    QVERIFY(!w.hasFault());
    QSignalSpy spy(&w, &qVesselTouchDeviceWidget::faultChanged);

    w.setFault(QStringLiteral("device lost (USB unplugged)"));
    QVERIFY(fault->isVisible());
    QVERIFY(fault->text().contains(QStringLiteral("device lost (USB unplugged)")));
    QVERIFY(w.hasFault());
    QCOMPARE(w.faultMessage(), QStringLiteral("device lost (USB unplugged)"));
    QCOMPARE(spy.count(), 1);
    // Red text, as the user sees it.
    QCOMPARE(fault->palette().color(QPalette::WindowText), QColor(0xb0, 0x00, 0x00));

    w.setFault(QStringLiteral("watchdog: no update for 5 ms")); // replaced, still shown
    QCOMPARE(spy.count(), 1);
    QVERIFY(fault->text().contains(QStringLiteral("watchdog")));

    w.clearFault();
    QVERIFY(!fault->isVisible());
    QVERIFY(!w.hasFault());
    QCOMPARE(w.faultMessage(), QString());
    QCOMPARE(spy.count(), 2);
    QCOMPARE(spy.at(1).at(0).toBool(), false);
  }

  void statusAndCapabilitiesAreShownWithUnits()
  {
    qVesselTouchDeviceWidget w;
    w.show();
    QCOMPARE(text(w, "maxForceValue"), QStringLiteral("-"));
    w.setStatusText(QStringLiteral("connected, 1000 Hz"));
    QCOMPARE(w.statusText(), QStringLiteral("connected, 1000 Hz"));
    QCOMPARE(text(w, "statusValue"), QStringLiteral("connected, 1000 Hz"));

    QVariantMap caps;
    caps[QStringLiteral("name")] = QStringLiteral("OpenFFBoard");
    caps[QStringLiteral("sensedDof")] = 3;
    caps[QStringLiteral("actuatedDof")] = 2;
    caps[QStringLiteral("workspace_mm")] = QVariantList{ 120.0, 80.0, 30.0 };
    caps[QStringLiteral("maxContinuousForce_N")] = 2.5;
    caps[QStringLiteral("maxStiffness_N_per_m")] = 800.0;
    caps[QStringLiteral("maxUpdateRate_Hz")] = 1000.0;
    caps[QStringLiteral("hasPressure")] = true;
    caps[QStringLiteral("buttonCount")] = 4;
    w.setCapabilityMap(caps);
    QCOMPARE(text(w, "nameValue"), QStringLiteral("OpenFFBoard"));
    QCOMPARE(text(w, "dofValue"), QStringLiteral("3 sensed, 2 actuated"));
    QCOMPARE(text(w, "workspaceValue"), QStringLiteral("120 × 80 × 30 mm"));
    QCOMPARE(text(w, "maxForceValue"), QStringLiteral("2.50 N"));
    QCOMPARE(text(w, "maxStiffnessValue"), QStringLiteral("800 N/m"));
    QCOMPARE(text(w, "rateValue"), QStringLiteral("1000 Hz"));
    QCOMPARE(text(w, "pressureValue"), QStringLiteral("yes"));
    QCOMPARE(text(w, "buttonsValue"), QStringLiteral("4"));
    QCOMPARE(w.capabilities().maxStiffness_N_per_m, 800.0);
    QVERIFY(child<QDoubleSpinBox>(w, "zMaximumSpinBox")->isVisible()); // 3 DOF: z calibrated

    qVesselTouchDeviceCapabilities planar;
    planar.hasPressure = false;
    w.setCapabilities(planar);
    QCOMPARE(text(w, "pressureValue"), QStringLiteral("no"));
    QCOMPARE(text(w, "maxForceValue"), QStringLiteral("-")); // 0 = unknown
    QVERIFY(!child<QDoubleSpinBox>(w, "zMaximumSpinBox")->isVisible());
    w.clearCapabilities();
    QCOMPARE(text(w, "dofValue"), QStringLiteral("-"));
  }

  void calibrationIsReadOnlyAndShownOnlyForAGivenHidCalibration()
  {
    qVesselTouchDeviceWidget w;
    w.setAvailableDevices({ { "hid:1", "Wheel", "hid" }, { "pointer", "Mouse", "pointer" } });
    w.setCurrentDeviceId("hid:1");
    w.show();
    auto* group = child<QGroupBox>(w, "calibrationGroup");
    QVERIFY(!w.hasCalibration());
    QVERIFY(!group->isVisible()); // no calibration given: nothing to show

    qVesselTouchDeviceCalibration c;
    c.axes[0] = { 0.0, 1000.0, 0.0, 100.0 };
    w.setCalibration(c);
    QVERIFY(group->isVisible());
    auto* xMaximum = child<QDoubleSpinBox>(w, "xMaximumSpinBox");
    QCOMPARE(child<QDoubleSpinBox>(w, "xRawMaximumSpinBox")->value(), 1000.0);
    QCOMPARE(w.calibration().toMillimetres(0, 500.0), 50.0);
    QCOMPARE(w.calibration().toMillimetres(5, 500.0), 0.0); // no such axis
    // A display of what the device applies, not a setting that would do nothing.
    QVERIFY(xMaximum->isReadOnly());
    QTest::keyClick(xMaximum, Qt::Key_Up);
    QCOMPARE(w.calibration().axes[0].maximum_mm, 100.0);

    w.setCurrentDeviceId("pointer"); // the mouse has no raw axes to calibrate
    QVERIFY(!group->isVisible());
    w.setCurrentDeviceId("hid:1");
    QVERIFY(group->isVisible());
    w.clearCalibration();
    QVERIFY(!group->isVisible());
  }
};

QTEST_MAIN(qVesselTouchDeviceWidgetTest)
#include "qVesselTouchDeviceWidgetTest.moc"

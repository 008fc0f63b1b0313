// The force zones: k(P) itself, thresholds dragged with the mouse, spin boxes, the live dot.

// Route QTest's mouse events through the window system, as real ones are: with the widget-only
// path, QTest::mouseMove only moves the cursor and a drag never reaches the plot.
#define QTEST_QPA_MOUSE_HANDLING
#include "qVesselTouchForceZonesPlot.h"
#include "qVesselTouchForceZonesWidget.h"

#include <QDoubleSpinBox>
#include <QImage>
#include <QLabel>
#include <QSignalSpy>
#include <QTest>

#include <cmath>
#include <limits>

class qVesselTouchForceZonesWidgetTest : public QObject
{
  Q_OBJECT

private:
  static QDoubleSpinBox* spinBox(qVesselTouchForceZonesWidget& w, const char* name)
  {
    return w.findChild<QDoubleSpinBox*>(QString::fromLatin1(name));
  }
  // A shown widget with a known plot size, so pixel positions are meaningful.
  static void showSized(qVesselTouchForceZonesWidget& w)
  {
    w.resize(420, 320);
    w.show();
    QVERIFY(QTest::qWaitForWindowExposed(&w));
    QVERIFY(w.plot()->width() > 200);
  }
  // One pixel column of the plot is this much pressure.
  static double pressurePerPixel(const qVesselTouchForceZonesPlot* plot)
  {
    return 1.0 / (plot->pixelForPressure(1.0) - plot->pixelForPressure(0.0));
  }

private slots:
  void zoneGainHasThreeZones()
  {
    using W = qVesselTouchForceZonesWidget;
    QCOMPARE(W::zoneGain(0.0, 0.1, 0.5, 2.0), 0.0);
    QCOMPARE(W::zoneGain(0.09, 0.1, 0.5, 2.0), 0.0);
    QCOMPARE(W::zoneGain(0.1, 0.1, 0.5, 2.0), 0.0);
    QCOMPARE(W::zoneGain(0.3, 0.1, 0.5, 2.0), 1.0); // half-way up the proportional zone
    QCOMPARE(W::zoneGain(0.5, 0.1, 0.5, 2.0), 2.0);
    QCOMPARE(W::zoneGain(0.9, 0.1, 0.5, 2.0), 2.0);
    QCOMPARE(W::zoneGain(7.0, 0.1, 0.5, 2.0), 2.0);  // P clamped to 1
    QCOMPARE(W::zoneGain(-1.0, 0.1, 0.5, 2.0), 0.0); // P clamped to 0
    QCOMPARE(W::zoneGain(std::numeric_limits<double>::quiet_NaN(), 0.1, 0.5, 2.0), 0.0);
    // Degenerate thresholds: a step at zeroBelow, never a division by zero.
    QCOMPARE(W::zoneGain(0.4, 0.3, 0.3, 2.0), 2.0);
    QCOMPARE(W::zoneGain(0.2, 0.3, 0.3, 2.0), 0.0);
  }

  void defaultsShowInTheSpinBoxes()
  {
    qVesselTouchForceZonesWidget w;
    QCOMPARE(w.zeroBelow(), 0.05);
    QCOMPARE(w.saturateAbove(), 0.5);
    QCOMPARE(w.gain_N(), 1.0);
    QCOMPARE(spinBox(w, "zeroBelowSpinBox")->value(), 0.05);
    QCOMPARE(spinBox(w, "saturateAboveSpinBox")->value(), 0.5);
    QCOMPARE(spinBox(w, "gainSpinBox")->value(), 1.0);
    QCOMPARE(spinBox(w, "gainSpinBox")->suffix(), QStringLiteral(" N"));
    QCOMPARE(w.plot()->zeroBelow(), 0.05);
  }

  void draggingTheSaturationThresholdMovesIt()
  {
    qVesselTouchForceZonesWidget w;
    showSized(w);
    qVesselTouchForceZonesPlot* plot = w.plot();
    QSignalSpy thresholds(&w, &qVesselTouchForceZonesWidget::thresholdsChanged);
    QSignalSpy parameters(&w, &qVesselTouchForceZonesWidget::parametersChanged);
    const int y = plot->height() / 2;
    const QPoint start(plot->pixelForPressure(0.5), y);
    const QPoint end(plot->pixelForPressure(0.7), y);

    QTest::mousePress(plot, Qt::LeftButton, Qt::NoModifier, start);
    QCOMPARE(plot->draggedHandle(), qVesselTouchForceZonesPlot::SaturateAboveHandle);
    QTest::mouseMove(plot, QPoint(plot->pixelForPressure(0.6), y));
    QTest::mouseMove(plot, end);
    QTest::mouseRelease(plot, Qt::LeftButton, Qt::NoModifier, end);

    QVERIFY(thresholds.count() >= 1);
    const double tolerance = pressurePerPixel(plot) + 1e-3;
    QVERIFY2(std::abs(w.saturateAbove() - 0.7) <= tolerance,
      qPrintable(QString::number(w.saturateAbove())));
    QCOMPARE(thresholds.last().at(0).toDouble(), 0.05); // the other threshold did not move
    QCOMPARE(thresholds.last().at(1).toDouble(), w.saturateAbove());
    QCOMPARE(spinBox(w, "saturateAboveSpinBox")->value(), w.saturateAbove());
    QCOMPARE(plot->saturateAbove(), w.saturateAbove());
    QCOMPARE(parameters.count(), thresholds.count());
    QCOMPARE(plot->draggedHandle(), qVesselTouchForceZonesPlot::NoHandle);

    // After the release, moving the mouse drags nothing.
    const int before = thresholds.count();
    QTest::mouseMove(plot, QPoint(plot->pixelForPressure(0.9), y));
    QCOMPARE(thresholds.count(), before);
  }

  void draggingTheZeroThresholdStopsBeforeTheOther()
  {
    qVesselTouchForceZonesWidget w;
    showSized(w);
    qVesselTouchForceZonesPlot* plot = w.plot();
    QSignalSpy thresholds(&w, &qVesselTouchForceZonesWidget::thresholdsChanged);
    const int y = plot->height() / 3;
    QTest::mousePress(
      plot, Qt::LeftButton, Qt::NoModifier, QPoint(plot->pixelForPressure(0.05), y));
    QCOMPARE(plot->draggedHandle(), qVesselTouchForceZonesPlot::ZeroBelowHandle);
    QTest::mouseMove(plot, QPoint(plot->pixelForPressure(0.95), y));
    QTest::mouseRelease(
      plot, Qt::LeftButton, Qt::NoModifier, QPoint(plot->pixelForPressure(0.95), y));
    QVERIFY(thresholds.count() >= 1);
    QCOMPARE(w.saturateAbove(), 0.5);
    QVERIFY(std::abs(w.zeroBelow() - (0.5 - qVesselTouchForceZonesWidget::kMinimumGap)) < 1e-9);
    QCOMPARE(spinBox(w, "zeroBelowSpinBox")->value(), w.zeroBelow());
  }

  void pressAwayFromAHandleDragsNothing()
  {
    qVesselTouchForceZonesWidget w;
    showSized(w);
    qVesselTouchForceZonesPlot* plot = w.plot();
    QSignalSpy thresholds(&w, &qVesselTouchForceZonesWidget::thresholdsChanged);
    const int y = plot->height() / 2;
    QTest::mousePress(plot, Qt::LeftButton, Qt::NoModifier, QPoint(plot->pixelForPressure(0.8), y));
    QCOMPARE(plot->draggedHandle(), qVesselTouchForceZonesPlot::NoHandle);
    QTest::mouseMove(plot, QPoint(plot->pixelForPressure(0.9), y));
    QTest::mouseRelease(
      plot, Qt::LeftButton, Qt::NoModifier, QPoint(plot->pixelForPressure(0.9), y));
    QCOMPARE(thresholds.count(), 0);
    QCOMPARE(w.saturateAbove(), 0.5);
  }

  void spinBoxesEditThresholdsAndGain()
  {
    qVesselTouchForceZonesWidget w;
    QSignalSpy thresholds(&w, &qVesselTouchForceZonesWidget::thresholdsChanged);
    QSignalSpy gain(&w, &qVesselTouchForceZonesWidget::gainChanged);
    spinBox(w, "zeroBelowSpinBox")->setValue(0.1);
    QCOMPARE(thresholds.count(), 1);
    QCOMPARE(w.zeroBelow(), 0.1);
    QCOMPARE(w.plot()->zeroBelow(), 0.1);
    spinBox(w, "gainSpinBox")->setValue(2.5);
    QCOMPARE(gain.count(), 1);
    QCOMPARE(gain.at(0).at(0).toDouble(), 2.5);
    QCOMPARE(w.gain_N(), 2.5);
    QCOMPARE(w.plot()->gain_N(), 2.5);
    // Setting the same values again emits nothing (no feedback loop through the spin boxes).
    w.setThresholds(0.1, 0.5);
    w.setGain_N(2.5);
    QCOMPARE(thresholds.count(), 1);
    QCOMPARE(gain.count(), 1);
  }

  void crossingThresholdsPushTheOtherOne()
  {
    qVesselTouchForceZonesWidget w;
    spinBox(w, "zeroBelowSpinBox")->setValue(0.8);
    QCOMPARE(w.zeroBelow(), 0.8);
    QVERIFY(std::abs(w.saturateAbove() - 0.81) < 1e-9);
    QCOMPARE(spinBox(w, "saturateAboveSpinBox")->value(), w.saturateAbove());
  }

  void livePressureMovesTheDot()
  {
    qVesselTouchForceZonesWidget w;
    showSized(w);
    QLabel* live = w.findChild<QLabel*>(QStringLiteral("liveValue"));
    QCOMPARE(w.liveGain_N(), 0.0);
    QVERIFY(!w.plot()->hasLivePressure());

    w.setGain_N(2.0);
    w.setLivePressure(0.275); // half-way between 0.05 and 0.5
    QVERIFY(std::abs(w.liveGain_N() - 1.0) < 1e-12);
    QVERIFY2(live->text().contains(QStringLiteral("k(P) = 1.00 N")), qPrintable(live->text()));
    QVERIFY(w.plot()->hasLivePressure());

    // The dot is painted where (P, k(P)) is: a red pixel at its centre.
    qVesselTouchForceZonesPlot* plot = w.plot();
    const QImage image = plot->grab().toImage();
    const double dpr = image.devicePixelRatio();
    const QColor centre = image.pixelColor(
      int(plot->pixelForPressure(0.275) * dpr), int(plot->pixelForGain(1.0) * dpr));
    QVERIFY2(
      centre.red() > 180 && centre.green() < 80 && centre.blue() < 80, qPrintable(centre.name()));

    w.setLivePressure(0.9);
    QCOMPARE(w.liveGain_N(), 2.0);
    w.clearLivePressure();
    QVERIFY(!w.plot()->hasLivePressure());
    QCOMPARE(live->text(), QStringLiteral("no pressure input"));
  }
};

QTEST_MAIN(qVesselTouchForceZonesWidgetTest)
#include "qVesselTouchForceZonesWidgetTest.moc"

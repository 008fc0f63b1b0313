// The haptic zoom: logarithmic slider <-> spin box in sync, both ways, one signal per change.
#include "qVesselTouchHapticZoomWidget.h"

#include <QDoubleSpinBox>
#include <QSignalSpy>
#include <QSlider>
#include <QTest>
#include <QToolButton>

#include <cmath>
#include <limits>

class qVesselTouchHapticZoomWidgetTest : public QObject
{
  Q_OBJECT

private:
  static QSlider* slider(qVesselTouchHapticZoomWidget& w)
  {
    return w.findChild<QSlider*>(QStringLiteral("ratioSlider"));
  }
  static QDoubleSpinBox* spinBox(qVesselTouchHapticZoomWidget& w)
  {
    return w.findChild<QDoubleSpinBox*>(QStringLiteral("ratioSpinBox"));
  }

private slots:
  void mappingIsLogarithmicWithOneAtTheMiddle()
  {
    using W = qVesselTouchHapticZoomWidget;
    QCOMPARE(W::sliderPositionToRatio(0), 0.1);
    QCOMPARE(W::sliderPositionToRatio(W::kSliderSteps / 2), 1.0);
    QCOMPARE(W::sliderPositionToRatio(W::kSliderSteps), 10.0);
    // A quarter of the way is 10^-0.5: equal slider distances are equal ratios, not differences.
    QVERIFY(std::abs(W::sliderPositionToRatio(W::kSliderSteps / 4) - std::sqrt(0.1)) < 1e-12);
    QCOMPARE(W::ratioToSliderPosition(0.1), 0);
    QCOMPARE(W::ratioToSliderPosition(1.0), W::kSliderSteps / 2);
    QCOMPARE(W::ratioToSliderPosition(10.0), W::kSliderSteps);
    QCOMPARE(W::ratioToSliderPosition(0.01), 0);
    QCOMPARE(W::ratioToSliderPosition(100.0), W::kSliderSteps);
    for (int position = 0; position <= W::kSliderSteps; position += 37)
    {
      QCOMPARE(W::ratioToSliderPosition(W::sliderPositionToRatio(position)), position);
    }
  }

  void defaultIsOneAtTheSliderMiddle()
  {
    qVesselTouchHapticZoomWidget w;
    QCOMPARE(w.ratio(), 1.0);
    QCOMPARE(slider(w)->value(), qVesselTouchHapticZoomWidget::kSliderSteps / 2);
    QCOMPARE(spinBox(w)->value(), 1.0);
    QCOMPARE(slider(w)->minimum(), 0);
    QCOMPARE(slider(w)->maximum(), qVesselTouchHapticZoomWidget::kSliderSteps);
  }

  void sliderEndsDriveTheSpinBoxOnce()
  {
    qVesselTouchHapticZoomWidget w;
    QSignalSpy spy(&w, &qVesselTouchHapticZoomWidget::ratioChanged);
    slider(w)->setValue(slider(w)->maximum());
    QCOMPARE(spy.count(), 1);
    QCOMPARE(spy.at(0).at(0).toDouble(), 10.0);
    QCOMPARE(spinBox(w)->value(), 10.0);
    QCOMPARE(w.ratio(), 10.0);

    slider(w)->setValue(slider(w)->minimum());
    QCOMPARE(spy.count(), 2);
    QCOMPARE(spy.at(1).at(0).toDouble(), 0.1);
    QCOMPARE(spinBox(w)->value(), 0.1);
    QCOMPARE(slider(w)->value(), 0); // not bounced back by the spin box
  }

  void keyboardOnTheSliderMovesTheSpinBox()
  {
    qVesselTouchHapticZoomWidget w;
    w.show();
    QSignalSpy spy(&w, &qVesselTouchHapticZoomWidget::ratioChanged);
    slider(w)->setFocus();
    QTest::keyClick(slider(w), Qt::Key_End);
    QCOMPARE(w.ratio(), 10.0);
    QCOMPARE(spinBox(w)->value(), 10.0);
    QTest::keyClick(slider(w), Qt::Key_Home);
    QCOMPARE(w.ratio(), 0.1);
    QCOMPARE(spy.count(), 2);
  }

  void spinBoxDrivesTheSliderOnce()
  {
    qVesselTouchHapticZoomWidget w;
    QSignalSpy spy(&w, &qVesselTouchHapticZoomWidget::ratioChanged);
    spinBox(w)->setValue(0.1);
    QCOMPARE(spy.count(), 1);
    QCOMPARE(slider(w)->value(), 0);
    spinBox(w)->setValue(10.0);
    QCOMPARE(slider(w)->value(), qVesselTouchHapticZoomWidget::kSliderSteps);
    // sqrt(10) = 3.162 sits three quarters of the way on a log scale.
    spinBox(w)->setValue(3.162);
    QCOMPARE(slider(w)->value(), 3 * qVesselTouchHapticZoomWidget::kSliderSteps / 4);
    QCOMPARE(w.ratio(), 3.162); // the typed value is kept, not the slider's rounding of it
    QCOMPARE(spy.count(), 3);
  }

  void typedValueInTheSpinBoxIsApplied()
  {
    qVesselTouchHapticZoomWidget w;
    w.show();
    QSignalSpy spy(&w, &qVesselTouchHapticZoomWidget::ratioChanged);
    QDoubleSpinBox* box = spinBox(w);
    box->setFocus();
    box->selectAll();
    QTest::keyClicks(box, QStringLiteral("2.5"));
    QTest::keyClick(box, Qt::Key_Return);
    QCOMPARE(spy.count(), 1);
    QCOMPARE(w.ratio(), 2.5);
    QCOMPARE(slider(w)->value(), qVesselTouchHapticZoomWidget::ratioToSliderPosition(2.5));
  }

  void setRatioClampsAndIgnoresRepeats()
  {
    qVesselTouchHapticZoomWidget w;
    QSignalSpy spy(&w, &qVesselTouchHapticZoomWidget::ratioChanged);
    w.setRatio(1.0);
    QCOMPARE(spy.count(), 0);
    w.setRatio(50.0);
    QCOMPARE(w.ratio(), 10.0);
    w.setRatio(0.0);
    QCOMPARE(w.ratio(), 0.1);
    w.setRatio(std::numeric_limits<double>::quiet_NaN());
    QCOMPARE(w.ratio(), 0.1);
    QCOMPARE(spy.count(), 2);
    QCOMPARE(w.property("ratio").toDouble(), 0.1);
  }

  void resetButtonGoesBackToOne()
  {
    qVesselTouchHapticZoomWidget w;
    w.setRatio(4.0);
    QSignalSpy spy(&w, &qVesselTouchHapticZoomWidget::ratioChanged);
    QTest::mouseClick(w.findChild<QToolButton*>(QStringLiteral("resetButton")), Qt::LeftButton);
    QCOMPARE(spy.count(), 1);
    QCOMPARE(w.ratio(), 1.0);
    QCOMPARE(slider(w)->value(), qVesselTouchHapticZoomWidget::kSliderSteps / 2);
  }
};

QTEST_MAIN(qVesselTouchHapticZoomWidgetTest)
#include "qVesselTouchHapticZoomWidgetTest.moc"

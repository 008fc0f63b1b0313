// Loop statistics: the formatting of each figure and what the labels show.
#include "qVesselTouchLoopStatsWidget.h"

#include <QLabel>
#include <QTest>

class qVesselTouchLoopStatsWidgetTest : public QObject
{
  Q_OBJECT

private:
  static QString text(QWidget& w, const char* name)
  {
    QLabel* label = w.findChild<QLabel*>(QString::fromLatin1(name));
    if (!label)
    {
      qFatal("no label %s", name);
    }
    return label->text();
  }
  static qVesselTouchLoopStats running()
  {
    qVesselTouchLoopStats s;
    s.running = true;
    s.nominalRate_Hz = 1000.0;
    s.achievedRate_Hz = 998.74;
    s.periodErrorP50_us = 3.14;
    s.periodErrorP99_us = 9.8;
    s.periodErrorMax_us = 1250.0;
    s.ticks = 120000;
    s.overruns = 3;
    s.tickCostP50_us = 0.84;
    s.tickCostMax_us = 4.2;
    s.realtimeScheduling = true;
    s.tracing = true;
    s.pathId = 3;
    s.pointIndex = 127;
    return s;
  }

private slots:
  void formatsEachFigure()
  {
    using W = qVesselTouchLoopStatsWidget;
    QCOMPARE(W::formatRate(998.74, 1000.0), QStringLiteral("998.7 Hz of 1000 Hz"));
    QCOMPARE(W::formatDuration(3.14), QStringLiteral("3.1 µs"));
    QCOMPARE(W::formatDuration(999.94), QStringLiteral("999.9 µs"));
    QCOMPARE(W::formatDuration(1250.0), QStringLiteral("1250.0 µs"));
    QCOMPARE(W::formatPeriodError(3.14, 9.8, 1250.0),
      QStringLiteral("p50 3.1 µs · p99 9.8 µs · max 1250.0 µs"));
    QCOMPARE(W::formatOverruns(3, 120000), QStringLiteral("3 of 120000 ticks (0.0025 %)"));
    QCOMPARE(W::formatOverruns(0, 0), QStringLiteral("0 of 0 ticks"));
    QCOMPARE(W::formatState(false, true, 3, 127), QStringLiteral("stopped"));
    QCOMPARE(W::formatState(true, false, -1, -1), QStringLiteral("exploring"));
    QCOMPARE(W::formatState(true, true, 3, 127), QStringLiteral("tracing path 3, point 127"));
    QCOMPARE(W::formatState(true, true, -1, -1), QStringLiteral("tracing"));
  }

  void stoppedLoopShowsDashes()
  {
    qVesselTouchLoopStatsWidget w;
    QCOMPARE(text(w, "stateValue"), QStringLiteral("stopped"));
    QCOMPARE(text(w, "rateValue"), QStringLiteral("-"));
    QCOMPARE(text(w, "schedulingValue"), QStringLiteral("-"));
  }

  void runningLoopShowsItsFigures()
  {
    qVesselTouchLoopStatsWidget w;
    w.setStats(running());
    QCOMPARE(text(w, "stateValue"), QStringLiteral("tracing path 3, point 127"));
    QCOMPARE(text(w, "rateValue"), QStringLiteral("998.7 Hz of 1000 Hz"));
    QCOMPARE(
      text(w, "periodErrorValue"), QStringLiteral("p50 3.1 µs · p99 9.8 µs · max 1250.0 µs"));
    QCOMPARE(text(w, "overrunsValue"), QStringLiteral("3 of 120000 ticks (0.0025 %)"));
    QCOMPARE(text(w, "tickCostValue"), QStringLiteral("p50 0.8 µs · max 4.2 µs"));
    QCOMPARE(text(w, "schedulingValue"), QStringLiteral("SCHED_FIFO granted"));
    QCOMPARE(w.stats().ticks, quint64(120000));

    w.setInteractionState(false, -1, -1);
    QCOMPARE(text(w, "stateValue"), QStringLiteral("exploring"));
    QCOMPARE(text(w, "rateValue"), QStringLiteral("998.7 Hz of 1000 Hz")); // untouched
  }

  void deniedRealtimeIsSaidClearly()
  {
    qVesselTouchLoopStatsWidget w;
    w.show();
    qVesselTouchLoopStats s = running();
    s.realtimeScheduling = false;
    w.setStats(s);
    QCOMPARE(
      text(w, "schedulingValue"), QStringLiteral("SCHED_FIFO not granted (normal scheduling)"));
    // Shown in orange (a notice, not a fault); green when granted.
    QLabel* label = w.findChild<QLabel*>(QStringLiteral("schedulingValue"));
    QCOMPARE(label->palette().color(QPalette::WindowText), QColor(0xb3, 0x59, 0x00));
    s.realtimeScheduling = true;
    w.setStats(s);
    QCOMPARE(label->palette().color(QPalette::WindowText), QColor(0x1a, 0x7f, 0x1a));

    w.clear();
    QCOMPARE(text(w, "stateValue"), QStringLiteral("stopped"));
    QCOMPARE(text(w, "periodErrorValue"), QStringLiteral("-"));
  }
};

QTEST_MAIN(qVesselTouchLoopStatsWidgetTest)
#include "qVesselTouchLoopStatsWidgetTest.moc"

#include "qVesselTouchLoopStatsWidget.h"

#include "ui_qVesselTouchLoopStatsWidget.h"

#include <QLabel>

namespace
{
// Rewrites a label only when its text changes, so a 10 Hz refresh does not relayout.
void setText(QLabel* label, const QString& text)
{
  if (label->text() != text)
  {
    label->setText(text);
  }
}

void setStyle(QLabel* label, const QString& styleSheet)
{
  if (label->styleSheet() != styleSheet)
  {
    label->setStyleSheet(styleSheet);
  }
}
} // namespace

class qVesselTouchLoopStatsWidgetPrivate
{
public:
  Ui::qVesselTouchLoopStatsWidget Ui;
  qVesselTouchLoopStats Stats;

  void show();
};

void qVesselTouchLoopStatsWidgetPrivate::show()
{
  using W = qVesselTouchLoopStatsWidget;
  const qVesselTouchLoopStats& s = this->Stats;
  const QString none = QStringLiteral("-");
  setText(this->Ui.stateValue, W::formatState(s.running, s.tracing, s.pathId, s.pointIndex));
  setText(
    this->Ui.rateValue, s.running ? W::formatRate(s.achievedRate_Hz, s.nominalRate_Hz) : none);
  setText(this->Ui.periodErrorValue,
    s.running ? W::formatPeriodError(s.periodErrorP50_us, s.periodErrorP99_us, s.periodErrorMax_us)
              : none);
  setText(this->Ui.overrunsValue, s.running ? W::formatOverruns(s.overruns, s.ticks) : none);
  setText(this->Ui.tickCostValue,
    s.running ? QObject::tr("p50 %1 · max %2")
                  .arg(W::formatDuration(s.tickCostP50_us), W::formatDuration(s.tickCostMax_us))
              : none);
  if (!s.running)
  {
    setText(this->Ui.schedulingValue, none);
    setStyle(this->Ui.schedulingValue, QString());
  }
  else if (s.realtimeScheduling)
  {
    setText(this->Ui.schedulingValue, QObject::tr("SCHED_FIFO granted"));
    setStyle(this->Ui.schedulingValue, QStringLiteral("QLabel { color: #1a7f1a; }"));
  }
  else
  {
    // Not a fault, but the user should know why the period error may be larger.
    setText(this->Ui.schedulingValue, QObject::tr("SCHED_FIFO not granted (normal scheduling)"));
    setStyle(this->Ui.schedulingValue, QStringLiteral("QLabel { color: #b35900; }"));
  }
}

qVesselTouchLoopStatsWidget::qVesselTouchLoopStatsWidget(QWidget* parent)
  : QWidget(parent)
  , d_ptr(new qVesselTouchLoopStatsWidgetPrivate)
{
  Q_D(qVesselTouchLoopStatsWidget);
  d->Ui.setupUi(this);
  d->show();
}

qVesselTouchLoopStatsWidget::~qVesselTouchLoopStatsWidget() = default;

qVesselTouchLoopStats qVesselTouchLoopStatsWidget::stats() const
{
  Q_D(const qVesselTouchLoopStatsWidget);
  return d->Stats;
}

QString qVesselTouchLoopStatsWidget::formatRate(double achieved_Hz, double nominal_Hz)
{
  return tr("%1 Hz of %2 Hz")
    .arg(QString::number(achieved_Hz, 'f', 1), QString::number(nominal_Hz, 'f', 0));
}

QString qVesselTouchLoopStatsWidget::formatDuration(double value_us)
{
  // Always microseconds, like the labels: a 2 ms stall reads "2000.0 µs" beside "9.8 µs".
  return QString::number(value_us, 'f', 1) + QStringLiteral(" µs");
}

QString qVesselTouchLoopStatsWidget::formatPeriodError(double p50_us, double p99_us, double max_us)
{
  return tr("p50 %1 · p99 %2 · max %3")
    .arg(formatDuration(p50_us), formatDuration(p99_us), formatDuration(max_us));
}

QString qVesselTouchLoopStatsWidget::formatOverruns(quint64 overruns, quint64 ticks)
{
  if (ticks == 0)
  {
    return tr("%1 of 0 ticks").arg(overruns);
  }
  const double percent = 100.0 * double(overruns) / double(ticks);
  return tr("%1 of %2 ticks (%3 %)").arg(overruns).arg(ticks).arg(QString::number(percent, 'g', 2));
}

QString qVesselTouchLoopStatsWidget::formatState(bool running,
  bool tracing,
  int pathId,
  int pointIndex)
{
  if (!running)
  {
    return tr("stopped");
  }
  if (!tracing)
  {
    return tr("exploring");
  }
  if (pathId < 0)
  {
    return tr("tracing");
  }
  return tr("tracing path %1, point %2").arg(pathId).arg(pointIndex);
}

void qVesselTouchLoopStatsWidget::setStats(const qVesselTouchLoopStats& stats)
{
  Q_D(qVesselTouchLoopStatsWidget);
  d->Stats = stats;
  d->show();
}

void qVesselTouchLoopStatsWidget::setInteractionState(bool tracing, int pathId, int pointIndex)
{
  Q_D(qVesselTouchLoopStatsWidget);
  d->Stats.tracing = tracing;
  d->Stats.pathId = pathId;
  d->Stats.pointIndex = pointIndex;
  d->show();
}

void qVesselTouchLoopStatsWidget::clear()
{
  this->setStats(qVesselTouchLoopStats());
}

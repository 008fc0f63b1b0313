// Shows how the haptic loop is doing: achieved rate, period error p50/p99/max, overruns, tick
// cost, SCHED_FIFO granted or not, and the interaction state (exploring / tracing, path/point).
// Pure Qt: the module glue calls setStats() from a ~10 Hz GUI timer.
#ifndef qVesselTouchLoopStatsWidget_h
#define qVesselTouchLoopStatsWidget_h

#include "qVesselTouchLoopStats.h"

#include <QScopedPointer>
#include <QWidget>

class qVesselTouchLoopStatsWidgetPrivate;

class qVesselTouchLoopStatsWidget : public QWidget
{
  Q_OBJECT
public:
  explicit qVesselTouchLoopStatsWidget(QWidget* parent = nullptr);
  ~qVesselTouchLoopStatsWidget() override;

  /// The figures last shown. Default: a default-constructed struct (loop stopped).
  qVesselTouchLoopStats stats() const;

  /// "998.7 Hz of 1000 Hz" (one decimal achieved, nominal rounded).
  static QString formatRate(double achieved_Hz, double nominal_Hz);
  /// Microseconds with one decimal, whatever the size: "12.3 µs", "1250.0 µs".
  static QString formatDuration(double value_us);
  /// "p50 3.1 µs · p99 9.8 µs · max 1250.0 µs".
  static QString formatPeriodError(double p50_us, double p99_us, double max_us);
  /// "3 of 120000 ticks (0.003 %)"; "0 of 0 ticks" before the first tick.
  static QString formatOverruns(quint64 overruns, quint64 ticks);
  /// "stopped", "exploring", or "tracing path 3, point 127".
  static QString formatState(bool running, bool tracing, int pathId, int pointIndex);

public slots:
  /// Shows new figures. Cheap: labels are rewritten only when their text changes.
  void setStats(const qVesselTouchLoopStats& stats);
  /// Only the interaction state, for hosts that poll it apart from the statistics.
  void setInteractionState(bool tracing, int pathId, int pointIndex);
  /// Back to the stopped display.
  void clear();

private:
  QScopedPointer<qVesselTouchLoopStatsWidgetPrivate> d_ptr;
  Q_DECLARE_PRIVATE(qVesselTouchLoopStatsWidget);
  Q_DISABLE_COPY(qVesselTouchLoopStatsWidget);
};

#endif

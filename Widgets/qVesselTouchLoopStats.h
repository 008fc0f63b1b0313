// What the loop statistics widget shows, in one plain struct the module glue fills at ~10 Hz
// from vtouch::LoopStatisticsSummary and the published agent state.
#ifndef qVesselTouchLoopStats_h
#define qVesselTouchLoopStats_h

#include <QtGlobal>

struct qVesselTouchLoopStats
{
  /// The haptic loop is running. Default false (everything else is then shown as "-").
  bool running = false;
  /// Requested loop rate, Hz. Default 1000 Hz.
  double nominalRate_Hz = 1000.0;
  /// Ticks per second since the start, Hz. Default 0.
  double achievedRate_Hz = 0.0;
  /// Lateness of the tick start against its absolute deadline: median, 99th percentile and
  /// maximum, microseconds. Default 0.
  double periodErrorP50_us = 0.0;
  double periodErrorP99_us = 0.0;
  double periodErrorMax_us = 0.0;
  /// Ticks since the start. Default 0.
  quint64 ticks = 0;
  /// Ticks that ended after the next deadline. Default 0.
  quint64 overruns = 0;
  /// Time spent inside the tick: median and maximum, microseconds. Default 0.
  double tickCostP50_us = 0.0;
  double tickCostMax_us = 0.0;
  /// The loop thread got SCHED_FIFO (real-time) scheduling. Default false.
  bool realtimeScheduling = false;
  /// The agent traces a centerline (true) or the cursor explores freely (false). Default false.
  bool tracing = false;
  /// While tracing: the path id and the point index of the agent; -1 when unknown.
  int pathId = -1;
  int pointIndex = -1;
};

#endif

// Passes a run's progress on to a slow listener at most once per period of wall time, never
// going back (issue 16 item 6, h18q). The first rank of a distributed run reports the stitch's
// progress through one: ParaView sends the first rank's reports to the client at most once a
// second (vtkPVProgressHandler, the client's only view of a remote run and the only moment its
// panel takes the Cancel click), so a report every few milliseconds of check points would cost
// the rank for nothing, and one per period keeps a report ready for each of ParaView's sends.
#pragma once

#include <algorithm>
#include <functional>
#include <utility>

namespace vtouch
{

class ProgressThrottle
{
public:
  /// Project rule: 0.25 s, a quarter of ParaView's server interval (1 s): the next report is
  /// never more than a quarter of a second late for a send, and a rank spends at most four
  /// reports a second.
  static constexpr double kDefaultPeriod_s = 0.25;

  /// `sink` receives the fractions passed on (it may be empty: nothing is passed on).
  /// `period_s`: the least wall time between two reports, seconds.
  explicit ProgressThrottle(std::function<void(double)> sink, double period_s = kDefaultPeriod_s)
    : Sink(std::move(sink))
    , Period_s(period_s)
  {
  }

  /// Offers `fraction` at time `now_s` (seconds of a monotonic clock, vtouch::steadyNow_s): the
  /// highest fraction offered so far is passed on when this is the first offer or `period_s`
  /// passed since the last one passed on. Returns whether it was passed on.
  bool offer(double fraction, double now_s)
  {
    this->Highest = std::max(this->Highest, fraction);
    if (this->Reported && now_s - this->Last_s < this->Period_s)
    {
      return false;
    }
    this->Reported = true;
    this->Last_s = now_s;
    if (this->Sink)
    {
      this->Sink(this->Highest);
    }
    return true;
  }

  /// The highest fraction offered so far (0 before any).
  double highest() const { return this->Highest; }

private:
  std::function<void(double)> Sink;
  double Period_s;
  double Highest = 0.0;
  double Last_s = 0.0;
  bool Reported = false;
};

} // namespace vtouch

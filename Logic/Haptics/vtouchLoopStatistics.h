// Timing statistics of the haptic loop: fixed histograms, written by the loop, read by anyone.
#pragma once

#include <array>
#include <atomic>
#include <cstdint>

namespace vtouch
{

/// A consistent-enough summary (counters are read one by one while the loop runs).
struct LoopStatisticsSummary
{
  double nominalRate_Hz = 0.0;
  double achievedRate_Hz = 0.0; ///< ticks / elapsed time since start
  std::uint64_t ticks = 0;
  std::uint64_t overruns = 0;         ///< ticks that ended after the next deadline
  std::uint64_t skippedDeadlines = 0; ///< deadlines dropped after a stall (no catch-up burst)
  /// Deadlines that came due: ticks + skippedDeadlines. ticks / deadlines is the fraction served.
  std::uint64_t deadlines = 0;
  /// Wake-ups later than the watchdog (whole-host stalls), and the time they lost, s.
  std::uint64_t stalls = 0;
  double stallTime_s = 0.0;
  /// ticks / (elapsed - stallTime): the rate the loop held while the host ran it. Compare with
  /// achievedRate_Hz (all time) and skippedDeadlines to tell host stalls from a slow loop.
  double achievedRateOutsideStalls_Hz = 0.0;
  double periodErrorP50_us = 0.0; ///< lateness of the tick start against its absolute deadline
  double periodErrorP99_us = 0.0;
  double periodErrorP999_us = 0.0;
  double periodErrorMax_us = 0.0;
  double tickCostP50_us = 0.0; ///< time spent inside the tick function
  double tickCostP99_us = 0.0;
  double tickCostMax_us = 0.0;
};

/// Histograms with 1 us bins up to 4 ms then 100 us bins up to 100 ms (period error) and 50 ns bins
/// up to 200 us (tick cost). record() is wait-free (relaxed atomics), never allocates.
class LoopStatistics
{
public:
  void reset(double nominalRate_Hz);
  void recordPeriodError(double lateness_us) noexcept;
  void recordTickCost(double cost_us) noexcept;
  void recordOverrun(std::uint64_t skipped) noexcept;
  /// A wake-up `lateness_s` after its deadline, beyond the watchdog (a host stall).
  void recordStall(double lateness_s) noexcept;
  void setElapsed(double elapsed_s) noexcept;
  LoopStatisticsSummary summary() const;

private:
  static constexpr int kFineBins = 4000;  // 1 us
  static constexpr int kCoarseBins = 960; // 100 us, 4 ms .. 100 ms
  static constexpr int kErrorBins = kFineBins + kCoarseBins + 1;
  static constexpr int kCostBins = 4001; // 50 ns, last bin = overflow
  std::array<std::atomic<std::uint32_t>, kErrorBins> ErrorHist{};
  std::array<std::atomic<std::uint32_t>, kCostBins> CostHist{};
  std::atomic<std::uint64_t> Ticks{ 0 };
  std::atomic<std::uint64_t> Overruns{ 0 };
  std::atomic<std::uint64_t> Skipped{ 0 };
  std::atomic<std::uint64_t> Stalls{ 0 };
  std::atomic<double> StallTime_s{ 0.0 };
  std::atomic<double> MaxError_us{ 0.0 };
  std::atomic<double> MaxCost_us{ 0.0 };
  std::atomic<double> Elapsed_s{ 0.0 };
  std::atomic<double> Nominal_Hz{ 0.0 };
};

} // namespace vtouch

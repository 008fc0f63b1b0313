#include "vtouchLoopStatistics.h"

#include <algorithm>
#include <cmath>

namespace vtouch
{

namespace
{
template<std::size_t N>
double percentile(const std::array<std::atomic<std::uint32_t>, N>& hist,
  double q,
  double (*binValue)(int))
{
  std::uint64_t total = 0;
  for (const auto& c : hist)
  {
    total += c.load(std::memory_order_relaxed);
  }
  if (total == 0)
  {
    return 0.0;
  }
  const double rank = q * static_cast<double>(total);
  std::uint64_t acc = 0;
  for (std::size_t i = 0; i < N; ++i)
  {
    acc += hist[i].load(std::memory_order_relaxed);
    if (static_cast<double>(acc) >= rank)
    {
      return binValue(static_cast<int>(i));
    }
  }
  return binValue(static_cast<int>(N) - 1);
}

void atomicMax(std::atomic<double>& a, double v)
{
  double cur = a.load(std::memory_order_relaxed);
  while (v > cur && !a.compare_exchange_weak(cur, v, std::memory_order_relaxed))
  {
  }
}

double errorBinUpper_us(int i)
{
  return i < 4000 ? i + 1.0 : 4000.0 + (i - 4000 + 1) * 100.0;
}
double costBinUpper_us(int i)
{
  return (i + 1) * 0.05;
}
} // namespace

void LoopStatistics::reset(double nominalRate_Hz)
{
  for (auto& c : this->ErrorHist)
  {
    c.store(0, std::memory_order_relaxed);
  }
  for (auto& c : this->CostHist)
  {
    c.store(0, std::memory_order_relaxed);
  }
  this->Ticks.store(0);
  this->Overruns.store(0);
  this->Skipped.store(0);
  this->Stalls.store(0);
  this->StallTime_s.store(0.0);
  this->MaxError_us.store(0.0);
  this->MaxCost_us.store(0.0);
  this->Elapsed_s.store(0.0);
  this->Nominal_Hz.store(nominalRate_Hz);
}

void LoopStatistics::recordPeriodError(double us) noexcept
{
  us = std::max(0.0, us);
  int bin = 0;
  if (us < kFineBins)
  {
    bin = static_cast<int>(us);
  }
  else
  {
    bin = std::min(kErrorBins - 1, kFineBins + static_cast<int>((us - kFineBins) / 100.0));
  }
  this->ErrorHist[bin].fetch_add(1, std::memory_order_relaxed);
  this->Ticks.fetch_add(1, std::memory_order_relaxed);
  atomicMax(this->MaxError_us, us);
}

void LoopStatistics::recordTickCost(double us) noexcept
{
  us = std::max(0.0, us);
  const int bin = std::min(kCostBins - 1, static_cast<int>(us / 0.05));
  this->CostHist[bin].fetch_add(1, std::memory_order_relaxed);
  atomicMax(this->MaxCost_us, us);
}

void LoopStatistics::recordOverrun(std::uint64_t skipped) noexcept
{
  this->Overruns.fetch_add(1, std::memory_order_relaxed);
  this->Skipped.fetch_add(skipped, std::memory_order_relaxed);
}

void LoopStatistics::recordStall(double lateness_s) noexcept
{
  this->Stalls.fetch_add(1, std::memory_order_relaxed);
  // Single writer (the loop thread): load + store is enough.
  this->StallTime_s.store(
    this->StallTime_s.load(std::memory_order_relaxed) + std::max(0.0, lateness_s),
    std::memory_order_relaxed);
}

void LoopStatistics::setElapsed(double s) noexcept
{
  this->Elapsed_s.store(s, std::memory_order_relaxed);
}

LoopStatisticsSummary LoopStatistics::summary() const
{
  LoopStatisticsSummary s;
  s.nominalRate_Hz = this->Nominal_Hz.load();
  s.ticks = this->Ticks.load();
  s.overruns = this->Overruns.load();
  s.skippedDeadlines = this->Skipped.load();
  const double elapsed = this->Elapsed_s.load();
  s.achievedRate_Hz = elapsed > 0.0 ? static_cast<double>(s.ticks) / elapsed : 0.0;
  s.deadlines = s.ticks + s.skippedDeadlines;
  s.stalls = this->Stalls.load();
  s.stallTime_s = this->StallTime_s.load();
  const double running = elapsed - s.stallTime_s;
  s.achievedRateOutsideStalls_Hz = running > 0.0 ? static_cast<double>(s.ticks) / running : 0.0;
  s.periodErrorP50_us = percentile(this->ErrorHist, 0.5, &errorBinUpper_us);
  s.periodErrorP99_us = percentile(this->ErrorHist, 0.99, &errorBinUpper_us);
  s.periodErrorP999_us = percentile(this->ErrorHist, 0.999, &errorBinUpper_us);
  s.periodErrorMax_us = this->MaxError_us.load();
  s.tickCostP50_us = percentile(this->CostHist, 0.5, &costBinUpper_us);
  s.tickCostP99_us = percentile(this->CostHist, 0.99, &costBinUpper_us);
  s.tickCostMax_us = this->MaxCost_us.load();
  return s;
}

} // namespace vtouch

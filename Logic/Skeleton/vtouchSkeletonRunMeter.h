// Private to Logic/Skeleton: progress, cancellation and stage timing of one voxel-coding run.
#pragma once

#include "vtouchVoxelCoding.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace vtouch
{
namespace skeleton
{

/// Counts the work of a run (about six units per vessel voxel) and calls the caller's progress
/// callback at check points, every 2^16 units; throws VoxelCodingAborted there when the callback
/// asks to stop. Every stage that loops over voxels ticks it. Used from the caller's thread only,
/// except `stopRequested`, which the BS code's thread polls.
class RunMeter
{
public:
  /// `progress` may be empty (no reports, no cancellation); it must outlive the meter.
  explicit RunMeter(const std::function<bool(double)>& progress)
    : Progress(progress)
  {
  }

  /// Work units expected for the whole run (the denominator of the reported fraction), >= 1.
  void setTotalWork(std::uint64_t units) { this->TotalWork = std::max<std::uint64_t>(1, units); }

  void tick(std::uint64_t amount = 1)
  {
    this->Work += amount;
    if ((this->Work & 0xFFFF) < amount)
    {
      this->checkpoint();
    }
  }

  /// Reports the progress so far; throws VoxelCodingAborted when the caller asks to stop. Loops
  /// whose iterations are not counted as work (stale queue entries) call it every 2^16
  /// iterations.
  void checkpoint()
  {
    if (this->Progress &&
        !this->Progress(
          std::min(1.0, static_cast<double>(this->Work) / static_cast<double>(this->TotalWork))))
    {
      this->stopRequested = true; // the BS thread stops too, before the unwinding joins it
      throw VoxelCodingAborted();
    }
  }

  /// The last report (1.0) at the end of the run; throws VoxelCodingAborted when asked to stop.
  void finish() const
  {
    if (this->Progress && !this->Progress(1.0))
    {
      throw VoxelCodingAborted();
    }
  }

  /// Set when the run stops (cancelled, or an error unwinding it): a stage on another thread
  /// checks it and gives up.
  std::atomic<bool> stopRequested{ false };

  /// Wall time per stage (name, seconds), in order of first appearance: RawSkeleton::stageSeconds.
  std::vector<std::pair<std::string, double>> stageSeconds;

  /// Adds `seconds` to the entry `name`, creating it at the end.
  void accumulate(const char* name, double seconds)
  {
    for (auto& e : this->stageSeconds)
    {
      if (e.first == name)
      {
        e.second += seconds;
        return;
      }
    }
    this->stageSeconds.emplace_back(name, seconds);
  }

private:
  const std::function<bool(double)>& Progress;
  std::uint64_t Work = 0;
  std::uint64_t TotalWork = 1;
};

/// Adds the wall time of its scope to the meter's entry `name` (nested scopes count in both).
struct StageTimer
{
  RunMeter& meter;
  const char* name;
  std::chrono::steady_clock::time_point t0 = std::chrono::steady_clock::now();
  ~StageTimer()
  {
    meter.accumulate(
      name, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
};

} // namespace skeleton
} // namespace vtouch

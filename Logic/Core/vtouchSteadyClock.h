// The one monotonic clock every layer reads (devices' timestamps, the watchdog, replay and
// simulated real-time clocks): seconds of std::chrono::steady_clock as a double. Lock-free,
// allocation-free, safe in the haptic tick.
#pragma once

#include <chrono>

namespace vtouch
{

/// Seconds since the steady clock's epoch (arbitrary origin; only differences mean anything).
inline double steadyNow_s() noexcept
{
  using namespace std::chrono;
  return duration<double>(steady_clock::now().time_since_epoch()).count();
}

} // namespace vtouch

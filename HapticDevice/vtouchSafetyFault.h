// Why the device layer is holding the force at zero.
#pragma once

#include <cstdint>

namespace vtouch
{

/// Safety fault codes, readable without locks (stored in a std::atomic by SafeHapticDevice).
enum class SafetyFault : std::uint8_t
{
  None = 0,
  NonFiniteForce, ///< a NaN/Inf force was commanded (zero force sent instead)
  Watchdog,       ///< no write() arrived within the watchdog timeout (zero force sent)
  DeviceError,    ///< a device read/write failed (zero force attempted)
  Disconnected    ///< the device went away; it is reopened when it comes back
};

inline const char* toString(SafetyFault fault)
{
  switch (fault)
  {
    case SafetyFault::None:
      return "none";
    case SafetyFault::NonFiniteForce:
      return "non-finite force commanded";
    case SafetyFault::Watchdog:
      return "watchdog: no force update in time";
    case SafetyFault::DeviceError:
      return "device error";
    case SafetyFault::Disconnected:
      return "device disconnected";
  }
  return "unknown fault";
}

} // namespace vtouch

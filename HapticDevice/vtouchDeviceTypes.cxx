#include "vtouchDeviceTypes.h"

namespace vtouch
{

const char* toString(DeviceStatus status)
{
  switch (status)
  {
    case DeviceStatus::Ok:
      return "ok";
    case DeviceStatus::NotOpen:
      return "device not open";
    case DeviceStatus::Disconnected:
      return "device disconnected";
    case DeviceStatus::Unsupported:
      return "not supported by this device";
    case DeviceStatus::InvalidArgument:
      return "invalid argument";
    case DeviceStatus::IoError:
      return "I/O error";
    case DeviceStatus::Timeout:
      return "timeout";
    case DeviceStatus::Fault:
      return "safety fault";
  }
  return "unknown status";
}

} // namespace vtouch

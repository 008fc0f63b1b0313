#include "vtouchHidPidDevice.h"
#include "vtouchHidapiTransport.h"

#include <gtest/gtest.h>

#include <memory>
#include <string>

namespace
{
// The real transport, without hardware: whatever the machine has, nothing may crash or hang, and
// a missing device must come back as a clear error.

TEST(HidapiTransport, EnumeratesWithoutCrashingWhenNoDeviceIsPresent)
{
  vtouch::HidapiTransport transport;
  const auto devices = transport.enumerate();
  for (const auto& d : devices)
  {
    EXPECT_FALSE(d.path.empty());
  }
}

TEST(HidapiTransport, ReportsClearErrorWhenPathDoesNotExist)
{
  vtouch::HidapiTransport transport;
  EXPECT_FALSE(transport.open("/dev/hidraw-vesseltouch-missing"));
  EXPECT_NE(std::string(transport.lastError()).find("cannot open"), std::string::npos);
  EXPECT_FALSE(transport.isOpen());
  std::uint8_t buffer[8] = {};
  EXPECT_LT(transport.readInput(buffer, sizeof(buffer)), 0);
  EXPECT_LT(transport.writeOutput(buffer, sizeof(buffer)), 0);
}

TEST(HidPidDevice, FailsOpenWithReasonWhenHidPathDoesNotExist)
{
  vtouch::HidPidDevice device(
    std::make_shared<vtouch::HidapiTransport>(), "/dev/hidraw-vesseltouch-missing");
  EXPECT_NE(device.open(), vtouch::DeviceStatus::Ok);
  EXPECT_NE(std::string(device.lastError()).find("cannot open"), std::string::npos);
  EXPECT_FALSE(device.isOpen());
}

} // namespace

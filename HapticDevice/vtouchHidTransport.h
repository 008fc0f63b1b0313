// The few HID calls the drivers need, behind an interface: hidapi in production, a fake in tests.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace vtouch
{

/// One HID interface found by enumerate().
struct HidDeviceInfo
{
  std::string path; ///< opaque path for open() (e.g. /dev/hidraw3)
  std::uint16_t vendorId = 0;
  std::uint16_t productId = 0;
  std::string manufacturer;
  std::string product;
  std::string serial;
  std::uint16_t usagePage = 0; ///< top-level usage page (0 when the back end does not tell)
  std::uint16_t usage = 0;
  int interfaceNumber = -1;
};

/// A HID connection. One device at a time. Reports go in and out as hidapi has them: the first
/// byte is the report ID when the device numbers its reports, and there is no ID byte otherwise
/// (writes to such devices still start with a 0 byte, which is not sent).
///
/// Threading: enumerate/open/close/reportDescriptor from a control thread; readInput/writeOutput
/// from the haptic thread; feature reports from the control thread (open/close).
class HidTransport
{
public:
  virtual ~HidTransport() = default;

  /// Every HID interface present (may be empty; never throws).
  virtual std::vector<HidDeviceInfo> enumerate() = 0;
  /// Opens a device; false with lastError() on failure (missing, or no permission).
  virtual bool open(const std::string& path) = 0;
  virtual void close() = 0;
  virtual bool isOpen() const = 0;
  /// Copies the report descriptor; returns its length, or -1.
  virtual int reportDescriptor(std::uint8_t* buffer, std::size_t size) = 0;
  /// Reads one pending input report without blocking: its length, 0 when none, -1 on error.
  virtual int readInput(std::uint8_t* buffer, std::size_t size) = 0;
  /// Writes one output report (first byte = report ID or 0): bytes written, or -1.
  virtual int writeOutput(const std::uint8_t* report, std::size_t size) = 0;
  /// Sends a feature report (first byte = report ID or 0): bytes written, or -1.
  virtual int sendFeature(const std::uint8_t* report, std::size_t size) = 0;
  /// Gets a feature report; report[0] holds the ID on entry. Bytes read (ID included), or -1.
  virtual int getFeature(std::uint8_t* report, std::size_t size) = 0;
  /// True when the last failure means the device is gone (unplugged).
  virtual bool disconnected() const = 0;
  /// Why the last call failed; a string owned by the transport, valid until the next call.
  virtual const char* lastError() const = 0;
};

} // namespace vtouch

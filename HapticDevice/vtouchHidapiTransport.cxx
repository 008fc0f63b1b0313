#include "vtouchHidapiTransport.h"

#include <hidapi.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <mutex>

namespace vtouch
{

namespace
{
std::string narrow(const wchar_t* text)
{
  std::string out;
  for (; text && *text; ++text)
  {
    out.push_back(*text < 0x80 ? static_cast<char>(*text) : '?');
  }
  return out;
}

bool initialise()
{
  static std::once_flag once;
  static bool ok = false;
  std::call_once(once, []() { ok = hid_init() == 0; });
  return ok;
}

bool isGoneErrno(int e)
{
  return e == ENODEV || e == ENXIO || e == ENOENT || e == EPIPE || e == ESHUTDOWN;
}
} // namespace

HidapiTransport::HidapiTransport()
{
  initialise();
}

HidapiTransport::~HidapiTransport()
{
  this->close();
}

void HidapiTransport::setError(const char* what, int errnoValue)
{
  this->Gone = isGoneErrno(errnoValue);
  std::snprintf(this->Error.data(),
    this->Error.size(),
    "%s: %s",
    what,
    errnoValue ? std::strerror(errnoValue) : "failed");
}

std::vector<HidDeviceInfo> HidapiTransport::enumerate()
{
  std::vector<HidDeviceInfo> devices;
  if (!initialise())
  {
    std::snprintf(this->Error.data(), this->Error.size(), "%s", "hid_init failed");
    return devices;
  }
  hid_device_info* list = hid_enumerate(0, 0);
  for (hid_device_info* d = list; d; d = d->next)
  {
    HidDeviceInfo info;
    info.path = d->path ? d->path : "";
    info.vendorId = d->vendor_id;
    info.productId = d->product_id;
    info.manufacturer = narrow(d->manufacturer_string);
    info.product = narrow(d->product_string);
    info.serial = narrow(d->serial_number);
    info.usagePage = d->usage_page;
    info.usage = d->usage;
    info.interfaceNumber = d->interface_number;
    devices.push_back(info);
  }
  hid_free_enumeration(list);
  return devices;
}

bool HidapiTransport::open(const std::string& path)
{
  this->close();
  this->Gone = false;
  errno = 0;
  this->Device = hid_open_path(path.c_str());
  if (!this->Device)
  {
    const int e = errno;
    std::snprintf(this->Error.data(),
      this->Error.size(),
      "cannot open %s: %s%s",
      path.c_str(),
      e ? std::strerror(e) : "failed",
      e == EACCES || e == EPERM ? " (add a udev rule giving your user access to hidraw)" : "");
    this->Gone = isGoneErrno(e);
    return false;
  }
  this->Path = path;
  return true;
}

void HidapiTransport::close()
{
  if (this->Device)
  {
    hid_close(this->Device);
    this->Device = nullptr;
  }
}

int HidapiTransport::reportDescriptor(std::uint8_t* buffer, std::size_t size)
{
#if defined(HID_API_VERSION) && HID_API_VERSION >= HID_API_MAKE_VERSION(0, 14, 0)
  if (this->Device)
  {
    const int n = hid_get_report_descriptor(this->Device, buffer, size);
    if (n >= 0)
    {
      return n;
    }
  }
#endif
  // hidapi < 0.14 has no call for it; the hidraw node's sysfs entry has the same bytes.
  const std::string prefix = "/dev/";
  if (this->Path.compare(0, prefix.size(), prefix) != 0)
  {
    std::snprintf(this->Error.data(),
      this->Error.size(),
      "%s",
      "report descriptor unavailable (hidapi < 0.14 and not a /dev/hidraw path)");
    return -1;
  }
  const std::string node = this->Path.substr(prefix.size());
  std::ifstream in("/sys/class/hidraw/" + node + "/device/report_descriptor", std::ios::binary);
  if (!in)
  {
    this->setError("cannot read the report descriptor from sysfs", errno);
    return -1;
  }
  in.read(reinterpret_cast<char*>(buffer), static_cast<std::streamsize>(size));
  return static_cast<int>(in.gcount());
}

int HidapiTransport::readInput(std::uint8_t* buffer, std::size_t size)
{
  if (!this->Device)
  {
    return -1;
  }
  errno = 0;
  const int n = hid_read_timeout(this->Device, buffer, size, 0);
  if (n < 0)
  {
    this->setError("hid_read failed", errno ? errno : ENODEV);
  }
  return n;
}

int HidapiTransport::writeOutput(const std::uint8_t* report, std::size_t size)
{
  if (!this->Device)
  {
    return -1;
  }
  errno = 0;
  const int n = hid_write(this->Device, report, size);
  if (n < 0)
  {
    this->setError("hid_write failed", errno);
  }
  return n;
}

int HidapiTransport::sendFeature(const std::uint8_t* report, std::size_t size)
{
  if (!this->Device)
  {
    return -1;
  }
  errno = 0;
  const int n = hid_send_feature_report(this->Device, report, size);
  if (n < 0)
  {
    this->setError("hid_send_feature_report failed", errno);
  }
  return n;
}

int HidapiTransport::getFeature(std::uint8_t* report, std::size_t size)
{
  if (!this->Device)
  {
    return -1;
  }
  errno = 0;
  const int n = hid_get_feature_report(this->Device, report, size);
  if (n < 0)
  {
    this->setError("hid_get_feature_report failed", errno);
  }
  return n;
}

} // namespace vtouch

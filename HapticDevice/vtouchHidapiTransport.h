// HidTransport over hidapi (hidraw back end on Linux).
#pragma once

#include "vtouchHidTransport.h"

#include <array>

struct hid_device_;

namespace vtouch
{

/// The real transport. hidapi is initialised once per process (hid_init is reference-free, so it
/// is never torn down while another instance may still use it).
class HidapiTransport : public HidTransport
{
public:
  HidapiTransport();
  ~HidapiTransport() override;

  std::vector<HidDeviceInfo> enumerate() override;
  bool open(const std::string& path) override;
  void close() override;
  bool isOpen() const override { return this->Device != nullptr; }
  int reportDescriptor(std::uint8_t* buffer, std::size_t size) override;
  int readInput(std::uint8_t* buffer, std::size_t size) override;
  int writeOutput(const std::uint8_t* report, std::size_t size) override;
  int sendFeature(const std::uint8_t* report, std::size_t size) override;
  int getFeature(std::uint8_t* report, std::size_t size) override;
  bool disconnected() const override { return this->Gone; }
  const char* lastError() const override { return this->Error.data(); }

private:
  void setError(const char* what, int errnoValue);

  hid_device_* Device = nullptr;
  std::string Path;
  bool Gone = false;
  std::array<char, 256> Error{};
};

} // namespace vtouch

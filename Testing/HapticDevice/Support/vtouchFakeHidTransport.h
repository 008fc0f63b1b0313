// A scripted HidTransport: replays a report descriptor and input reports, records every report
// the driver sends, and can be unplugged or made to fail. For the tests and fuzzers only:
// it lives under Testing/ and never ships in the plugin (issue 18, item 4).
#pragma once

#include "vtouchHidTransport.h"

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <mutex>
#include <string>
#include <vector>

namespace vtouch
{

/// One simulated HID device.
struct FakeHidDevice
{
  HidDeviceInfo info;
  std::vector<std::uint8_t> descriptor;
  /// Answers getFeature(): `report` holds the requested ID in [0] and has the requested size;
  /// fill it and return the length, or -1 to fail. Empty: every getFeature fails.
  std::function<int(std::uint8_t* report, std::size_t size)> featureResponder;
};

/// What the driver sent, in order.
struct FakeHidRecord
{
  enum class Kind
  {
    Output,
    SetFeature,
    GetFeature
  };
  Kind kind = Kind::Output;
  std::vector<std::uint8_t> bytes; ///< as passed to the transport (ID byte first)
};

/// Thread-safe (one mutex): the haptic thread may write while a test thread inspects.
class FakeHidTransport : public HidTransport
{
public:
  FakeHidTransport() = default;
  explicit FakeHidTransport(std::vector<FakeHidDevice> devices);

  /// Adds a device (it appears in enumerate()).
  void addDevice(const FakeHidDevice& device);
  /// Queues an input report for readInput().
  void pushInput(const std::vector<std::uint8_t>& report);
  /// Unplugs (every call fails as a disconnection, open() too) or re-plugs the open device.
  void setUnplugged(bool unplugged);
  /// Makes writes fail (I/O error, not a disconnection) after `count` more successful writes;
  /// negative = never.
  void failWritesAfter(int count);
  /// Makes writes block until releaseStall() (a stuck USB endpoint).
  void stallWrites(bool stall);
  void releaseStall() { this->stallWrites(false); }
  /// Number of writes currently blocked in a stall.
  int stalledWriters() const { return this->Stalled.load(); }

  /// Every report sent, oldest first.
  std::vector<FakeHidRecord> records() const;
  /// Output reports only.
  std::vector<std::vector<std::uint8_t>> outputs() const;
  void clearRecords();
  int openCount() const;

  std::vector<HidDeviceInfo> enumerate() override;
  bool open(const std::string& path) override;
  void close() override;
  bool isOpen() const override;
  int reportDescriptor(std::uint8_t* buffer, std::size_t size) override;
  int readInput(std::uint8_t* buffer, std::size_t size) override;
  int writeOutput(const std::uint8_t* report, std::size_t size) override;
  int sendFeature(const std::uint8_t* report, std::size_t size) override;
  int getFeature(std::uint8_t* report, std::size_t size) override;
  bool disconnected() const override;
  const char* lastError() const override;

private:
  int failIfUnusable();

  mutable std::mutex Mutex;
  std::condition_variable StallReleased;
  std::vector<FakeHidDevice> Devices;
  int Current = -1;
  bool Unplugged = false;
  bool Gone = false;
  bool Stall = false;
  std::atomic<int> Stalled{ 0 };
  int WritesBeforeFailure = -1;
  int Opens = 0;
  std::deque<std::vector<std::uint8_t>> Inputs;
  std::vector<FakeHidRecord> Records;
  const char* Error = "";
};

} // namespace vtouch

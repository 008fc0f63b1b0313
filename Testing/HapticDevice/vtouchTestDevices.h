// Test doubles shared by the HapticDevice tests.
#pragma once

#include "vtouchHapticDevice.h"

#include <atomic>
#include <cstdio>
#include <mutex>
#include <vector>

namespace vtouch
{
namespace test
{

/// A device that records every force written and fails or disappears on command.
/// Its counters are atomics so that a test thread can watch them while another thread writes.
class RecordingDevice : public HapticDevice
{
public:
  RecordingDevice()
  {
    std::snprintf(this->Caps.name, sizeof(this->Caps.name), "%s", "recording device");
    this->Caps.maxContinuousForce_N = 2.0;
    this->Caps.maxUpdateRate_Hz = 1000.0;
  }

  DeviceStatus open() override
  {
    if (this->Unplugged.load())
    {
      return DeviceStatus::Disconnected;
    }
    this->Opens.fetch_add(1);
    this->OpenFlag = true;
    return DeviceStatus::Ok;
  }
  void close() override { this->OpenFlag = false; }
  bool isOpen() const override { return this->OpenFlag; }
  const DeviceCapabilities& capabilities() const override { return this->Caps; }
  DeviceStatus read(DeviceState& state) override
  {
    if (this->Unplugged.load())
    {
      return DeviceStatus::Disconnected;
    }
    state.timestamp_s += 0.001;
    return DeviceStatus::Ok;
  }
  DeviceStatus write(const Vec3& force) override
  {
    this->Writes.fetch_add(1);
    if (this->Unplugged.load())
    {
      return DeviceStatus::Disconnected;
    }
    if (this->FailWrites.load())
    {
      return DeviceStatus::IoError;
    }
    this->LastX.store(force.x);
    this->LastY.store(force.y);
    if (this->KeepHistory)
    {
      std::lock_guard<std::mutex> lock(this->HistoryMutex);
      this->History.push_back(force);
    }
    return DeviceStatus::Ok;
  }
  const char* lastError() const override { return "recording device error"; }

  Vec3 last() const { return Vec3{ this->LastX.load(), this->LastY.load(), 0.0 }; }

  DeviceCapabilities Caps;
  bool OpenFlag = false;
  bool KeepHistory = true;
  std::atomic<bool> Unplugged{ false };
  std::atomic<bool> FailWrites{ false };
  std::atomic<int> Opens{ 0 };
  std::atomic<long> Writes{ 0 };
  std::atomic<double> LastX{ 0.0 };
  std::atomic<double> LastY{ 0.0 };
  std::mutex HistoryMutex;
  std::vector<Vec3> History;
};

} // namespace test
} // namespace vtouch

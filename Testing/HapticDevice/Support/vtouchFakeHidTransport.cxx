#include "vtouchFakeHidTransport.h"

#include <algorithm>
#include <cstring>

namespace vtouch
{

FakeHidTransport::FakeHidTransport(std::vector<FakeHidDevice> devices)
  : Devices(std::move(devices))
{
}

void FakeHidTransport::addDevice(const FakeHidDevice& device)
{
  std::lock_guard<std::mutex> lock(this->Mutex);
  this->Devices.push_back(device);
}

void FakeHidTransport::pushInput(const std::vector<std::uint8_t>& report)
{
  std::lock_guard<std::mutex> lock(this->Mutex);
  this->Inputs.push_back(report);
}

void FakeHidTransport::setUnplugged(bool unplugged)
{
  std::lock_guard<std::mutex> lock(this->Mutex);
  this->Unplugged = unplugged;
}

void FakeHidTransport::failWritesAfter(int count)
{
  std::lock_guard<std::mutex> lock(this->Mutex);
  this->WritesBeforeFailure = count;
}

void FakeHidTransport::stallWrites(bool stall)
{
  {
    std::lock_guard<std::mutex> lock(this->Mutex);
    this->Stall = stall;
  }
  this->StallReleased.notify_all();
}

std::vector<FakeHidRecord> FakeHidTransport::records() const
{
  std::lock_guard<std::mutex> lock(this->Mutex);
  return this->Records;
}

std::vector<std::vector<std::uint8_t>> FakeHidTransport::outputs() const
{
  std::lock_guard<std::mutex> lock(this->Mutex);
  std::vector<std::vector<std::uint8_t>> out;
  for (const FakeHidRecord& r : this->Records)
  {
    if (r.kind == FakeHidRecord::Kind::Output)
    {
      out.push_back(r.bytes);
    }
  }
  return out;
}

void FakeHidTransport::clearRecords()
{
  std::lock_guard<std::mutex> lock(this->Mutex);
  this->Records.clear();
}

int FakeHidTransport::openCount() const
{
  std::lock_guard<std::mutex> lock(this->Mutex);
  return this->Opens;
}

std::vector<HidDeviceInfo> FakeHidTransport::enumerate()
{
  std::lock_guard<std::mutex> lock(this->Mutex);
  std::vector<HidDeviceInfo> infos;
  for (const FakeHidDevice& d : this->Devices)
  {
    infos.push_back(d.info);
  }
  return infos;
}

bool FakeHidTransport::open(const std::string& path)
{
  std::lock_guard<std::mutex> lock(this->Mutex);
  this->Current = -1;
  if (this->Unplugged)
  {
    this->Gone = true;
    this->Error = "fake: no such device (unplugged)";
    return false;
  }
  for (std::size_t i = 0; i < this->Devices.size(); ++i)
  {
    if (this->Devices[i].info.path == path)
    {
      this->Current = static_cast<int>(i);
      this->Gone = false;
      ++this->Opens;
      return true;
    }
  }
  this->Error = "fake: no device at that path";
  return false;
}

void FakeHidTransport::close()
{
  std::lock_guard<std::mutex> lock(this->Mutex);
  this->Current = -1;
}

bool FakeHidTransport::isOpen() const
{
  std::lock_guard<std::mutex> lock(this->Mutex);
  return this->Current >= 0;
}

int FakeHidTransport::failIfUnusable()
{
  if (this->Current < 0)
  {
    this->Error = "fake: not open";
    return -1;
  }
  if (this->Unplugged)
  {
    this->Gone = true;
    this->Error = "fake: device unplugged";
    return -1;
  }
  return 0;
}

int FakeHidTransport::reportDescriptor(std::uint8_t* buffer, std::size_t size)
{
  std::lock_guard<std::mutex> lock(this->Mutex);
  if (this->failIfUnusable() < 0)
  {
    return -1;
  }
  const auto& d = this->Devices[static_cast<std::size_t>(this->Current)].descriptor;
  const std::size_t n = std::min(size, d.size());
  std::copy(d.begin(), d.begin() + static_cast<std::ptrdiff_t>(n), buffer);
  return static_cast<int>(n);
}

int FakeHidTransport::readInput(std::uint8_t* buffer, std::size_t size)
{
  std::lock_guard<std::mutex> lock(this->Mutex);
  if (this->failIfUnusable() < 0)
  {
    return -1;
  }
  if (this->Inputs.empty())
  {
    return 0;
  }
  const std::vector<std::uint8_t> report = std::move(this->Inputs.front());
  this->Inputs.pop_front();
  const std::size_t n = std::min(size, report.size());
  std::copy(report.begin(), report.begin() + static_cast<std::ptrdiff_t>(n), buffer);
  return static_cast<int>(n);
}

int FakeHidTransport::writeOutput(const std::uint8_t* report, std::size_t size)
{
  std::unique_lock<std::mutex> lock(this->Mutex);
  if (this->Stall)
  {
    ++this->Stalled;
    this->StallReleased.wait(lock, [this]() { return !this->Stall; });
    --this->Stalled;
  }
  if (this->failIfUnusable() < 0)
  {
    return -1;
  }
  if (this->WritesBeforeFailure == 0)
  {
    this->Gone = false;
    this->Error = "fake: write failed (I/O error)";
    return -1;
  }
  if (this->WritesBeforeFailure > 0)
  {
    --this->WritesBeforeFailure;
  }
  this->Records.push_back(
    FakeHidRecord{ FakeHidRecord::Kind::Output, std::vector<std::uint8_t>(report, report + size) });
  return static_cast<int>(size);
}

int FakeHidTransport::sendFeature(const std::uint8_t* report, std::size_t size)
{
  std::lock_guard<std::mutex> lock(this->Mutex);
  if (this->failIfUnusable() < 0)
  {
    return -1;
  }
  this->Records.push_back(FakeHidRecord{
    FakeHidRecord::Kind::SetFeature, std::vector<std::uint8_t>(report, report + size) });
  return static_cast<int>(size);
}

int FakeHidTransport::getFeature(std::uint8_t* report, std::size_t size)
{
  std::lock_guard<std::mutex> lock(this->Mutex);
  if (this->failIfUnusable() < 0 || size == 0)
  {
    return -1;
  }
  this->Records.push_back(
    FakeHidRecord{ FakeHidRecord::Kind::GetFeature, std::vector<std::uint8_t>(1, report[0]) });
  const auto& responder = this->Devices[static_cast<std::size_t>(this->Current)].featureResponder;
  if (!responder)
  {
    this->Error = "fake: feature report not supported";
    return -1;
  }
  const int n = responder(report, size);
  if (n < 0)
  {
    this->Error = "fake: feature report refused";
  }
  return n;
}

bool FakeHidTransport::disconnected() const
{
  std::lock_guard<std::mutex> lock(this->Mutex);
  return this->Gone;
}

const char* FakeHidTransport::lastError() const
{
  std::lock_guard<std::mutex> lock(this->Mutex);
  return this->Error;
}

} // namespace vtouch

#include "vtouchSafeHapticDevice.h"

#include "vtouchSteadyClock.h"

#include <algorithm>
#include <chrono>
#include <utility>

namespace vtouch
{

SafeHapticDevice::SafeHapticDevice(std::unique_ptr<HapticDevice> inner,
  SafeHapticDeviceParameters parameters)
  : Inner(std::move(inner))
  , Parameters(std::move(parameters))
  , Filter(Parameters.filter)
{
}

SafeHapticDevice::~SafeHapticDevice()
{
  this->close();
}

double SafeHapticDevice::now_s() const
{
  return this->Parameters.clock_s ? this->Parameters.clock_s() : steadyNow_s();
}

bool SafeHapticDevice::tryAcquireIo()
{
  return !this->IoBusy.exchange(true, std::memory_order_acquire);
}

void SafeHapticDevice::releaseIo()
{
  this->IoBusy.store(false, std::memory_order_release);
}

void SafeHapticDevice::latch(SafetyFault fault, const char* reason)
{
  SafetyFault expected = SafetyFault::None;
  // The first fault wins: it is the cause, later ones are consequences.
  if (this->Fault.compare_exchange_strong(expected, fault) || fault == SafetyFault::Disconnected)
  {
    this->Fault.store(fault);
    this->LastError.store(reason ? reason : toString(fault));
  }
}

DeviceStatus SafeHapticDevice::open()
{
  if (!this->Inner)
  {
    this->LastError.store("safe device: no device to wrap");
    return DeviceStatus::NotOpen;
  }
  {
    std::lock_guard<std::mutex> lock(this->ControlMutex);
    while (!this->tryAcquireIo())
    {
      std::this_thread::yield();
    }
    const DeviceStatus status = this->Inner->open();
    if (status != DeviceStatus::Ok)
    {
      this->LastError.store(this->Inner->lastError());
      this->releaseIo();
      return status;
    }
    const DeviceCapabilities& caps = this->Inner->capabilities();
    ForceSafetyParameters filter = this->Parameters.filter;
    if (caps.actuatedDof <= 0)
    {
      filter.maxForce_N = 0.0;
    }
    else if (caps.maxContinuousForce_N > 0.0)
    {
      filter.maxForce_N = std::min(filter.maxForce_N, caps.maxContinuousForce_N);
    }
    this->Filter.setParameters(filter);
    this->Filter.reset();
    this->LastTick_s = -1.0;
    this->ResetFilter.store(false);
    this->PendingZero.store(false);
    this->Fault.store(SafetyFault::None);
    this->Armed.store(false);
    this->LastError.store("");
    this->IsOpenFlag.store(true);
    this->releaseIo();
  }
  this->startThread();
  return DeviceStatus::Ok;
}

void SafeHapticDevice::close()
{
  this->stopThread();
  std::lock_guard<std::mutex> lock(this->ControlMutex);
  this->IsOpenFlag.store(false);
  this->Armed.store(false);
  if (!this->Inner)
  {
    return;
  }
  while (!this->tryAcquireIo())
  {
    std::this_thread::yield();
  }
  if (this->Inner->isOpen())
  {
    this->Inner->write(Vec3{});
    this->Inner->close();
  }
  this->SentX.store(0.0);
  this->SentY.store(0.0);
  this->SentZ.store(0.0);
  this->releaseIo();
}

bool SafeHapticDevice::isOpen() const
{
  return this->IsOpenFlag.load();
}

DeviceStatus SafeHapticDevice::read(DeviceState& state)
{
  if (!this->IsOpenFlag.load())
  {
    this->LastError.store("safe device: not open");
    return DeviceStatus::NotOpen;
  }
  if (this->Fault.load() == SafetyFault::Disconnected)
  {
    return DeviceStatus::Disconnected;
  }
  if (!this->tryAcquireIo())
  {
    this->LastError.store("safe device: the watchdog is zeroing the force");
    return DeviceStatus::Fault;
  }
  DeviceStatus status = this->Inner->read(state);
  if (status == DeviceStatus::Disconnected || status == DeviceStatus::NotOpen)
  {
    this->latch(SafetyFault::Disconnected, this->Inner->lastError());
    this->Inner->write(Vec3{});
    status = DeviceStatus::Disconnected;
  }
  else if (status == DeviceStatus::IoError)
  {
    this->latch(SafetyFault::DeviceError, this->Inner->lastError());
    this->Inner->write(Vec3{});
  }
  this->releaseIo();
  return status;
}

DeviceStatus SafeHapticDevice::write(const Vec3& force_Device_N)
{
  if (!this->IsOpenFlag.load())
  {
    this->LastError.store("safe device: not open");
    return DeviceStatus::NotOpen;
  }
  const double now = this->now_s();
  this->LastWrite_s.store(now);
  this->Armed.store(true);
  if (!this->tryAcquireIo())
  {
    this->LastError.store("safe device: the watchdog is zeroing the force");
    return DeviceStatus::Fault;
  }
  if (this->ResetFilter.exchange(false))
  {
    this->Filter.reset();
    this->LastTick_s = -1.0;
  }
  const SafetyFault latched = this->Fault.load();
  if (latched != SafetyFault::None)
  {
    this->Filter.reset();
    if (latched != SafetyFault::Disconnected)
    {
      this->Inner->write(Vec3{});
    }
    this->SentX.store(0.0);
    this->SentY.store(0.0);
    this->SentZ.store(0.0);
    this->releaseIo();
    return latched == SafetyFault::Disconnected ? DeviceStatus::Disconnected : DeviceStatus::Fault;
  }

  const double rate = this->Inner->capabilities().maxUpdateRate_Hz;
  const double dt =
    this->LastTick_s < 0.0 ? (rate > 0.0 ? 1.0 / rate : 0.001) : now - this->LastTick_s;
  this->LastTick_s = now;
  SafetyFault nonFinite = SafetyFault::None;
  const Vec3 safe = this->Filter.apply(force_Device_N, dt, &nonFinite);
  DeviceStatus status = this->Inner->write(safe);
  if (status == DeviceStatus::Ok)
  {
    this->SentX.store(safe.x, std::memory_order_relaxed);
    this->SentY.store(safe.y, std::memory_order_relaxed);
    this->SentZ.store(safe.z, std::memory_order_relaxed);
  }
  else if (status != DeviceStatus::Unsupported)
  {
    const bool gone = status == DeviceStatus::Disconnected || status == DeviceStatus::NotOpen;
    this->latch(
      gone ? SafetyFault::Disconnected : SafetyFault::DeviceError, this->Inner->lastError());
    this->Filter.reset();
    this->Inner->write(Vec3{});
    this->SentX.store(0.0);
    this->SentY.store(0.0);
    this->SentZ.store(0.0);
    status = gone ? DeviceStatus::Disconnected : status;
  }
  this->releaseIo();
  if (nonFinite != SafetyFault::None && status == DeviceStatus::Ok)
  {
    this->NonFiniteCount.fetch_add(1);
    this->LastError.store("safe device: non-finite force commanded (zero force sent)");
    return DeviceStatus::InvalidArgument;
  }
  return status;
}

bool SafeHapticDevice::clearFault()
{
  const SafetyFault fault = this->Fault.load();
  if (fault == SafetyFault::Disconnected)
  {
    return false; // cleared by the reopen, once the device is back
  }
  this->ResetFilter.store(true);
  this->Armed.store(false);
  this->PendingZero.store(false);
  SafetyFault expected = fault;
  return this->Fault.compare_exchange_strong(expected, SafetyFault::None);
}

Vec3 SafeHapticDevice::lastSentForce_N() const
{
  return Vec3{ this->SentX.load(std::memory_order_relaxed),
    this->SentY.load(std::memory_order_relaxed),
    this->SentZ.load(std::memory_order_relaxed) };
}

bool SafeHapticDevice::pollWatchdog(double now_s)
{
  if (!this->IsOpenFlag.load())
  {
    return false;
  }
  const SafetyFault fault = this->Fault.load();
  if (fault == SafetyFault::Disconnected)
  {
    if (this->Parameters.autoReopen)
    {
      this->tryReopen(now_s);
    }
    return false;
  }
  if (this->PendingZero.load() && this->tryAcquireIo())
  {
    this->Inner->write(Vec3{});
    this->PendingZero.store(false);
    this->releaseIo();
    return true;
  }
  const double timeout = this->Parameters.watchdogTimeout_s;
  if (timeout > 0.0 && fault == SafetyFault::None && this->Armed.load() &&
      now_s - this->LastWrite_s.load() > timeout)
  {
    this->latch(SafetyFault::Watchdog, "safe device: watchdog: no force update in time");
    this->WatchdogTrips.fetch_add(1);
    if (this->tryAcquireIo())
    {
      this->Inner->write(Vec3{});
      this->Filter.reset();
      this->SentX.store(0.0);
      this->SentY.store(0.0);
      this->SentZ.store(0.0);
      this->releaseIo();
    }
    else
    {
      // The haptic thread is stuck inside the device's I/O: zero as soon as it lets go.
      this->PendingZero.store(true);
    }
    return true;
  }
  return false;
}

void SafeHapticDevice::tryReopen(double now_s)
{
  if (now_s - this->LastReopenAttempt_s.load() < this->Parameters.reopenInterval_s)
  {
    return;
  }
  this->LastReopenAttempt_s.store(now_s);
  std::unique_lock<std::mutex> lock(this->ControlMutex, std::try_to_lock);
  if (!lock.owns_lock() || !this->IsOpenFlag.load() || !this->tryAcquireIo())
  {
    return;
  }
  this->Inner->close();
  if (this->Inner->open() == DeviceStatus::Ok)
  {
    this->Filter.reset();
    this->LastTick_s = -1.0;
    this->Armed.store(false);
    this->ReopenCount.fetch_add(1);
    this->LastError.store("safe device: reopened after a disconnection");
    this->Fault.store(SafetyFault::None);
  }
  this->releaseIo();
}

void SafeHapticDevice::startThread()
{
  const bool needed = this->Parameters.watchdogThread &&
                      (this->Parameters.watchdogTimeout_s > 0.0 || this->Parameters.autoReopen);
  if (!needed || this->Watchdog.joinable())
  {
    return;
  }
  this->Stop.store(false);
  this->Watchdog = std::thread([this]() { this->watchdogLoop(); });
}

void SafeHapticDevice::stopThread()
{
  if (!this->Watchdog.joinable())
  {
    return;
  }
  {
    std::lock_guard<std::mutex> lock(this->WakeMutex);
    this->Stop.store(true);
  }
  this->Wake.notify_all();
  this->Watchdog.join();
}

void SafeHapticDevice::watchdogLoop()
{
  const double timeout = this->Parameters.watchdogTimeout_s;
  const double period_s = timeout > 0.0 ? std::clamp(timeout / 4.0, 0.0005, 0.005) : 0.02;
  const auto period = std::chrono::duration<double>(period_s);
  std::unique_lock<std::mutex> lock(this->WakeMutex);
  while (!this->Stop.load())
  {
    this->Wake.wait_for(lock, period, [this]() { return this->Stop.load(); });
    if (this->Stop.load())
    {
      break;
    }
    lock.unlock();
    this->pollWatchdog(this->now_s());
    lock.lock();
  }
}

} // namespace vtouch

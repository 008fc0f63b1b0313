// Plays a recorded trajectory (CSV: time,x,y,pressure,buttons) and records every commanded force,
// so that an exploration can be reproduced and compared.
#pragma once

#include "vtouchHapticDevice.h"
#include "vtouchVelocityEstimator.h"

#include <cstdint>
#include <string>
#include <vector>

namespace vtouch
{

/// One recorded sample, device frame.
struct ReplaySample
{
  double time_s = 0.0;     ///< since the start of the recording
  Vec2 position_Device_mm; ///< handle position
  double pressure = 0.0;   ///< [0, 1]
  std::uint32_t buttons = 0;
};

/// One commanded force as recorded.
struct ReplayForce
{
  double time_s = 0.0; ///< replay time at which it was written
  Vec3 force_Device_N;
};

/// Parameters of a ReplayDevice.
struct ReplayDeviceParameters
{
  enum class Clock : std::uint8_t
  {
    Manual,  ///< advance(dt) moves replay time (deterministic)
    RealTime ///< replay time is the steady clock since open()
  };
  /// Time source. Default Manual.
  Clock clock = Clock::Manual;
  /// Start again at the end. Default false (the last sample holds).
  bool loop = false;
  /// Where close() writes the recorded forces as CSV (time_s,fx_N,fy_N,fz_N); empty = nowhere.
  std::string forceRecordPath;
  /// Forces kept (reserved at open(), never grown while running). Default 600000 (10 min at 1 kHz).
  std::size_t forceCapacity = 600000;
  /// Capabilities reported (the recording has no force limits of its own).
  Vec2 workspace_mm{ 160.0, 120.0 };
  double maxContinuousForce_N = 3.0;
  double maxStiffness_N_per_m = 1000.0;
};

/// Reads positions by linear interpolation between recorded samples (buttons hold the previous
/// sample's value). The CSV may start with a header line and may contain # comments.
class ReplayDevice : public HapticDevice
{
public:
  explicit ReplayDevice(const ReplayDeviceParameters& parameters = ReplayDeviceParameters{});

  /// Loads a CSV file / text. Times must increase. Only while closed.
  bool loadCsv(const std::string& path, std::string& error);
  bool parseCsv(const std::string& text, std::string& error);
  /// Uses these samples (times must increase). Only while closed.
  bool setSamples(std::vector<ReplaySample> samples, std::string& error);
  const std::vector<ReplaySample>& samples() const { return this->Samples; }

  /// Writes samples as CSV (the format loadCsv() reads).
  static bool saveCsv(const std::string& path, const std::vector<ReplaySample>& samples);
  /// Writes forces as CSV.
  static bool saveForcesCsv(const std::string& path, const std::vector<ReplayForce>& forces);

  DeviceStatus open() override;
  void close() override;
  bool isOpen() const override { return this->Open; }
  const DeviceCapabilities& capabilities() const override { return this->Capabilities; }
  DeviceStatus read(DeviceState& state) override;
  DeviceStatus write(const Vec3& force_Device_N) override;
  const char* lastError() const override { return this->LastError; }

  /// Moves replay time forward (Manual clock).
  void advance(double dt_s);
  double time_s() const { return this->Time_s; }
  /// True once replay time passed the last sample (never when looping).
  bool finished() const;
  /// Every force written since open() (up to forceCapacity).
  const std::vector<ReplayForce>& forces() const { return this->Forces; }
  /// Forces dropped because forceCapacity was reached.
  std::uint64_t droppedForces() const { return this->Dropped; }

private:
  double currentTime();
  ReplaySample sampleAt(double t);

  ReplayDeviceParameters Parameters;
  std::vector<ReplaySample> Samples;
  std::vector<ReplayForce> Forces;
  DeviceCapabilities Capabilities;
  VelocityEstimator Velocity;
  bool Open = false;
  double Time_s = 0.0;
  double Origin_s = 0.0;
  std::size_t Cursor = 0; // sample at or before the last time read
  std::uint64_t Dropped = 0;
  const char* LastError = "";
};

} // namespace vtouch

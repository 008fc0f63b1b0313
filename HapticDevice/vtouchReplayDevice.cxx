#include "vtouchReplayDevice.h"

#include "vtouchSteadyClock.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

namespace vtouch
{

namespace
{

bool parseLine(const std::string& line, ReplaySample& s)
{
  double v[5] = { 0, 0, 0, 0, 0 };
  const char* p = line.c_str();
  for (int i = 0; i < 5; ++i)
  {
    char* end = nullptr;
    v[i] = std::strtod(p, &end);
    if (end == p || !std::isfinite(v[i]))
    {
      return false;
    }
    p = end;
    while (*p == ' ' || *p == '\t')
    {
      ++p;
    }
    if (i < 4)
    {
      if (*p != ',')
      {
        return false;
      }
      ++p;
    }
  }
  while (*p == ' ' || *p == '\t' || *p == '\r')
  {
    ++p;
  }
  if (*p != '\0' || v[4] < 0.0 || v[4] > 4294967295.0)
  {
    return false;
  }
  s.time_s = v[0];
  s.position_Device_mm = Vec2{ v[1], v[2] };
  s.pressure = std::clamp(v[3], 0.0, 1.0);
  s.buttons = static_cast<std::uint32_t>(v[4]);
  return true;
}
} // namespace

ReplayDevice::ReplayDevice(const ReplayDeviceParameters& parameters)
  : Parameters(parameters)
{
}

bool ReplayDevice::loadCsv(const std::string& path, std::string& error)
{
  std::ifstream in(path);
  if (!in)
  {
    error = "cannot open " + path;
    return false;
  }
  std::stringstream text;
  text << in.rdbuf();
  return this->parseCsv(text.str(), error);
}

bool ReplayDevice::parseCsv(const std::string& text, std::string& error)
{
  std::vector<ReplaySample> samples;
  std::istringstream in(text);
  std::string line;
  int number = 0;
  while (std::getline(in, line))
  {
    ++number;
    const auto first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#')
    {
      continue;
    }
    ReplaySample s;
    if (!parseLine(line, s))
    {
      if (samples.empty() && number == 1 && line.find("time") != std::string::npos)
      {
        continue; // header
      }
      error = "line " + std::to_string(number) + ": expected time,x,y,pressure,buttons";
      return false;
    }
    samples.push_back(s);
  }
  return this->setSamples(std::move(samples), error);
}

bool ReplayDevice::setSamples(std::vector<ReplaySample> samples, std::string& error)
{
  if (this->Open)
  {
    error = "replay device: close it before loading";
    return false;
  }
  if (samples.empty())
  {
    error = "no samples";
    return false;
  }
  for (std::size_t i = 1; i < samples.size(); ++i)
  {
    if (!(samples[i].time_s > samples[i - 1].time_s))
    {
      error = "times must increase (sample " + std::to_string(i) + ")";
      return false;
    }
  }
  this->Samples = std::move(samples);
  return true;
}

bool ReplayDevice::saveCsv(const std::string& path, const std::vector<ReplaySample>& samples)
{
  std::FILE* f = std::fopen(path.c_str(), "w");
  if (!f)
  {
    return false;
  }
  std::fprintf(f, "time,x,y,pressure,buttons\n");
  for (const ReplaySample& s : samples)
  {
    std::fprintf(f,
      "%.9g,%.17g,%.17g,%.17g,%u\n",
      s.time_s,
      s.position_Device_mm.x,
      s.position_Device_mm.y,
      s.pressure,
      s.buttons);
  }
  return std::fclose(f) == 0;
}

bool ReplayDevice::saveForcesCsv(const std::string& path, const std::vector<ReplayForce>& forces)
{
  std::FILE* f = std::fopen(path.c_str(), "w");
  if (!f)
  {
    return false;
  }
  std::fprintf(f, "time_s,fx_N,fy_N,fz_N\n");
  for (const ReplayForce& r : forces)
  {
    std::fprintf(f,
      "%.9g,%.17g,%.17g,%.17g\n",
      r.time_s,
      r.force_Device_N.x,
      r.force_Device_N.y,
      r.force_Device_N.z);
  }
  return std::fclose(f) == 0;
}

DeviceStatus ReplayDevice::open()
{
  if (this->Samples.empty())
  {
    this->LastError = "replay device: no trajectory loaded";
    return DeviceStatus::NotOpen;
  }
  DeviceCapabilities caps;
  std::snprintf(caps.name, sizeof(caps.name), "%s", "VesselTouch replay");
  caps.sensedDof = 2;
  caps.actuatedDof = 2;
  caps.workspace_mm = Vec3{ this->Parameters.workspace_mm.x, this->Parameters.workspace_mm.y, 0.0 };
  caps.maxContinuousForce_N = this->Parameters.maxContinuousForce_N;
  caps.maxStiffness_N_per_m = this->Parameters.maxStiffness_N_per_m;
  caps.maxUpdateRate_Hz = 10000.0;
  caps.hasPressure = true;
  caps.buttonCount = 32;
  this->Capabilities = caps;
  this->Forces.clear();
  this->Forces.reserve(this->Parameters.forceCapacity);
  this->Dropped = 0;
  this->Velocity.reset();
  this->Time_s = this->Samples.front().time_s;
  this->Origin_s = steadyNow_s() - this->Time_s;
  this->Cursor = 0;
  this->LastError = "";
  this->Open = true;
  return DeviceStatus::Ok;
}

void ReplayDevice::close()
{
  if (!this->Open)
  {
    return;
  }
  this->Open = false;
  if (!this->Parameters.forceRecordPath.empty() &&
      !saveForcesCsv(this->Parameters.forceRecordPath, this->Forces))
  {
    this->LastError = "replay device: cannot write the force record";
  }
}

void ReplayDevice::advance(double dt_s)
{
  if (dt_s > 0.0 && std::isfinite(dt_s))
  {
    this->Time_s += dt_s;
  }
}

double ReplayDevice::currentTime()
{
  if (this->Parameters.clock == ReplayDeviceParameters::Clock::RealTime)
  {
    this->Time_s = steadyNow_s() - this->Origin_s;
  }
  return this->Time_s;
}

bool ReplayDevice::finished() const
{
  return !this->Parameters.loop && !this->Samples.empty() &&
         this->Time_s > this->Samples.back().time_s;
}

ReplaySample ReplayDevice::sampleAt(double t)
{
  const std::vector<ReplaySample>& s = this->Samples;
  const double t0 = s.front().time_s;
  const double t1 = s.back().time_s;
  if (this->Parameters.loop && t1 > t0 && t > t1)
  {
    t = t0 + std::fmod(t - t0, t1 - t0);
    this->Cursor = 0;
  }
  if (t <= t0)
  {
    this->Cursor = 0;
    return s.front();
  }
  if (t >= t1)
  {
    this->Cursor = s.size() - 1;
    return s.back();
  }
  // Time moves forward: walk the cursor from where it was (amortised O(1) per read).
  if (s[this->Cursor].time_s > t)
  {
    this->Cursor = 0;
  }
  while (this->Cursor + 1 < s.size() && s[this->Cursor + 1].time_s <= t)
  {
    ++this->Cursor;
  }
  const ReplaySample& a = s[this->Cursor];
  const ReplaySample& b = s[std::min(this->Cursor + 1, s.size() - 1)];
  const double span = b.time_s - a.time_s;
  const double w = span > 0.0 ? (t - a.time_s) / span : 0.0;
  ReplaySample out = a;
  out.time_s = t;
  out.position_Device_mm = a.position_Device_mm + (b.position_Device_mm - a.position_Device_mm) * w;
  out.pressure = a.pressure + (b.pressure - a.pressure) * w;
  return out;
}

DeviceStatus ReplayDevice::read(DeviceState& state)
{
  if (!this->Open)
  {
    this->LastError = "replay device: not open";
    return DeviceStatus::NotOpen;
  }
  const double t = this->currentTime();
  const ReplaySample s = this->sampleAt(t);
  DeviceState out;
  out.timestamp_s = t;
  out.position_Device_mm = Vec3{ s.position_Device_mm.x, s.position_Device_mm.y, 0.0 };
  out.pressure = s.pressure;
  out.buttons = s.buttons;
  this->Velocity.add(t, out.position_Device_mm);
  out.velocity_Device_mm_per_s = this->Velocity.velocity_mm_per_s();
  state = out;
  return DeviceStatus::Ok;
}

DeviceStatus ReplayDevice::write(const Vec3& force_Device_N)
{
  if (!this->Open)
  {
    this->LastError = "replay device: not open";
    return DeviceStatus::NotOpen;
  }
  // Recorded as commanded (NaN included): the record is for comparing force laws.
  if (this->Forces.size() < this->Forces.capacity())
  {
    this->Forces.push_back(ReplayForce{ this->currentTime(), force_Device_N });
  }
  else
  {
    ++this->Dropped;
  }
  if (!force_Device_N.isFinite())
  {
    this->LastError = "replay device: non-finite force";
    return DeviceStatus::InvalidArgument;
  }
  return DeviceStatus::Ok;
}

} // namespace vtouch

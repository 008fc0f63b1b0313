#include "vtouchDeviceCalibration.h"

#include "vtouchJsonValue.h"

#include <dlfcn.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#ifndef VTOUCH_PRESETS_DIR
#define VTOUCH_PRESETS_DIR ""
#endif

namespace vtouch
{

namespace
{
/// "0x1209" or 4617 -> 4617; false for anything else.
bool readId(const JsonValue* value, std::uint16_t& id)
{
  if (!value)
  {
    return false;
  }
  if (value->type() == JsonValue::Type::Number)
  {
    const double n = value->number(-1.0);
    if (n < 0.0 || n > 65535.0 || n != std::floor(n))
    {
      return false;
    }
    id = static_cast<std::uint16_t>(n);
    return true;
  }
  const std::string text = value->string("");
  if (text.empty())
  {
    return false;
  }
  char* end = nullptr;
  const unsigned long n = std::strtoul(text.c_str(), &end, 0);
  if (*end != '\0' || n > 65535)
  {
    return false;
  }
  id = static_cast<std::uint16_t>(n);
  return true;
}

Vec2 readPair(const JsonValue* value, const Vec2& fallback)
{
  if (!value || value->items().size() != 2)
  {
    return fallback;
  }
  const Vec2 v{ value->items()[0].number(fallback.x), value->items()[1].number(fallback.y) };
  return v.isFinite() ? v : fallback;
}
} // namespace

bool DeviceCalibration::fromJson(const std::string& text,
  DeviceCalibration& calibration,
  std::string& error)
{
  JsonValue root;
  if (!JsonValue::parse(text, root, error))
  {
    return false;
  }
  if (!root.isObject())
  {
    error = "a preset must be a JSON object";
    return false;
  }
  DeviceCalibration c;
  c.name = root.stringAt("name", "");
  if (!readId(root.find("vendorId"), c.vendorId) || !readId(root.find("productId"), c.productId))
  {
    error = "vendorId and productId are required (numbers or \"0x....\" strings)";
    return false;
  }
  if (const JsonValue* axes = root.find("axes"))
  {
    c.rawMinimum = readPair(axes->find("rawMinimum"), c.rawMinimum);
    c.rawMaximum = readPair(axes->find("rawMaximum"), c.rawMaximum);
    c.workspace_mm = readPair(axes->find("workspace_mm"), c.workspace_mm);
    c.invertX = axes->booleanAt("invertX", c.invertX);
    c.invertY = axes->booleanAt("invertY", c.invertY);
    c.countsPerMm = axes->numberAt("countsPerMm", c.countsPerMm);
  }
  if (const JsonValue* force = root.find("force"))
  {
    c.fullScaleForce_N = force->numberAt("fullScaleForce_N", c.fullScaleForce_N);
    c.maxContinuousForce_N = force->numberAt("maxContinuousForce_N", c.maxContinuousForce_N);
    c.maxStiffness_N_per_m = force->numberAt("maxStiffness_N_per_m", c.maxStiffness_N_per_m);
    c.maxUpdateRate_Hz = force->numberAt("maxUpdateRate_Hz", c.maxUpdateRate_Hz);
    c.directionOffset_deg = force->numberAt("directionOffset_deg", c.directionOffset_deg);
    c.keepAlive_s = force->numberAt("keepAlive_s", c.keepAlive_s);
    const std::string mode = force->stringAt("effectMode", "auto");
    if (mode == "auto")
      c.effectMode = PidEffectMode::Auto;
    else if (mode == "perAxis")
      c.effectMode = PidEffectMode::PerAxis;
    else if (mode == "polar")
      c.effectMode = PidEffectMode::Polar;
    else if (mode == "singleX")
      c.effectMode = PidEffectMode::SingleX;
    else
    {
      error = "effectMode must be auto, perAxis, polar or singleX";
      return false;
    }
  }
  if (const JsonValue* quirks = root.find("quirks"))
  {
    c.infiniteDuration = static_cast<std::int64_t>(
      quirks->numberAt("infiniteDuration", static_cast<double>(c.infiniteDuration)));
    c.blockLoadRetries = static_cast<int>(quirks->numberAt("blockLoadRetries", c.blockLoadRetries));
  }
  if (!(c.fullScaleForce_N > 0.0) || !(c.maxContinuousForce_N >= 0.0) ||
      !(c.workspace_mm.x > 0.0 && c.workspace_mm.y > 0.0) || !(c.countsPerMm > 0.0) ||
      c.blockLoadRetries < 1 || c.blockLoadRetries > 100)
  {
    error = "out-of-range value (forces, workspace, countsPerMm or blockLoadRetries)";
    return false;
  }
  calibration = c;
  return true;
}

bool DeviceCalibration::fromFile(const std::string& path,
  DeviceCalibration& calibration,
  std::string& error)
{
  std::ifstream in(path);
  if (!in)
  {
    error = "cannot open " + path;
    return false;
  }
  std::stringstream text;
  text << in.rdbuf();
  if (!fromJson(text.str(), calibration, error))
  {
    error = path + ": " + error;
    return false;
  }
  return true;
}

bool DeviceCalibration::findPreset(const std::string& directory,
  std::uint16_t vendorId,
  std::uint16_t productId,
  DeviceCalibration& calibration)
{
  std::error_code ec;
  if (directory.empty() || !std::filesystem::is_directory(directory, ec))
  {
    return false;
  }
  for (const auto& entry : std::filesystem::directory_iterator(directory, ec))
  {
    if (entry.path().extension() != ".json")
    {
      continue;
    }
    DeviceCalibration candidate;
    std::string error;
    if (fromFile(entry.path().string(), candidate, error) && candidate.vendorId == vendorId &&
        candidate.productId == productId)
    {
      calibration = candidate;
      return true;
    }
  }
  return false;
}

std::string DeviceCalibration::findInstalledPresetDirectory(
  const std::string& startDirectory, int levels)
{
  std::error_code ec;
  std::filesystem::path directory = std::filesystem::absolute(startDirectory, ec);
  if (ec)
  {
    return std::string();
  }
  for (int level = 0; level <= levels && !directory.empty(); ++level)
  {
    const std::filesystem::path candidate = directory / "share" / "VesselTouch" / "Presets";
    std::error_code missing; // a folder that does not exist is not an error here
    if (std::filesystem::is_directory(candidate, missing))
    {
      return candidate.string();
    }
    if (directory == directory.parent_path())
    {
      break;
    }
    directory = directory.parent_path();
  }
  return std::string();
}

std::string DeviceCalibration::presetDirectory()
{
  const char* env = std::getenv("VESSELTOUCH_PRESETS_DIR");
  if (env && *env)
  {
    return std::string(env);
  }
  // The library or executable this function was linked into (the plugin, a tool, a test).
  Dl_info info{};
  if (dladdr(reinterpret_cast<void*>(&DeviceCalibration::presetDirectory), &info) != 0 &&
    info.dli_fname && *info.dli_fname)
  {
    const std::string installed = DeviceCalibration::findInstalledPresetDirectory(
      std::filesystem::path(info.dli_fname).parent_path().string());
    if (!installed.empty())
    {
      return installed;
    }
  }
  return std::string(VTOUCH_PRESETS_DIR);
}

} // namespace vtouch

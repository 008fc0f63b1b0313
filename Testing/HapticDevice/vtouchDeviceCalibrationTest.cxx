#include "vtouchDeviceCalibration.h"
#include "vtouchJsonValue.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <string>

namespace
{
using vtouch::DeviceCalibration;
using vtouch::JsonValue;
using vtouch::PidEffectMode;

TEST(JsonValue, ParsesNestedDocumentWhenValid)
{
  JsonValue v;
  std::string error;
  ASSERT_TRUE(JsonValue::parse(
    R"({"a": [1, -2.5e1, true, null], "b": {"c": "x\"\u00e9"}, "d": false})", v, error))
    << error;
  ASSERT_TRUE(v.isObject());
  EXPECT_EQ(v.find("a")->items().size(), 4u);
  EXPECT_DOUBLE_EQ(v.find("a")->items()[1].number(0), -25.0);
  EXPECT_EQ(v.find("b")->stringAt("c", ""), "x\"\xC3\xA9");
  EXPECT_FALSE(v.booleanAt("d", true));
  EXPECT_EQ(v.find("missing"), nullptr);
}

TEST(JsonValue, RejectsDocumentWhenMalformed)
{
  const std::string deep(100, '[');
  const std::string bad[] = {
    "", "{", "[1,]", "{\"a\" 1}", "tru", "\"abc", "1 2", "{\"a\":1,}", "[\"\\x\"]", "-", deep
  };
  for (const std::string& text : bad)
  {
    JsonValue v;
    std::string error;
    EXPECT_FALSE(JsonValue::parse(text, v, error)) << text;
    EXPECT_FALSE(error.empty());
  }
}

TEST(DeviceCalibration, ReadsEveryMemberWhenPresetIsComplete)
{
  DeviceCalibration c;
  std::string error;
  ASSERT_TRUE(DeviceCalibration::fromJson(R"({
      "name": "test", "vendorId": "0x1209", "productId": 65456,
      "axes": {"rawMinimum": [-100, 0], "rawMaximum": [100, 50], "workspace_mm": [80, 40],
               "invertX": true, "invertY": false, "countsPerMm": 8},
      "force": {"fullScaleForce_N": 2.5, "maxContinuousForce_N": 1.2, "effectMode": "polar",
                "directionOffset_deg": 90, "keepAlive_s": 0.1},
      "quirks": {"infiniteDuration": 0, "blockLoadRetries": 7}})",
    c,
    error))
    << error;
  EXPECT_EQ(c.vendorId, 0x1209);
  EXPECT_EQ(c.productId, 0xFFB0);
  EXPECT_DOUBLE_EQ(c.rawMaximum.y, 50.0);
  EXPECT_DOUBLE_EQ(c.workspace_mm.x, 80.0);
  EXPECT_TRUE(c.invertX);
  EXPECT_FALSE(c.invertY);
  EXPECT_EQ(c.effectMode, PidEffectMode::Polar);
  EXPECT_EQ(c.infiniteDuration, 0);
  EXPECT_EQ(c.blockLoadRetries, 7);
}

TEST(DeviceCalibration, RejectsPresetWhenIdsMissingOrValuesOutOfRange)
{
  DeviceCalibration c;
  std::string error;
  EXPECT_FALSE(DeviceCalibration::fromJson(R"({"vendorId": 1})", c, error));
  EXPECT_FALSE(DeviceCalibration::fromJson(R"({"vendorId": 1, "productId": 70000})", c, error));
  EXPECT_FALSE(DeviceCalibration::fromJson(
    R"({"vendorId": 1, "productId": 2, "force": {"fullScaleForce_N": 0}})", c, error));
  EXPECT_FALSE(DeviceCalibration::fromJson(
    R"({"vendorId": 1, "productId": 2, "force": {"effectMode": "sideways"}})", c, error));
  EXPECT_FALSE(DeviceCalibration::fromJson("[1]", c, error));
}

TEST(DeviceCalibration, FindsShippedPresetWhenIdsMatch)
{
  DeviceCalibration c;
  ASSERT_TRUE(DeviceCalibration::findPreset(VTOUCH_TEST_PRESETS_DIR, 0x1209, 0xFFB0, c));
  EXPECT_EQ(c.effectMode, PidEffectMode::PerAxis);
  ASSERT_TRUE(DeviceCalibration::findPreset(VTOUCH_TEST_PRESETS_DIR, 0x045E, 0x001B, c));
  EXPECT_EQ(c.effectMode, PidEffectMode::Polar);
  EXPECT_FALSE(DeviceCalibration::findPreset(VTOUCH_TEST_PRESETS_DIR, 0x0001, 0x0002, c));
  EXPECT_FALSE(DeviceCalibration::findPreset("/nonexistent", 0x1209, 0xFFB0, c));
}

TEST(DeviceCalibration, FindsInstalledPresetsAboveThePluginFolder)
{
  // An unpacked package: <root>/lib/paraview-5.11/plugins/VesselTouch/VesselTouch.so and
  // <root>/share/VesselTouch/Presets.
  namespace fs = std::filesystem;
  const fs::path root = fs::temp_directory_path() /
    ("vtouch-presets-" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
      "-" + std::to_string(reinterpret_cast<std::uintptr_t>(&root) & 0xffff));
  const fs::path plugin = root / "lib" / "paraview-5.11" / "plugins" / "VesselTouch";
  const fs::path presets = root / "share" / "VesselTouch" / "Presets";
  fs::create_directories(plugin);
  EXPECT_EQ(DeviceCalibration::findInstalledPresetDirectory(plugin.string()), "")
    << "no presets installed yet";
  fs::create_directories(presets);
  EXPECT_EQ(fs::path(DeviceCalibration::findInstalledPresetDirectory(plugin.string())), presets);
  EXPECT_EQ(fs::path(DeviceCalibration::findInstalledPresetDirectory(root.string())), presets);
  EXPECT_EQ(DeviceCalibration::findInstalledPresetDirectory(plugin.string(), 2), "")
    << "the search stops after the given number of parents";
  EXPECT_EQ(DeviceCalibration::findInstalledPresetDirectory("/nonexistent/a/b"), "");
  fs::remove_all(root);
}

TEST(DeviceCalibration, PresetDirectoryHonoursTheEnvironmentFirst)
{
  ::setenv("VESSELTOUCH_PRESETS_DIR", "/opt/presets-from-env", 1);
  EXPECT_EQ(DeviceCalibration::presetDirectory(), "/opt/presets-from-env");
  ::unsetenv("VESSELTOUCH_PRESETS_DIR");
  // A build tree has no share/VesselTouch/Presets above the test: the source tree's folder.
  EXPECT_TRUE(std::filesystem::is_directory(DeviceCalibration::presetDirectory()));
}

} // namespace

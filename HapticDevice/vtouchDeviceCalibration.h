// Per-device calibration (raw HID axis range -> millimetres, force scale, PID quirks), stored as
// small JSON presets under Resources/Presets, one file per vendor/product id.
#pragma once

#include "vtouchVector.h"

#include <cstdint>
#include <string>

namespace vtouch
{

/// How a HID PID device renders a 2D force.
enum class PidEffectMode : std::uint8_t
{
  Auto,    ///< per-axis when the magnitude is signed and Axes Enable exists, else polar
  PerAxis, ///< one constant-force effect per axis, signed magnitude, no direction updates
  Polar,   ///< one effect: direction (angle) + unsigned magnitude
  SingleX  ///< one effect on X only (devices with neither direction nor axes enable)
};

/// Calibration of one device model. Defaults suit an unknown joystick: the full logical range
/// maps onto a 100 mm x 100 mm workspace and 1 N is the full-scale force. Without a preset,
/// HidPidDevice replaces the workspace by the axes' physical extent when the report descriptor
/// gives them a length unit (hidPhysicalWorkspace_mm).
struct DeviceCalibration
{
  std::string name;            ///< preset name, e.g. "OpenFFBoard (2 axes)"
  std::uint16_t vendorId = 0;  ///< USB vendor id the preset applies to
  std::uint16_t productId = 0; ///< USB product id the preset applies to

  /// Raw axis value at the low end (x, y); NaN-free. When rawMinimum == rawMaximum the field's
  /// logical range is used. Default 0/0 (use the logical range).
  Vec2 rawMinimum;
  Vec2 rawMaximum;
  /// Extent the raw range spans, mm. Default 100 x 100.
  Vec2 workspace_mm{ 100.0, 100.0 };
  /// Flip an axis so that the device frame is x right, y up. Default: y flipped (HID Y grows
  /// toward the user).
  bool invertX = false;
  bool invertY = true;
  /// Relative axes (mice): counts per millimetre. Default 16 (about 400 dpi).
  double countsPerMm = 16.0;

  /// Force at full-scale magnitude, N. Default 1 N.
  double fullScaleForce_N = 1.0;
  /// Force the device may hold indefinitely, N (goes to capabilities). Default 0.5 N.
  double maxContinuousForce_N = 0.5;
  /// Largest stable stiffness at 1 kHz, N/m. Default 200 N/m.
  double maxStiffness_N_per_m = 200.0;
  /// Useful output report rate, Hz. Default 500 Hz.
  double maxUpdateRate_Hz = 500.0;

  /// Effect layout. Default Auto.
  PidEffectMode effectMode = PidEffectMode::Auto;
  /// Angle added to the computed direction, degrees (some firmwares rotate their polar frame).
  /// Default 0: 0 degrees pushes toward +y, 90 toward +x (DirectInput polar convention).
  double directionOffset_deg = 0.0;
  /// Raw value that means "infinite duration": -1 = all ones in the field (0xFFFF for 16 bits,
  /// what the PID spec and most firmwares use); 0 for firmwares that treat 0 as infinite.
  std::int64_t infiniteDuration = -1;
  /// Block Load answers polled after Create New Effect before giving up. Default 5.
  int blockLoadRetries = 5;
  /// Re-send an unchanged force report after this long, s (some firmwares time out). Default 0.05.
  double keepAlive_s = 0.05;

  /// Parses a preset document. Returns false and sets `error` when it is not valid.
  static bool fromJson(const std::string& text, DeviceCalibration& calibration, std::string& error);
  /// Loads one preset file.
  static bool fromFile(const std::string& path, DeviceCalibration& calibration, std::string& error);
  /// Looks through every *.json in `directory` for the preset of (vendorId, productId).
  /// Returns false (and leaves `calibration` unchanged) when none matches.
  static bool findPreset(const std::string& directory,
    std::uint16_t vendorId,
    std::uint16_t productId,
    DeviceCalibration& calibration);
  /// The presets folder: $VESSELTOUCH_PRESETS_DIR if set; else share/VesselTouch/Presets found
  /// above the binary holding this code (an installed or unpacked package: the plugin sits in
  /// lib/paraview-5.11/plugins/VesselTouch/); else the source tree's Resources/Presets.
  static std::string presetDirectory();
  /// The first `share/VesselTouch/Presets` folder in `startDirectory` or up to `levels` parents
  /// above it; "" when there is none.
  static std::string findInstalledPresetDirectory(const std::string& startDirectory, int levels = 5);
};

} // namespace vtouch

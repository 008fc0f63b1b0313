// The scripted "hand" that drives a SimulatedDevice: what a person's hand does to the handle.
#pragma once

#include "vtouchVector.h"

#include <cstdint>
#include <functional>

namespace vtouch
{

/// What the hand does at one instant, in the device frame.
struct HandSample
{
  /// Force the hand applies to the handle (used when the script drives by force), newtons.
  Vec2 force_Device_N;
  /// Where the hand is (used when the script drives by position), millimetres.
  Vec2 position_Device_mm;
  /// Hand velocity (used with the hand damping when driving by position), mm/s. Default 0.
  Vec2 velocity_Device_mm_per_s;
  /// Pressure/z channel reported by the device, normalized to [0, 1]. Default 0.
  double pressure = 0.0;
  /// Buttons held, bit i for button i. Default none.
  std::uint32_t buttons = 0;
};

/// A hand trajectory. Set it on the device before open(); it is evaluated at every integration
/// sub-step, so the callable must not allocate, lock or throw (a lambda capturing plain values is
/// fine; std::function stores it once, when the script is set).
struct HandScript
{
  enum class Drive : std::uint8_t
  {
    Force,   ///< the hand pushes with HandSample::force_Device_N
    Position ///< the hand holds HandSample::position_Device_mm through a spring and damper
  };

  /// How the hand acts on the handle. Default: by force.
  Drive drive = Drive::Force;
  /// Hand stiffness coupling hand and handle when drive == Position, N/m. Default 200 N/m
  /// (a relaxed grip holding a pen).
  double handStiffness_N_per_m = 200.0;
  /// Hand damping when drive == Position, N·s/m. Default 2 N·s/m.
  double handDamping_N_s_per_m = 2.0;
  /// The trajectory: fills `sample` for simulated time `time_s` (seconds since open()).
  /// Empty means a hand that neither pushes nor holds (free handle).
  std::function<void(double time_s, HandSample& sample)> trajectory;

  /// A hand that does nothing: the handle moves only under the device force.
  static HandScript none() { return HandScript{}; }

  /// A hand pushing with a constant force.
  static HandScript constantForce(const Vec2& force_Device_N)
  {
    HandScript script;
    script.drive = Drive::Force;
    script.trajectory = [force_Device_N](double, HandSample& s)
    { s.force_Device_N = force_Device_N; };
    return script;
  }

  /// A hand holding the handle at a fixed point.
  static HandScript holdAt(const Vec2& position_Device_mm, double handStiffness_N_per_m = 200.0)
  {
    HandScript script;
    script.drive = Drive::Position;
    script.handStiffness_N_per_m = handStiffness_N_per_m;
    script.trajectory = [position_Device_mm](double, HandSample& s)
    { s.position_Device_mm = position_Device_mm; };
    return script;
  }

  /// A hand moving along a straight line at constant velocity from `start_Device_mm`.
  static HandScript moveLinear(const Vec2& start_Device_mm,
    const Vec2& velocity_Device_mm_per_s,
    double handStiffness_N_per_m = 200.0)
  {
    HandScript script;
    script.drive = Drive::Position;
    script.handStiffness_N_per_m = handStiffness_N_per_m;
    script.trajectory = [start_Device_mm, velocity_Device_mm_per_s](double t, HandSample& s)
    {
      s.position_Device_mm = start_Device_mm + velocity_Device_mm_per_s * t;
      s.velocity_Device_mm_per_s = velocity_Device_mm_per_s;
    };
    return script;
  }

  /// A hand tracing a circle (centre, radius in mm, frequency in Hz), e.g. for demos.
  static HandScript circle(const Vec2& center_Device_mm,
    double radius_mm,
    double frequency_Hz,
    double handStiffness_N_per_m = 200.0)
  {
    HandScript script;
    script.drive = Drive::Position;
    script.handStiffness_N_per_m = handStiffness_N_per_m;
    script.trajectory = [center_Device_mm, radius_mm, frequency_Hz](double t, HandSample& s)
    {
      const double w = 2.0 * 3.14159265358979323846 * frequency_Hz;
      s.position_Device_mm =
        center_Device_mm + Vec2{ std::cos(w * t), std::sin(w * t) } * radius_mm;
      s.velocity_Device_mm_per_s = Vec2{ -std::sin(w * t), std::cos(w * t) } * (radius_mm * w);
    };
    return script;
  }
};

} // namespace vtouch

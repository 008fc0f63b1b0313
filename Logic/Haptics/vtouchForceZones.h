// Yi & Hayward's force zones k(P): the force gain as a function of the pressure/z input.
#pragma once

namespace vtouch
{

/// k(P) = 0                                   for P <  zeroBelow      (zero-force zone: unattended)
///      = gain * (P - zeroBelow) / (saturateAbove - zeroBelow)  in between (proportional zone)
///      = gain                                for P >= saturateAbove  (saturation zone)
/// P is the device's normalized pressure in [0, 1]. Devices without a pressure input get the full
/// gain (usePressure = false).
struct ForceZones
{
  /// Gain k in the saturation zone, newtons per unit slope. Default 1.0 N.
  double gain_N = 1.0;
  /// Upper end of the zero-force zone, normalized pressure. Default 0.05.
  double zeroBelow = 0.05;
  /// Start of the saturation zone, normalized pressure (> zeroBelow). Default 0.5.
  double saturateAbove = 0.5;
  /// False for devices without a pressure/z input: k(P) = gain everywhere. Default true.
  bool usePressure = true;

  /// k(P) in newtons. Never throws; non-finite P gives 0.
  double gain(double pressure) const;
  /// k(P) / gain_N in [0, 1].
  double fraction(double pressure) const;
};

} // namespace vtouch

// Velocity from a fixed-size timestamped position history (CHAI3D keeps one too, we never
// allocate).
#pragma once

#include "vtouchVector.h"

#include <array>
#include <cstddef>

namespace vtouch
{

/// Least-squares slope of position against time over the newest samples of a ring buffer.
///
/// A straight-line fit over a few milliseconds rejects quantization steps far better than a
/// two-point difference while adding only half the window of lag. Samples with a timestamp that
/// does not increase are ignored (a repeated read of the same report).
class VelocityEstimator
{
public:
  /// Largest number of samples kept.
  static constexpr std::size_t kCapacity = 32;

  /// `windowSamples`: samples used for the fit (2..kCapacity), default 8.
  /// `maxWindow_s`: samples older than this relative to the newest are ignored, default 0.02 s.
  explicit VelocityEstimator(std::size_t windowSamples = 8, double maxWindow_s = 0.02);

  /// Forgets the history (velocity becomes zero).
  void reset();

  /// Adds one sample. Returns false (and ignores it) when time does not increase or is not finite.
  bool add(double timestamp_s, const Vec3& position_mm);

  /// The current estimate, mm/s; zero with fewer than two usable samples.
  Vec3 velocity_mm_per_s() const { return this->Velocity; }

  std::size_t size() const { return this->Count; }
  std::size_t windowSamples() const { return this->Window; }

private:
  void update();

  struct Sample
  {
    double t_s = 0.0;
    Vec3 p_mm;
  };
  std::array<Sample, kCapacity> Samples{};
  std::size_t Head = 0;  // index of the next write
  std::size_t Count = 0; // valid samples
  std::size_t Window = 8;
  double MaxWindow_s = 0.02;
  Vec3 Velocity;
};

} // namespace vtouch

// A small seeded random source for the phantoms: the same seed gives the same numbers on every
// platform and standard library (std::uniform_real_distribution is implementation-defined).
#pragma once

#include "vtouchVector.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace vtouch
{

class PhantomRandom
{
public:
  explicit PhantomRandom(std::uint64_t seed)
    : State(seed * 0x9E3779B97F4A7C15ull + 0x632BE59BD9B4E019ull)
  {
  }

  /// splitmix64 (Steele, Lea & Flood 2014): counter-based, so a value depends only on the seed
  /// and the draw's rank.
  static std::uint64_t mix(std::uint64_t x)
  {
    x += 0x9E3779B97F4A7C15ull;
    x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
    x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
    return x ^ (x >> 31);
  }

  /// Uniform in [0, 1).
  double uniform()
  {
    this->State += 0x9E3779B97F4A7C15ull;
    return static_cast<double>(mix(this->State) >> 11) * (1.0 / 9007199254740992.0);
  }

  double uniform(double lo, double hi) { return lo + (hi - lo) * this->uniform(); }

  /// Uniform integer in [0, n) (n > 0).
  int index(int n) { return static_cast<int>(this->uniform() * n) % n; }

  /// A unit vector uniform on the sphere.
  Vec3 direction()
  {
    const double z = this->uniform(-1.0, 1.0);
    const double phi = this->uniform(0.0, 6.283185307179586);
    const double s = std::sqrt(std::max(0.0, 1.0 - z * z));
    return { s * std::cos(phi), s * std::sin(phi), z };
  }

private:
  std::uint64_t State;
};

} // namespace vtouch

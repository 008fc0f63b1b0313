#include "vtouchRawAngiogramTestImages.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <random>

namespace vtouch::test
{
namespace
{
constexpr int kSub = 4;

void addShape(SyntheticAngiogram& g,
  std::array<double, 3> lo,
  std::array<double, 3> hi,
  double contrast,
  const std::function<bool(double, double, double)>& inside)
{
  for (std::int64_t k = std::max<std::int64_t>(0, static_cast<std::int64_t>(lo[2]) - 1);
       k <= std::min<std::int64_t>(g.dims[2] - 1, static_cast<std::int64_t>(hi[2]) + 1);
       ++k)
    for (std::int64_t j = std::max<std::int64_t>(0, static_cast<std::int64_t>(lo[1]) - 1);
         j <= std::min<std::int64_t>(g.dims[1] - 1, static_cast<std::int64_t>(hi[1]) + 1);
         ++j)
      for (std::int64_t i = std::max<std::int64_t>(0, static_cast<std::int64_t>(lo[0]) - 1);
           i <= std::min<std::int64_t>(g.dims[0] - 1, static_cast<std::int64_t>(hi[0]) + 1);
           ++i)
      {
        int n = 0;
        for (int c = 0; c < kSub; ++c)
          for (int b = 0; b < kSub; ++b)
            for (int a = 0; a < kSub; ++a)
            {
              n += inside(
                i - 0.5 + (a + 0.5) / kSub, j - 0.5 + (b + 0.5) / kSub, k - 0.5 + (c + 0.5) / kSub);
            }
        // Overlapping shapes do not add up: the brighter one wins.
        float& v = g.at(i, j, k);
        v = std::max(v, static_cast<float>(g.background + contrast * n / (kSub * kSub * kSub)));
      }
}
} // namespace

SyntheticAngiogram::SyntheticAngiogram(std::array<std::int64_t, 3> d, double bg)
  : dims(d)
  , voxels(static_cast<std::size_t>(d[0] * d[1] * d[2]), static_cast<float>(bg))
  , background(bg)
{
}

void SyntheticAngiogram::addTube(std::array<double, 3> a,
  std::array<double, 3> b,
  double r,
  double contrast)
{
  std::array<double, 3> lo, hi;
  for (int i = 0; i < 3; ++i)
  {
    lo[i] = std::min(a[i], b[i]) - r;
    hi[i] = std::max(a[i], b[i]) + r;
  }
  const double ab[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] };
  const double len2 = ab[0] * ab[0] + ab[1] * ab[1] + ab[2] * ab[2];
  addShape(*this,
    lo,
    hi,
    contrast,
    [&](double x, double y, double z)
    {
      const double ap[3] = { x - a[0], y - a[1], z - a[2] };
      const double t = std::clamp((ap[0] * ab[0] + ap[1] * ab[1] + ap[2] * ab[2]) / len2, 0.0, 1.0);
      const double dx = ap[0] - t * ab[0], dy = ap[1] - t * ab[1], dz = ap[2] - t * ab[2];
      return dx * dx + dy * dy + dz * dz <= r * r;
    });
}

void SyntheticAngiogram::addBox(std::array<double, 3> lo, std::array<double, 3> hi, double contrast)
{
  addShape(*this,
    lo,
    hi,
    contrast,
    [&](double x, double y, double z)
    { return x >= lo[0] && x <= hi[0] && y >= lo[1] && y <= hi[1] && z >= lo[2] && z <= hi[2]; });
}

void SyntheticAngiogram::addBall(std::array<double, 3> c, double r, double contrast)
{
  addShape(*this,
    { c[0] - r, c[1] - r, c[2] - r },
    { c[0] + r, c[1] + r, c[2] + r },
    contrast,
    [&](double x, double y, double z) {
      return (x - c[0]) * (x - c[0]) + (y - c[1]) * (y - c[1]) + (z - c[2]) * (z - c[2]) <= r * r;
    });
}

void SyntheticAngiogram::addNoise(double sigma, unsigned seed)
{
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, sigma);
  for (float& v : this->voxels)
  {
    v = static_cast<float>(v + noise(rng));
  }
}

} // namespace vtouch::test

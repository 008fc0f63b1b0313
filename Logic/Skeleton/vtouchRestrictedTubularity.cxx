#include "vtouchRestrictedTubularity.h"

namespace vtouch
{

std::vector<double> RestrictedTubularity::scales(const std::array<double, 3>& spacing_mm,
  const Parameters& p)
{
  const double minSpacing = std::min({ spacing_mm[0], spacing_mm[1], spacing_mm[2] });
  std::vector<double> s;
  const double first = p.sigmaMinimum_voxels * minSpacing;
  for (double sigma = first; s.empty() || sigma <= p.sigmaMaximum_mm * (1.0 + 1e-9);
       sigma *= std::sqrt(2.0))
  {
    s.push_back(sigma);
  }
  return s;
}

double RestrictedTubularity::measure(double l1, double l2, double l3, const Parameters& p)
{
  // Frangi et al. 1998, §3: a bright tube has l2, l3 strongly negative and l1 near 0.
  if (l2 >= 0.0 || l3 >= 0.0)
  {
    return 0.0;
  }
  const double ra = std::abs(l2) / std::abs(l3);                 // plate: small
  const double rb = std::abs(l1) / std::sqrt(std::abs(l2 * l3)); // blob: near 1
  const double s2 = l1 * l1 + l2 * l2 + l3 * l3;                 // structureness^2
  const double c = p.structureness;
  return (1.0 - std::exp(-ra * ra / (2.0 * p.alpha * p.alpha))) *
         std::exp(-rb * rb / (2.0 * p.beta * p.beta)) * (1.0 - std::exp(-s2 / (2.0 * c * c)));
}

std::vector<RestrictedTubularity::Level> RestrictedTubularity::levels(const std::vector<double>& sc,
  const std::array<double, 3>& spacing_mm,
  const std::array<std::int64_t, 3>& wholeDims,
  int tile_voxels)
{
  const double minSpacing = std::min({ spacing_mm[0], spacing_mm[1], spacing_mm[2] });
  const std::int64_t largest = std::max({ wholeDims[0], wholeDims[1], wholeDims[2] });
  std::vector<std::int64_t> factor(sc.size(), 1);
  for (std::size_t s = 0; s < sc.size(); ++s)
  {
    while (2 * factor[s] * minSpacing <= sc[s] && 2 * factor[s] <= largest / 4)
    {
      factor[s] *= 2;
    }
  }
  const std::int64_t t = tile_voxels;
  std::vector<Level> out;
  for (std::size_t first = 0; first < sc.size();)
  {
    Level level;
    level.factor = factor[first];
    level.first = first;
    const std::int64_t f = level.factor;
    std::size_t last = first;
    while (last < sc.size() && factor[last] == f)
    {
      level.bits |= last < 32 ? 1U << last : 0U;
      ++last;
    }
    level.last = last;
    for (int a = 0; a < 3; ++a)
    {
      level.pad[a] =
        static_cast<std::int64_t>(std::ceil(3.0 * sc[last - 1] / (f * spacing_mm[a]))) + 1;
      level.coarseDims[a] = (wholeDims[a] + f - 1) / f;
      level.tiles[a] = (level.coarseDims[a] + t - 1) / t;
    }
    out.push_back(level);
    first = last;
  }
  return out;
}

double RestrictedTubularity::siteMeasure(const float* g,
  const std::array<std::int64_t, 3>& b,
  const std::array<std::int64_t, 3>& q,
  const double spacing[3],
  double sigma,
  const Parameters& p)
{
  // Scale-normalised second derivatives (sigma^2, Lindeberg's gamma = 2, as ITK's
  // NormalizeAcrossScale) by central differences of the smoothed tile.
  const double norm = sigma * sigma;
  const auto at = [&](int dx, int dy, int dz)
  {
    const std::int64_t x = std::clamp<std::int64_t>(q[0] + dx, 0, b[0] - 1);
    const std::int64_t y = std::clamp<std::int64_t>(q[1] + dy, 0, b[1] - 1);
    const std::int64_t z = std::clamp<std::int64_t>(q[2] + dz, 0, b[2] - 1);
    return static_cast<double>(g[x + b[0] * (y + b[1] * z)]);
  };
  itk::SymmetricSecondRankTensor<double, 3> tensor;
  const double centre = at(0, 0, 0);
  const int e3[3][3] = { { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 } };
  for (unsigned a = 0; a < 3; ++a)
  {
    const double h = spacing[a];
    tensor(a, a) =
      norm *
      (at(e3[a][0], e3[a][1], e3[a][2]) - 2.0 * centre + at(-e3[a][0], -e3[a][1], -e3[a][2])) /
      (h * h);
    for (unsigned c = a + 1; c < 3; ++c)
    {
      const int u[3] = { e3[a][0] + e3[c][0], e3[a][1] + e3[c][1], e3[a][2] + e3[c][2] };
      const int v[3] = { e3[a][0] - e3[c][0], e3[a][1] - e3[c][1], e3[a][2] - e3[c][2] };
      tensor(a, c) = norm *
                     (at(u[0], u[1], u[2]) - at(v[0], v[1], v[2]) - at(-v[0], -v[1], -v[2]) +
                       at(-u[0], -u[1], -u[2])) /
                     (4.0 * spacing[a] * spacing[c]);
    }
  }
  itk::SymmetricSecondRankTensor<double, 3>::EigenValuesArrayType e;
  tensor.ComputeEigenValues(e);
  std::array<double, 3> l{ e[0], e[1], e[2] };
  std::sort(l.begin(), l.end(), [](double x, double y) { return std::abs(x) < std::abs(y); });
  return measure(l[0], l[1], l[2], p);
}

} // namespace vtouch

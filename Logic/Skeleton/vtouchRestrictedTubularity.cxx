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

} // namespace vtouch

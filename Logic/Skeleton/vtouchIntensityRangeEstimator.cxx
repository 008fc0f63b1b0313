#include "vtouchIntensityRangeEstimator.h"

#include <cstdio>

namespace vtouch
{

RobustStatistics RobustStatistics::of(std::vector<double>& values)
{
  RobustStatistics s;
  if (values.empty())
  {
    return s;
  }
  const auto at = [&values](double q)
  {
    const std::size_t k = std::min(values.size() - 1,
      static_cast<std::size_t>(q * static_cast<double>(values.size() - 1) + 0.5));
    std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(k), values.end());
    return values[k];
  };
  s.median = at(0.5);
  s.sigma = s.median - at(0.1587);
  const auto [lo, hi] = std::minmax_element(values.begin(), values.end());
  s.minimum = *lo;
  s.maximum = *hi;
  return s;
}

double RobustStatistics::otsu(const std::vector<double>& values)
{
  if (values.empty())
  {
    return 0.0;
  }
  const auto [lo, hi] = std::minmax_element(values.begin(), values.end());
  const double a = *lo, b = *hi;
  if (!(b > a))
  {
    return a;
  }
  constexpr int kBins = 256;
  std::vector<double> histogram(kBins, 0.0);
  const double width = (b - a) / kBins;
  for (double v : values)
  {
    histogram[static_cast<std::size_t>(std::min(kBins - 1, static_cast<int>((v - a) / width)))] +=
      1.0;
  }
  double total = 0.0, sum = 0.0;
  for (int i = 0; i < kBins; ++i)
  {
    total += histogram[i];
    sum += i * histogram[i];
  }
  // Otsu (1979) eq. 18: the split maximising the between-class variance.
  double w0 = 0.0, sum0 = 0.0, best = -1.0;
  int split = 0;
  for (int i = 0; i < kBins - 1; ++i)
  {
    w0 += histogram[i];
    sum0 += i * histogram[i];
    const double w1 = total - w0;
    if (w0 <= 0.0 || w1 <= 0.0)
    {
      continue;
    }
    const double m0 = sum0 / w0, m1 = (sum - sum0) / w1;
    const double between = w0 * w1 * (m0 - m1) * (m0 - m1);
    if (between > best)
    {
      best = between;
      split = i;
    }
  }
  return a + (split + 1) * width;
}

std::string IntensityRangeEstimator::backgroundMessage(double intensity)
{
  char text[200];
  std::snprintf(text,
    sizeof(text),
    "The seed is on background (intensity %g): pick a point on a vessel in the MIP.",
    intensity);
  return text;
}

std::string IntensityRangeEstimator::outsideMessage()
{
  return "The seed is outside the volume: pick a point on a vessel in the MIP.";
}

} // namespace vtouch

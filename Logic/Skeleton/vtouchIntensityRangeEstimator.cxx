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

IntensityRange IntensityRangeEstimator::fromVolumeSample(const Scan& s,
  const std::vector<double>& sample,
  const Parameters& p)
{
  IntensityRange r;
  r.upper = s.maximum;
  if (s.minimum == s.maximum)
  {
    r.message = "The volume holds a single intensity: it has no vessel-like structure.";
    return r;
  }
  if (s.twoValued)
  {
    r.binary = true;
    r.lower = r.weakLower = 0.5 * (s.minimum + s.maximum);
    r.background = s.minimum;
    r.vessel = s.maximum;
    r.ok = true;
    return r;
  }
  std::vector<double> ordered = sample;
  const RobustStatistics bg = RobustStatistics::of(ordered);
  r.background = bg.median;
  r.backgroundNoise = std::max(bg.sigma, 1e-3 * (s.maximum - s.minimum));
  const double floor = r.background + p.noiseMargin * r.backgroundNoise;
  std::vector<double> tail;
  for (double v : sample)
  {
    if (v > floor)
    {
      tail.push_back(v);
    }
  }
  // Fewer than 1e-4 of the voxels above the noise: nothing to extract.
  if (tail.size() < std::max<std::size_t>(2, sample.size() / 10000))
  {
    r.message = "The volume has no vessel-like structure: nothing is brighter than its "
                "background noise.";
    return r;
  }
  r.lower = std::max(RobustStatistics::otsu(tail), floor);
  std::vector<double> above;
  for (double v : tail)
  {
    if (v >= r.lower)
    {
      above.push_back(v);
    }
  }
  r.vessel = above.empty() ? r.lower : RobustStatistics::of(above).median;
  r.weakLower = r.lower;
  r.ok = true;
  return r;
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

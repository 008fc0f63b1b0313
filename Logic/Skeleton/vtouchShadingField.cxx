#include "vtouchShadingField.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace vtouch
{

namespace
{

/// Value at fraction q of the sorted sample (nearest rank); the sample is reordered.
double quantile(std::vector<double>& v, double q)
{
  const auto n = static_cast<std::ptrdiff_t>(v.size());
  const std::ptrdiff_t at =
    std::min<std::ptrdiff_t>(n - 1, static_cast<std::ptrdiff_t>(q * static_cast<double>(n)));
  std::nth_element(v.begin(), v.begin() + at, v.end());
  return v[static_cast<std::size_t>(at)];
}

/// Solves the symmetric system a x = b (n x n, row-major) by Gaussian elimination with partial
/// pivoting; false when singular.
bool solve(std::vector<double> a, std::vector<double> b, int n, std::vector<double>& x)
{
  for (int c = 0; c < n; ++c)
  {
    int pivot = c;
    for (int r = c + 1; r < n; ++r)
    {
      if (std::abs(a[static_cast<std::size_t>(r * n + c)]) >
          std::abs(a[static_cast<std::size_t>(pivot * n + c)]))
      {
        pivot = r;
      }
    }
    if (!(std::abs(a[static_cast<std::size_t>(pivot * n + c)]) > 1e-12))
    {
      return false;
    }
    for (int k = 0; k < n; ++k)
    {
      std::swap(a[static_cast<std::size_t>(c * n + k)], a[static_cast<std::size_t>(pivot * n + k)]);
    }
    std::swap(b[static_cast<std::size_t>(c)], b[static_cast<std::size_t>(pivot)]);
    for (int r = c + 1; r < n; ++r)
    {
      const double f =
        a[static_cast<std::size_t>(r * n + c)] / a[static_cast<std::size_t>(c * n + c)];
      for (int k = c; k < n; ++k)
      {
        a[static_cast<std::size_t>(r * n + k)] -= f * a[static_cast<std::size_t>(c * n + k)];
      }
      b[static_cast<std::size_t>(r)] -= f * b[static_cast<std::size_t>(c)];
    }
  }
  x.assign(static_cast<std::size_t>(n), 0.0);
  for (int r = n - 1; r >= 0; --r)
  {
    double s = b[static_cast<std::size_t>(r)];
    for (int k = r + 1; k < n; ++k)
    {
      s -= a[static_cast<std::size_t>(r * n + k)] * x[static_cast<std::size_t>(k)];
    }
    x[static_cast<std::size_t>(r)] = s / a[static_cast<std::size_t>(r * n + r)];
  }
  return true;
}

struct Block
{
  std::array<double, 3> centre{};
  double logLevel = 0.0; ///< log(B - m)
  double weight = 0.0;   ///< its samples
  bool kept = true;
};

} // namespace

void ShadingField::terms(const double u[3], double t[kTerms]) const
{
  t[0] = 1.0;
  t[1] = u[0];
  t[2] = u[1];
  t[3] = u[2];
  t[4] = u[0] * u[0];
  t[5] = u[1] * u[1];
  t[6] = u[2] * u[2];
  t[7] = u[0] * u[1];
  t[8] = u[0] * u[2];
  t[9] = u[1] * u[2];
}

double ShadingField::logGain(double i, double j, double k) const
{
  const double c[3] = { i, j, k };
  double u[3];
  for (int a = 0; a < 3; ++a)
  {
    u[a] = (c[a] - this->Centre[static_cast<std::size_t>(a)]) /
           this->HalfExtent[static_cast<std::size_t>(a)];
  }
  double t[kTerms];
  this->terms(u, t);
  double s = 0.0;
  for (int q = 0; q < kTerms; ++q)
  {
    s += this->Used[static_cast<std::size_t>(q)]
           ? this->Coefficients[static_cast<std::size_t>(q)] * t[q]
           : 0.0;
  }
  return s;
}

double ShadingField::gain(double i, double j, double k) const
{
  if (!this->Active)
  {
    return 1.0;
  }
  // Never beyond the span the blocks support (no extrapolation of the quadratic to the corners).
  const double l = std::min(std::log(this->SpanHigh),
    std::max(std::log(this->SpanLow), this->logGain(i, j, k) - this->Reference));
  return std::exp(l);
}

ShadingField::RowRecurrence ShadingField::rowRecurrence(std::int64_t j, std::int64_t k) const
{
  RowRecurrence r;
  if (!this->Active)
  {
    return r;
  }
  // logGain along the row: K0 + K1 u0 + C4 u0^2 with u0 = a0 + s0 i, the terms of u1 and u2 fixed.
  const double u1 = (static_cast<double>(j) - this->Centre[1]) / this->HalfExtent[1];
  const double u2 = (static_cast<double>(k) - this->Centre[2]) / this->HalfExtent[2];
  const auto& c = this->Coefficients;
  const double k0 = c[0] + c[2] * u1 + c[3] * u2 + c[5] * u1 * u1 + c[6] * u2 * u2 +
                    c[9] * u1 * u2 - this->Reference;
  const double k1 = c[1] + c[7] * u1 + c[8] * u2;
  const double s0 = 1.0 / this->HalfExtent[0], a0 = -this->Centre[0] * s0;
  const double a = k0 + k1 * a0 + c[4] * a0 * a0;
  const double b = (k1 + 2.0 * c[4] * a0) * s0;
  const double q = c[4] * s0 * s0;
  r.gain = std::exp(a);
  r.ratio = std::exp(b + q);
  r.ratioStep = std::exp(2.0 * q);
  return r;
}

void ShadingField::setReference(const std::array<std::int64_t, 3>& c)
{
  if (this->BlockCentres.empty())
  {
    return;
  }
  const double previous = this->Reference;
  this->Reference =
    this->logGain(static_cast<double>(c[0]), static_cast<double>(c[1]), static_cast<double>(c[2]));
  // The span follows the reference (the same blocks, another unit).
  this->SpanLow *= std::exp(previous - this->Reference);
  this->SpanHigh *= std::exp(previous - this->Reference);
  // The reference itself may lie beyond the outermost blocks' centres: its gain is 1.
  this->SpanLow = std::min(this->SpanLow, 1.0);
  this->SpanHigh = std::max(this->SpanHigh, 1.0);
}

std::string ShadingField::summary() const
{
  char text[240];
  if (this->Active)
  {
    std::snprintf(text,
      sizeof(text),
      "Shading corrected: the gain spans %.2f-%.2f of the seed's (or the volume's median) over "
      "%d blocks.",
      this->SpanLow,
      this->SpanHigh,
      this->BlocksUsed);
  }
  else if (!this->Why.empty())
  {
    return "No shading correction: " + this->Why + ".";
  }
  else
  {
    std::snprintf(text,
      sizeof(text),
      "No shading correction: the fitted gain spans %.2f (P95 / P5), under %.2f.",
      this->GainRatio,
      this->Gate);
  }
  return text;
}

ShadingField ShadingField::fit(const std::array<std::int64_t, 3>& wholeDims,
  std::uint64_t stride,
  std::vector<Sample> samples,
  const Parameters& p)
{
  ShadingField f;
  f.Gate = p.minimumGainRatio;
  f.Why = "too few blocks of the volume above its zero to fit a shading";
  for (std::size_t a = 0; a < 3; ++a)
  {
    f.Centre[a] = 0.5 * static_cast<double>(wholeDims[a] - 1);
    f.HalfExtent[a] = std::max(1.0, f.Centre[a]);
  }
  const std::int64_t voxels = wholeDims[0] * wholeDims[1] * wholeDims[2];
  // Values only (not a number is no evidence), inside the volume.
  samples.erase(std::remove_if(samples.begin(),
                  samples.end(),
                  [voxels](const Sample& x)
                  {
                    return !std::isfinite(x.value) ||
                           x.linear >=
                             static_cast<std::uint64_t>(std::max<std::int64_t>(0, voxels));
                  }),
    samples.end());
  if (samples.empty() || wholeDims[0] <= 0 || wholeDims[1] <= 0 || wholeDims[2] <= 0)
  {
    return f;
  }
  // The model's zero is the image's own (an MR magnitude's, a CT's stored with air at 0, the
  // phantom's). A sample of at most two values is a mask (or a single intensity): no shading.
  const double first = samples.front().value;
  double minimum = first, second = first;
  bool haveSecond = false, third = false;
  for (const Sample& x : samples)
  {
    minimum = std::min(minimum, x.value);
    if (x.value != first && !haveSecond)
    {
      second = x.value;
      haveSecond = true;
    }
    third = third || (x.value != first && x.value != second);
  }
  if (!third)
  {
    f.Why = "a binary mask or a single intensity";
    return f;
  }
  if (minimum < 0.0)
  {
    // A CT in Hounsfield units (air -1000, padding to -3024) or a subtraction image: its zero
    // is not the darkest tissue's, and the gain of a multiplicative model is not its shading.
    f.Why = "the volume has negative intensities (a CT in Hounsfield units, a subtraction), "
            "so a multiplicative shading does not apply";
    return f;
  }
  minimum = 0.0;
  f.Minimum = minimum;
  // The same sample in any order gives the same field (a single run's comes sorted).
  const auto byIndex = [](const Sample& a, const Sample& b) { return a.linear < b.linear; };
  if (!std::is_sorted(samples.begin(), samples.end(), byIndex))
  {
    std::sort(samples.begin(), samples.end(), byIndex);
  }
  // Blocks: edge e, at least minimumSamplesPerBlock lattice samples in a whole block.
  const double perVoxel = 1.0 / static_cast<double>(std::max<std::uint64_t>(1, stride));
  std::int64_t e = p.minimumBlockEdge_voxels;
  while (static_cast<double>(e * e * e) * perVoxel < static_cast<double>(p.minimumSamplesPerBlock))
  {
    ++e;
  }
  std::array<std::int64_t, 3> nb{};
  for (std::size_t a = 0; a < 3; ++a)
  {
    nb[a] = (wholeDims[a] + e - 1) / e;
  }
  std::vector<std::vector<double>> values(static_cast<std::size_t>(nb[0] * nb[1] * nb[2]));
  for (const Sample& x : samples)
  {
    const auto l = static_cast<std::int64_t>(x.linear);
    const std::int64_t i = l % wholeDims[0], j = (l / wholeDims[0]) % wholeDims[1],
                       k = l / (wholeDims[0] * wholeDims[1]);
    values[static_cast<std::size_t>((k / e * nb[1] + j / e) * nb[0] + i / e)].push_back(x.value);
  }
  std::vector<Block> blocks;
  std::vector<double> levels;
  for (std::size_t n = 0; n < values.size(); ++n)
  {
    const auto id = static_cast<std::int64_t>(n);
    std::vector<double>& v = values[n];
    if (v.size() < p.minimumSamplesPerBlock)
    {
      continue; // a thin remainder at the volume's face
    }
    const double median = quantile(v, 0.5);
    if (!(median > minimum))
    {
      continue; // the volume's zero (padding, air): not shading
    }
    Block b;
    const std::int64_t bi = id % nb[0], bj = (id / nb[0]) % nb[1], bk = id / (nb[0] * nb[1]);
    const std::int64_t idx[3] = { bi, bj, bk };
    for (std::size_t a = 0; a < 3; ++a)
    {
      const std::int64_t lo = idx[a] * e, hi = std::min(wholeDims[a], lo + e) - 1;
      b.centre[a] = 0.5 * static_cast<double>(lo + hi);
    }
    b.logLevel = std::log(median - minimum);
    b.weight = static_cast<double>(v.size());
    blocks.push_back(b);
    levels.push_back(median - minimum);
  }
  if (blocks.size() < 8)
  {
    return f;
  }
  // Blocks far below the typical one are air or lung, another tissue, not shading.
  const double typical = quantile(levels, 0.5);
  for (Block& b : blocks)
  {
    b.kept = std::exp(b.logLevel) >= 0.25 * typical;
  }
  // The terms the blocks' layers support (a linear term needs 2 layers, a quadratic 3).
  const auto layers = [&blocks](std::size_t a)
  {
    std::vector<double> c;
    for (const Block& b : blocks)
    {
      if (b.kept)
      {
        c.push_back(b.centre[a]);
      }
    }
    std::sort(c.begin(), c.end());
    return static_cast<int>(std::unique(c.begin(), c.end()) - c.begin());
  };
  const int n[3] = { layers(0), layers(1), layers(2) };
  f.Used = { true,
    n[0] >= 2,
    n[1] >= 2,
    n[2] >= 2,
    n[0] >= 3,
    n[1] >= 3,
    n[2] >= 3,
    n[0] >= 2 && n[1] >= 2,
    n[0] >= 2 && n[2] >= 2,
    n[1] >= 2 && n[2] >= 2 };
  std::vector<int> used;
  for (int q = 0; q < kTerms; ++q)
  {
    if (f.Used[static_cast<std::size_t>(q)])
    {
      used.push_back(q);
    }
  }
  const int m = static_cast<int>(used.size());
  bool fitted = false;
  for (int iteration = 0; iteration < p.fitIterations; ++iteration)
  {
    std::vector<double> a(static_cast<std::size_t>(m * m), 0.0),
      rhs(static_cast<std::size_t>(m), 0.0);
    int kept = 0;
    for (const Block& b : blocks)
    {
      if (!b.kept)
      {
        continue;
      }
      ++kept;
      double u[3], t[kTerms];
      for (std::size_t ax = 0; ax < 3; ++ax)
      {
        u[ax] = (b.centre[ax] - f.Centre[ax]) / f.HalfExtent[ax];
      }
      f.terms(u, t);
      for (int r = 0; r < m; ++r)
      {
        for (int c = 0; c < m; ++c)
        {
          a[static_cast<std::size_t>(r * m + c)] +=
            b.weight * t[used[static_cast<std::size_t>(r)]] * t[used[static_cast<std::size_t>(c)]];
        }
        rhs[static_cast<std::size_t>(r)] +=
          b.weight * t[used[static_cast<std::size_t>(r)]] * b.logLevel;
      }
    }
    std::vector<double> x;
    if (kept < 3 * m || !solve(a, rhs, m, x))
    {
      break;
    }
    f.Coefficients.fill(0.0);
    for (int r = 0; r < m; ++r)
    {
      f.Coefficients[static_cast<std::size_t>(used[static_cast<std::size_t>(r)])] =
        x[static_cast<std::size_t>(r)];
    }
    fitted = true;
    // Robust sigma of the residuals of the kept blocks; drop the far ones (of all the blocks
    // above the air's level: a block dropped once may come back), and fit again.
    std::vector<double> residuals;
    for (const Block& b : blocks)
    {
      if (b.kept)
      {
        residuals.push_back(b.logLevel - f.logGain(b.centre[0], b.centre[1], b.centre[2]));
      }
    }
    const double centre = quantile(residuals, 0.5);
    for (double& r : residuals)
    {
      r = std::abs(r - centre);
    }
    const double sigma = std::max(0.01, 1.4826 * quantile(residuals, 0.5));
    bool changed = false;
    for (Block& b : blocks)
    {
      if (std::exp(b.logLevel) < 0.25 * typical)
      {
        continue;
      }
      const bool keep = std::abs(b.logLevel - f.logGain(b.centre[0], b.centre[1], b.centre[2]) -
                                 centre) <= p.rejectSigmas * sigma;
      changed = changed || keep != b.kept;
      b.kept = keep;
    }
    if (!changed)
    {
      break;
    }
  }
  if (!fitted)
  {
    return f;
  }
  std::vector<double> fittedLog;
  for (const Block& b : blocks)
  {
    if (b.kept)
    {
      fittedLog.push_back(f.logGain(b.centre[0], b.centre[1], b.centre[2]));
      f.BlockCentres.push_back(b.centre);
    }
  }
  f.BlocksUsed = static_cast<int>(fittedLog.size());
  if (fittedLog.size() < static_cast<std::size_t>(3 * m))
  {
    return f;
  }
  f.Why.clear();
  std::vector<double> sorted = fittedLog;
  const double p5 = quantile(sorted, 0.05), p95 = quantile(sorted, 0.95);
  f.GainRatio = std::exp(p95 - p5);
  f.Reference = quantile(sorted, 0.5);
  f.SpanLow = std::exp(*std::min_element(fittedLog.begin(), fittedLog.end()) - f.Reference);
  f.SpanHigh = std::exp(*std::max_element(fittedLog.begin(), fittedLog.end()) - f.Reference);
  f.Active = f.GainRatio >= p.minimumGainRatio;
  return f;
}

} // namespace vtouch

#include "vtouchShadingField.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace vtouch
{

namespace
{

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

std::string ShadingField::sampleVerdict(std::vector<Sample>& samples,
  const std::array<std::int64_t, 3>& wholeDims)
{
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
    return "too few blocks of the volume above its zero to fit a shading";
  }
  // A sample of at most two values is a mask (or a single intensity).
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
    return "a binary mask or a single intensity";
  }
  if (minimum < 0.0)
  {
    // A CT in Hounsfield units (air -1000, padding to -3024) or a subtraction image: its zero
    // is not the darkest tissue's, and a multiplicative gain is not its shading.
    return "the volume has negative intensities (a CT in Hounsfield units, a subtraction), so "
           "a multiplicative shading does not apply";
  }
  return std::string();
}

int ShadingField::chooseTerms(const std::vector<ShadingBlock>& blocks)
{
  // A linear term needs 2 layers of kept blocks along its axis, a quadratic 3.
  const auto layers = [&blocks](std::size_t a)
  {
    std::vector<double> c;
    for (const ShadingBlock& b : blocks)
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
  this->Used = { true,
    n[0] >= 2,
    n[1] >= 2,
    n[2] >= 2,
    n[0] >= 3,
    n[1] >= 3,
    n[2] >= 3,
    n[0] >= 2 && n[1] >= 2,
    n[0] >= 2 && n[2] >= 2,
    n[1] >= 2 && n[2] >= 2 };
  return static_cast<int>(std::count(this->Used.begin(), this->Used.end(), true));
}

bool ShadingField::leastSquares(const std::vector<ShadingBlock>& blocks, int minimumBlocks)
{
  std::vector<int> used;
  for (int q = 0; q < kTerms; ++q)
  {
    if (this->Used[static_cast<std::size_t>(q)])
    {
      used.push_back(q);
    }
  }
  const int m = static_cast<int>(used.size());
  const auto at = [](int v) { return static_cast<std::size_t>(v); };
  std::vector<double> a(at(m * m), 0.0), rhs(at(m), 0.0);
  int kept = 0;
  for (const ShadingBlock& b : blocks)
  {
    if (!b.kept)
    {
      continue;
    }
    ++kept;
    double u[3], t[kTerms];
    for (std::size_t ax = 0; ax < 3; ++ax)
    {
      u[ax] = (b.centre[ax] - this->Centre[ax]) / this->HalfExtent[ax];
    }
    this->terms(u, t);
    for (int r = 0; r < m; ++r)
    {
      for (int c = 0; c < m; ++c)
      {
        a[at(r * m + c)] += b.weight * t[used[at(r)]] * t[used[at(c)]];
      }
      rhs[at(r)] += b.weight * t[used[at(r)]] * b.logLevel;
    }
  }
  std::vector<double> x;
  if (kept < minimumBlocks || !solve(a, rhs, m, x))
  {
    return false;
  }
  this->Coefficients.fill(0.0);
  for (int r = 0; r < m; ++r)
  {
    this->Coefficients[at(used[at(r)])] = x[at(r)];
  }
  return true;
}

bool ShadingField::fitRobustly(std::vector<ShadingBlock>& blocks, const Parameters& p)
{
  const int m = this->chooseTerms(blocks);
  bool fitted = false;
  for (int iteration = 0; iteration < p.fitIterations; ++iteration)
  {
    if (!this->leastSquares(blocks, 3 * m))
    {
      break;
    }
    fitted = true;
    // The kept blocks' residuals' robust sigma; the far blocks go (of every eligible block: a
    // block dropped once may come back), and the fit is redone.
    std::vector<double> residuals;
    for (const ShadingBlock& b : blocks)
    {
      if (b.kept)
      {
        residuals.push_back(b.logLevel - this->logGain(b.centre[0], b.centre[1], b.centre[2]));
      }
    }
    const double centre = ShadingBlocks::quantile(residuals, 0.5);
    for (double& r : residuals)
    {
      r = std::abs(r - centre);
    }
    const double sigma = std::max(0.01, 1.4826 * ShadingBlocks::quantile(residuals, 0.5));
    bool changed = false;
    for (ShadingBlock& b : blocks)
    {
      if (!b.eligible)
      {
        continue;
      }
      const double r = b.logLevel - this->logGain(b.centre[0], b.centre[1], b.centre[2]);
      const bool keep = std::abs(r - centre) <= p.rejectSigmas * sigma;
      changed = changed || keep != b.kept;
      b.kept = keep;
    }
    if (!changed)
    {
      break;
    }
  }
  return fitted &&
         std::count_if(
           blocks.begin(), blocks.end(), [](const ShadingBlock& b) { return b.kept; }) >= 3 * m;
}

ShadingField ShadingField::fit(const std::array<std::int64_t, 3>& wholeDims,
  std::uint64_t stride,
  std::vector<Sample> samples,
  const Parameters& p)
{
  ShadingField f;
  f.Gate = p.minimumGainRatio;
  for (std::size_t a = 0; a < 3; ++a)
  {
    f.Centre[a] = 0.5 * static_cast<double>(wholeDims[a] - 1);
    f.HalfExtent[a] = std::max(1.0, f.Centre[a]);
  }
  f.Why = sampleVerdict(samples, wholeDims);
  if (!f.Why.empty())
  {
    return f;
  }
  f.Why = "too few blocks of the volume above its zero to fit a shading";
  // The same sample in any order gives the same field (a single run's comes sorted).
  const auto byIndex = [](const Sample& a, const Sample& b) { return a.linear < b.linear; };
  if (!std::is_sorted(samples.begin(), samples.end(), byIndex))
  {
    std::sort(samples.begin(), samples.end(), byIndex);
  }
  std::vector<ShadingBlock> blocks = ShadingBlocks::levels(
    wholeDims, stride, samples, p.minimumBlockEdge_voxels, p.minimumSamplesPerBlock);
  if (blocks.size() < 8 || !f.fitRobustly(blocks, p))
  {
    return f;
  }
  f.Why.clear();
  std::vector<double> fittedLog;
  for (const ShadingBlock& b : blocks)
  {
    if (b.kept)
    {
      fittedLog.push_back(f.logGain(b.centre[0], b.centre[1], b.centre[2]));
      f.BlockCentres.push_back(b.centre);
    }
  }
  f.BlocksUsed = static_cast<int>(fittedLog.size());
  std::vector<double> sorted = fittedLog;
  const double p5 = ShadingBlocks::quantile(sorted, 0.05);
  const double p95 = ShadingBlocks::quantile(sorted, 0.95);
  f.GainRatio = std::exp(p95 - p5);
  f.Reference = ShadingBlocks::quantile(sorted, 0.5);
  f.SpanLow = std::exp(*std::min_element(fittedLog.begin(), fittedLog.end()) - f.Reference);
  f.SpanHigh = std::exp(*std::max_element(fittedLog.begin(), fittedLog.end()) - f.Reference);
  f.Active = f.GainRatio >= p.minimumGainRatio;
  return f;
}

} // namespace vtouch

#include "vtouchCurveGeometry.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace vtouch
{

namespace
{
constexpr int kMaxTerms = 5;
using Matrix = std::array<std::array<double, kMaxTerms>, kMaxTerms>;
using Column = std::array<double, kMaxTerms>;

/// Solves the n x n system a x = b (n <= 5) by Gaussian elimination with partial pivoting.
bool solve(int n, Matrix a, Column& b)
{
  for (int c = 0; c < n; ++c)
  {
    int piv = c;
    for (int r = c + 1; r < n; ++r)
    {
      if (std::abs(a[r][c]) > std::abs(a[piv][c]))
      {
        piv = r;
      }
    }
    if (std::abs(a[piv][c]) < 1e-12)
    {
      return false;
    }
    std::swap(a[c], a[piv]);
    std::swap(b[c], b[piv]);
    for (int r = c + 1; r < n; ++r)
    {
      const double f = a[r][c] / a[c][c];
      for (int k = c; k < n; ++k)
      {
        a[r][k] -= f * a[c][k];
      }
      b[r] -= f * b[c];
    }
  }
  for (int c = n - 1; c >= 0; --c)
  {
    for (int k = c + 1; k < n; ++k)
    {
      b[c] -= a[c][k] * b[k];
    }
    b[c] /= a[c][c];
  }
  return true;
}

/// Value and first three derivatives (per mm) at s[i] of a local polynomial fit.
struct LocalFit
{
  bool ok = false;
  Vec3 d[4];
};

LocalFit fitAt(const std::vector<Vec3>& p,
  const std::vector<double>& s,
  std::size_t i,
  double h,
  int maxDegree)
{
  const std::size_t n = p.size();
  // Window [s_i - h, s_i + h] by bisection on the monotone arc length.
  std::size_t a =
    static_cast<std::size_t>(std::lower_bound(s.begin(), s.end(), s[i] - h) - s.begin());
  std::size_t b =
    static_cast<std::size_t>(std::upper_bound(s.begin(), s.end(), s[i] + h) - s.begin());
  b = b > 0 ? b - 1 : 0;
  b = std::max(b, i);
  while (b - a < 6 && (a > 0 || b + 1 < n))
  {
    if (a > 0)
    {
      --a;
    }
    if (b + 1 < n && b - a < 6)
    {
      ++b;
    }
  }
  const double reach = std::max({ h, s[i] - s[a], s[b] - s[i], 1e-9 }) * 1.0001;
  const int degree =
    static_cast<int>(std::min<std::size_t>(static_cast<std::size_t>(maxDegree), (b - a) / 2 + 1));
  const int m = std::min(degree, static_cast<int>(b - a)) + 1;
  Matrix ata{};
  std::array<Column, 3> atb{};
  for (std::size_t j = a; j <= b; ++j)
  {
    const double t = (s[j] - s[i]) / reach; // in [-1, 1] for conditioning
    const double u = 1.0 - std::abs(t * t * t);
    const double w = u * u * u + 1e-6;
    double pw[kMaxTerms];
    pw[0] = 1.0;
    for (int k = 1; k < kMaxTerms; ++k)
    {
      pw[k] = pw[k - 1] * t;
    }
    const double xyz[3] = { p[j].x, p[j].y, p[j].z };
    for (int r = 0; r < m; ++r)
    {
      for (int c = 0; c < m; ++c)
      {
        ata[r][c] += w * pw[r] * pw[c];
      }
      for (int d = 0; d < 3; ++d)
      {
        atb[d][r] += w * pw[r] * xyz[d];
      }
    }
  }
  LocalFit fit;
  for (int d = 0; d < 3; ++d)
  {
    if (!solve(m, ata, atb[d]))
    {
      return fit;
    }
  }
  double scale = 1.0;
  double factorial = 1.0;
  for (int k = 0; k < 4; ++k)
  {
    if (k > 0)
    {
      scale /= reach;
      factorial *= k;
    }
    fit.d[k] = k < m ? Vec3{ atb[0][k], atb[1][k], atb[2][k] } * (scale * factorial) : Vec3{};
  }
  fit.ok = true;
  return fit;
}

/// The half width of point i's position fit: position_mm, widened toward widestPosition_mm (see
/// CurveGeometryWindows) while every point within the window bends with a radius of curvature
/// of at least the window / kBendRatio. Grows outward from i, nearest point first.
constexpr double kBendRatio = 1.2;
double positionWindow(const std::vector<double>& s,
  const std::vector<CurveSample>& samples,
  std::size_t i,
  const CurveGeometryWindows& windows)
{
  if (windows.widestPosition_mm <= windows.position_mm)
  {
    return windows.position_mm;
  }
  const std::size_t n = s.size();
  double window = 0.0;
  double curvature = samples[i].curvature;
  std::size_t a = i, b = i;
  while (a > 0 || b + 1 < n)
  {
    const double left = a > 0 ? s[i] - s[a - 1] : 1e300;
    const double right = b + 1 < n ? s[b + 1] - s[i] : 1e300;
    const bool takeLeft = left <= right;
    const double reach = takeLeft ? left : right;
    const double bend = std::max(curvature, samples[takeLeft ? a - 1 : b + 1].curvature);
    if (reach > windows.widestPosition_mm || reach * bend > kBendRatio)
    {
      break;
    }
    window = reach;
    curvature = bend;
    takeLeft ? --a : ++b;
  }
  return std::max(windows.position_mm, window);
}

Vec3 unit(const Vec3& v)
{
  const double n = v.norm();
  return n > 0.0 ? v * (1.0 / n) : Vec3{};
}
} // namespace

std::vector<CurveSample> computeCurveGeometry(const std::vector<Vec3>& points,
  const CurveGeometryWindows& windows)
{
  const std::size_t n = points.size();
  std::vector<CurveSample> out(n);
  std::vector<double> s(n, 0.0);
  for (std::size_t i = 1; i < n; ++i)
  {
    s[i] = s[i - 1] + (points[i] - points[i - 1]).norm();
  }
  for (std::size_t i = 0; i < n; ++i)
  {
    out[i].position = points[i];
    const std::size_t a = i > 0 ? i - 1 : i;
    const std::size_t b = i + 1 < n ? i + 1 : i;
    out[i].tangent = unit(points[b] - points[a]);
  }
  if (n < 3)
  {
    return out;
  }
  for (std::size_t i = 0; i < n; ++i)
  {
    const LocalFit k = fitAt(points, s, i, std::max(windows.curvature_mm, 1e-6), 4);
    if (k.ok && k.d[1].norm() > 0.0)
    {
      const double speed = k.d[1].norm();
      out[i].tangent = k.d[1] * (1.0 / speed);
      out[i].curvature = k.d[1].cross(k.d[2]).norm() / (speed * speed * speed);
    }
    const LocalFit t = fitAt(points, s, i, std::max(windows.torsion_mm, 1e-6), 3);
    if (t.ok)
    {
      const Vec3 b = t.d[1].cross(t.d[2]);
      const double b2 = b.dot(b);
      const double speed = t.d[1].norm();
      out[i].torsion = b2 > 1e-12 * std::pow(speed, 6) ? b.dot(t.d[3]) / b2 : 0.0;
    }
  }
  // Positions last: the curvature (fitted on the raw points) sets how wide each window may be.
  for (std::size_t i = 0; i < n && windows.position_mm > 0.0; ++i)
  {
    const LocalFit f = fitAt(points, s, i, positionWindow(s, out, i, windows), 3);
    if (f.ok)
    {
      out[i].position = f.d[0];
    }
  }
  return out;
}

std::vector<CurveSample> computeCurveGeometry(const std::vector<Vec3>& points,
  const CurveGeometryWindows& windows,
  std::vector<std::size_t> corners)
{
  const std::size_t n = points.size();
  corners.erase(
    std::remove_if(
      corners.begin(), corners.end(), [n](std::size_t c) { return c == 0 || c + 1 >= n; }),
    corners.end());
  std::sort(corners.begin(), corners.end());
  corners.erase(std::unique(corners.begin(), corners.end()), corners.end());
  if (corners.empty())
  {
    return computeCurveGeometry(points, windows);
  }
  std::vector<CurveSample> out(n);
  std::size_t first = 0;
  corners.push_back(n - 1);
  for (const std::size_t last : corners)
  {
    const std::vector<Vec3> piece(points.begin() + static_cast<std::ptrdiff_t>(first),
      points.begin() + static_cast<std::ptrdiff_t>(last) + 1);
    const std::vector<CurveSample> g = computeCurveGeometry(piece, windows);
    // The piece's first point is the previous piece's corner: average the two sides there.
    if (first > 0)
    {
      CurveSample& c = out[first];
      c.position = (c.position + g.front().position) * 0.5;
      const Vec3 sum = c.tangent + g.front().tangent;
      c.tangent = sum.norm() > 1e-9 ? unit(sum) : g.front().tangent;
      c.curvature = 0.5 * (c.curvature + g.front().curvature);
      c.torsion = 0.5 * (c.torsion + g.front().torsion);
    }
    else
    {
      out[first] = g.front();
    }
    std::copy(g.begin() + 1, g.end(), out.begin() + static_cast<std::ptrdiff_t>(first) + 1);
    first = last;
  }
  return out;
}

CurveGeometryWindows skeletonPathWindows(double medianRadius_mm,
  double largestSpacing_mm,
  double smoothingWindow_mm)
{
  // Windows scale with the vessel. Positions average over two diameters: the axis cannot carry
  // detail shorter than the lumen (wall bumps move the medial axis by a fraction of a radius),
  // and a cubic fit keeps the bends. Derivatives need more support.
  const double scale = std::max(2.0 * largestSpacing_mm, medianRadius_mm);
  CurveGeometryWindows windows;
  windows.position_mm = smoothingWindow_mm > 0.0 ? smoothingWindow_mm
                        : smoothingWindow_mm < 0.0
                          ? 0.0
                          : 4.0 * std::max(largestSpacing_mm, medianRadius_mm);
  // Automatic windows widen to three diameters where the path is straight enough
  // (CurveGeometryWindows::widestPosition_mm): more of the wall's bumps average out there.
  windows.widestPosition_mm =
    smoothingWindow_mm == 0.0 ? 6.0 * std::max(largestSpacing_mm, medianRadius_mm) : 0.0;
  const double base = smoothingWindow_mm > 0.0 ? smoothingWindow_mm : scale;
  windows.curvature_mm = 6.0 * base;
  windows.torsion_mm = 7.0 * base;
  return windows;
}

void applyCurveGeometry(SkeletonPath& path,
  const CurveGeometryWindows& windows,
  const std::vector<std::size_t>& corners)
{
  std::vector<Vec3> p(path.points.size());
  for (std::size_t i = 0; i < p.size(); ++i)
  {
    p[i] = path.points[i].position_World_mm;
  }
  const std::vector<CurveSample> g = computeCurveGeometry(p, windows, corners);
  for (std::size_t i = 0; i < p.size(); ++i)
  {
    SkeletonPoint& q = path.points[i];
    q.position_World_mm = g[i].position;
    q.tangent_World = g[i].tangent;
    q.curvature_per_mm = g[i].curvature;
    q.torsion_per_mm = g[i].torsion;
  }
}

} // namespace vtouch

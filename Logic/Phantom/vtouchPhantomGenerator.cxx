#include "vtouchPhantomGenerator.h"

#include "vtouchAngiogramRasterizer.h"
#include "vtouchPhantomShapes.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <thread>
#include <vector>

namespace vtouch
{
namespace
{
constexpr double kPi = 3.14159265358979323846;

/// splitmix64: a counter-based generator, so that noise is the same for a seed whatever the
/// number of threads.
std::uint64_t mix(std::uint64_t x)
{
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

double gaussianNoise(std::uint64_t seed, std::uint64_t index)
{
  const std::uint64_t a = mix(seed * 0xD1B54A32D192ED03ull + 2 * index);
  const std::uint64_t b = mix(seed * 0xD1B54A32D192ED03ull + 2 * index + 1);
  const double u1 = (static_cast<double>(a >> 11) + 1.0) * (1.0 / 9007199254740993.0);
  const double u2 = static_cast<double>(b >> 11) * (1.0 / 9007199254740992.0);
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * kPi * u2);
}

double segmentParameter(const Vec3& p, const Vec3& a, const Vec3& b)
{
  const Vec3 ab = b - a;
  const double len2 = ab.dot(ab);
  return len2 > 0.0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
}

/// One straight piece of the rasterized centerline (a chord of ~2 voxels of the fine sampling).
struct Chord
{
  Vec3 a;
  Vec3 b;
  double radiusA_mm = 0.0;
  double radiusB_mm = 0.0;
  double extendA_mm = 0.0; ///< how far beyond a to rasterize (bends); 0 at an open end
  double extendB_mm = 0.0;
  bool capA = false; ///< a is an open end: rasterize a full ball there
  bool capB = false;
  int path = 0;
};

/// Wall roughness: three seeded plane waves with a wavelength of 2.5 radii.
struct Roughness
{
  double amplitude = 0.0;
  Vec3 k[3];
  double phase[3] = { 0, 0, 0 };

  Roughness(double amp, double radius_mm, std::uint32_t seed)
    : amplitude(amp)
  {
    const double wave = 2.0 * kPi / (2.5 * std::max(radius_mm, 1e-6));
    for (int i = 0; i < 3; ++i)
    {
      const double u = static_cast<double>(mix(seed + 17u * i) >> 11) / 9007199254740992.0;
      const double v = static_cast<double>(mix(seed + 17u * i + 7) >> 11) / 9007199254740992.0;
      const double theta = std::acos(2 * u - 1);
      const double phi = 2 * kPi * v;
      k[i] =
        Vec3{ std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta) } *
        wave;
      phase[i] = 2 * kPi * static_cast<double>(mix(seed + 31u * i) >> 11) / 9007199254740992.0;
    }
  }

  double factor(const Vec3& p) const
  {
    if (amplitude == 0.0)
    {
      return 1.0;
    }
    double s = 0.0;
    for (int i = 0; i < 3; ++i)
    {
      s += std::sin(k[i].dot(p) + phase[i]);
    }
    return 1.0 + amplitude * s / 3.0;
  }
};

} // namespace

PhantomGenerator::PhantomGenerator(const PhantomSpec& spec)
  : Spec(spec)
  , Error(spec.validate())
{
  if (this->Error.empty())
  {
    const double minSpacing =
      std::min({ spec.spacing_mm[0], spec.spacing_mm[1], spec.spacing_mm[2] });
    this->Centerline = buildPhantomCenterline(spec, 0.25 * minSpacing);
  }
}

namespace
{
template<typename Visit>
void forEachFineSegment(const QSkeleton& s, Visit visit)
{
  for (const SkeletonPath& path : s.paths)
  {
    const auto& pts = path.points;
    for (std::size_t i = 0; i + 1 < pts.size(); ++i)
    {
      visit(pts[i], pts[i + 1]);
    }
    // A path whose tail joins its own head is a closed ring: close the polyline.
    if (path.tail.junction >= 0)
    {
      const Junction& j = s.junctions[path.tail.junction];
      if (j.parentPath == path.id && j.parentPoint == 0 && pts.size() > 1)
      {
        visit(pts.back(), pts.front());
      }
    }
  }
}
} // namespace

double PhantomGenerator::totalLength_mm() const
{
  double length = 0.0;
  forEachFineSegment(this->Centerline,
    [&](const SkeletonPoint& a, const SkeletonPoint& b)
    { length += (b.position_World_mm - a.position_World_mm).norm(); });
  return length;
}

double PhantomGenerator::distanceToCenterline_mm(const Vec3& p, double* radius_mm) const
{
  double best = std::numeric_limits<double>::infinity();
  double bestRadius = 0.0;
  forEachFineSegment(this->Centerline,
    [&](const SkeletonPoint& a, const SkeletonPoint& b)
    {
      const double t = segmentParameter(p, a.position_World_mm, b.position_World_mm);
      const Vec3 q = a.position_World_mm + (b.position_World_mm - a.position_World_mm) * t;
      const double d = (p - q).norm();
      if (d < best)
      {
        best = d;
        bestRadius = a.radius_mm + (b.radius_mm - a.radius_mm) * t;
      }
    });
  if (radius_mm)
  {
    *radius_mm = bestRadius;
  }
  return best;
}

namespace
{
/// Everything the rasterizer needs, computed once per fill().
class Rasterizer
{
public:
  Rasterizer(const PhantomSpec& spec, const QSkeleton& centerline)
    : Spec(spec)
  {
    this->MinSpacing = std::min({ spec.spacing_mm[0], spec.spacing_mm[1], spec.spacing_mm[2] });
    this->EdgeWidth_mm = 0.5 * this->MinSpacing;
    this->buildChords(centerline);
  }

  /// Profile value in [0, 1] at distance d from a centerline of radius r.
  double profile(double d, double r) const
  {
    if (this->Spec.profile == PhantomSpec::Profile::Flat)
    {
      return 0.5 * std::erfc((d - r) / this->EdgeWidth_mm);
    }
    const double q = d / r;
    return std::exp2(-q * q);
  }

  /// Distance beyond which the profile is negligible (< 2e-4 of the contrast).
  double cutoff(double r) const
  {
    return this->Spec.profile == PhantomSpec::Profile::Flat ? r + 3.0 * this->EdgeWidth_mm
                                                            : 3.5 * r;
  }

  /// Fills the profile buffer for slices [k0, k1) with max-combined vessel profiles.
  void splat(float* profileBuffer, int k0, int k1) const
  {
    if (this->Spec.shape == PhantomShape::Column)
    {
      this->splatColumn(profileBuffer, k0, k1);
      return;
    }
    for (const Chord& c : this->Chords)
    {
      this->splatChord(c, profileBuffer, k0, k1);
    }
  }

private:
  void buildChords(const QSkeleton& s)
  {
    const int stride = std::max(1, static_cast<int>(std::lround(2.0 / 0.25)));
    for (const SkeletonPath& path : s.paths)
    {
      const auto& pts = path.points;
      const bool closed = path.tail.junction >= 0 &&
                          s.junctions[path.tail.junction].parentPath == path.id &&
                          s.junctions[path.tail.junction].parentPoint == 0;
      std::vector<int> knots;
      for (int i = 0; i < static_cast<int>(pts.size()); i += stride)
      {
        knots.push_back(i);
      }
      if (knots.back() != static_cast<int>(pts.size()) - 1)
      {
        knots.push_back(static_cast<int>(pts.size()) - 1);
      }
      if (closed)
      {
        knots.push_back(0);
      }
      const std::size_t first = this->Chords.size();
      for (std::size_t k = 0; k + 1 < knots.size(); ++k)
      {
        Chord c;
        c.a = pts[knots[k]].position_World_mm;
        c.b = pts[knots[k + 1]].position_World_mm;
        c.radiusA_mm = pts[knots[k]].radius_mm;
        c.radiusB_mm = pts[knots[k + 1]].radius_mm;
        c.path = path.id;
        this->Chords.push_back(c);
      }
      const std::size_t last = this->Chords.size();
      // Extend each chord past its inner knots far enough to close the wedge on the outside of
      // a bend: cutoff * sin(bend angle) plus a voxel.
      for (std::size_t i = first; i < last; ++i)
      {
        Chord& c = this->Chords[i];
        const double margin =
          this->cutoff(std::max(c.radiusA_mm, c.radiusB_mm)) * (1.0 + this->Spec.wallRoughness);
        auto bend = [&](const Chord& other)
        {
          const Vec3 u = c.b - c.a;
          const Vec3 v = other.b - other.a;
          const double cosAngle = u.dot(v) / std::max(1e-12, u.norm() * v.norm());
          const double sinAngle = std::sqrt(std::max(0.0, 1.0 - cosAngle * cosAngle));
          return margin * sinAngle + this->MinSpacing;
        };
        const bool hasPrevious = i > first || closed;
        const bool hasNext = i + 1 < last || closed;
        if (hasPrevious)
        {
          c.extendA_mm = bend(this->Chords[i > first ? i - 1 : last - 1]);
        }
        if (hasNext)
        {
          c.extendB_mm = bend(this->Chords[i + 1 < last ? i + 1 : first]);
        }
      }
      if (!closed && last > first)
      {
        // Every open end gets a full ball: a rounded cap at a free end (the intensity is a
        // function of the distance to the centerline, so vessels end in a hemisphere), and no
        // notch where a vessel joins another.
        this->Chords[first].capA = true;
        this->Chords[last - 1].capB = true;
      }
      this->PathRoughness.emplace_back(this->Spec.wallRoughness,
        pts.front().radius_mm,
        this->Spec.seed * 7919u + static_cast<std::uint32_t>(path.id));
    }
    // Parents of junctions get balls too (a child may join in the middle of a parent).
    for (const Junction& j : s.junctions)
    {
      if (j.parentPath != j.childPath)
      {
        const SkeletonPoint& p = s.paths[j.parentPath].points[j.parentPoint];
        Chord ball;
        ball.a = ball.b = p.position_World_mm;
        ball.radiusA_mm = ball.radiusB_mm = p.radius_mm;
        ball.capA = true;
        ball.path = j.parentPath;
        this->Chords.push_back(ball);
      }
    }
  }

  void visitVoxel(const Chord& c, const Vec3& p, float& value, double t) const
  {
    const Vec3 q = c.a + (c.b - c.a) * t;
    const double d = (p - q).norm();
    const double r =
      (c.radiusA_mm + (c.radiusB_mm - c.radiusA_mm) * t) * this->PathRoughness[c.path].factor(p);
    const float v = static_cast<float>(this->profile(d, r));
    value = std::max(value, v);
  }

  void splatBall(const Chord& c, const Vec3& center, double radius, float* out, int k0, int k1)
    const
  {
    const double cut = this->cutoff(radius) * (1.0 + this->Spec.wallRoughness);
    int lo[3];
    int hi[3];
    for (int a = 0; a < 3; ++a)
    {
      const double cc = (&center.x)[a];
      lo[a] = std::max(0,
        static_cast<int>(
          std::floor((cc - cut - this->Spec.origin_mm[a]) / this->Spec.spacing_mm[a])));
      hi[a] = std::min(this->Spec.dimensions[a] - 1,
        static_cast<int>(
          std::ceil((cc + cut - this->Spec.origin_mm[a]) / this->Spec.spacing_mm[a])));
    }
    lo[2] = std::max(lo[2], k0);
    hi[2] = std::min(hi[2], k1 - 1);
    const auto& d = this->Spec.dimensions;
    for (int k = lo[2]; k <= hi[2]; ++k)
      for (int j = lo[1]; j <= hi[1]; ++j)
        for (int i = lo[0]; i <= hi[0]; ++i)
        {
          const Vec3 p = this->world(i, j, k);
          const double t = segmentParameter(p, c.a, c.b);
          this->visitVoxel(c, p, out[(static_cast<std::size_t>(k) * d[1] + j) * d[0] + i], t);
        }
  }

  Vec3 world(int i, int j, int k) const
  {
    const auto& o = this->Spec.origin_mm;
    const auto& s = this->Spec.spacing_mm;
    return { o[0] + i * s[0], o[1] + j * s[1], o[2] + k * s[2] };
  }

  /// Visits the voxels whose projection on the chord's line falls in [-extendA, L + extendB] and
  /// whose distance to the line is below the cutoff: columns along the chord's dominant axis.
  void splatChord(const Chord& c, float* out, int k0, int k1) const
  {
    if (c.capA)
    {
      this->splatBall(c, c.a, c.radiusA_mm, out, k0, k1);
    }
    if (c.capB)
    {
      this->splatBall(c, c.b, c.radiusB_mm, out, k0, k1);
    }
    const Vec3 ab = c.b - c.a;
    const double length = ab.norm();
    if (length <= 0.0)
    {
      return;
    }
    const Vec3 u = ab * (1.0 / length);
    const double cut =
      this->cutoff(std::max(c.radiusA_mm, c.radiusB_mm)) * (1.0 + this->Spec.wallRoughness);
    const double sMin = -c.extendA_mm;
    const double sMax = length + c.extendB_mm;

    // Dominant axis w (largest |u| in index units), the other two (a, b) span the columns.
    const double* uArr = &u.x;
    int w = 0;
    for (int axis = 1; axis < 3; ++axis)
    {
      if (std::abs(uArr[axis]) * this->Spec.spacing_mm[w] >
          std::abs(uArr[w]) * this->Spec.spacing_mm[axis])
      {
        w = axis;
      }
    }
    const int a = (w + 1) % 3;
    const int b = (w + 2) % 3;
    const double* A = &c.a.x;
    const double* B = &c.b.x;
    auto indexRange = [&](int axis, int& lo, int& hi)
    {
      const double reach = cut + std::max(c.extendA_mm, c.extendB_mm);
      const double mn = std::min(A[axis], B[axis]) - reach;
      const double mx = std::max(A[axis], B[axis]) + reach;
      lo = std::max(0,
        static_cast<int>(
          std::floor((mn - this->Spec.origin_mm[axis]) / this->Spec.spacing_mm[axis])));
      hi = std::min(this->Spec.dimensions[axis] - 1,
        static_cast<int>(
          std::ceil((mx - this->Spec.origin_mm[axis]) / this->Spec.spacing_mm[axis])));
    };
    int loA, hiA, loB, hiB;
    indexRange(a, loA, hiA);
    indexRange(b, loB, hiB);
    int wLimitLo = 0;
    int wLimitHi = this->Spec.dimensions[w] - 1;
    if (w == 2)
    {
      wLimitLo = std::max(wLimitLo, k0);
      wLimitHi = std::min(wLimitHi, k1 - 1);
    }
    if (a == 2)
    {
      loA = std::max(loA, k0);
      hiA = std::min(hiA, k1 - 1);
    }
    if (b == 2)
    {
      loB = std::max(loB, k0);
      hiB = std::min(hiB, k1 - 1);
    }
    const auto& d = this->Spec.dimensions;
    const double cut2 = cut * cut;
    int idx[3];
    for (idx[b] = loB; idx[b] <= hiB; ++idx[b])
    {
      for (idx[a] = loA; idx[a] <= hiA; ++idx[a])
      {
        // (p - A).u in [sMin, sMax] solved for the coordinate along w.
        const double pa = this->Spec.origin_mm[a] + idx[a] * this->Spec.spacing_mm[a];
        const double pb = this->Spec.origin_mm[b] + idx[b] * this->Spec.spacing_mm[b];
        const double rest = (pa - A[a]) * uArr[a] + (pb - A[b]) * uArr[b];
        double w0 = A[w] + (sMin - rest) / uArr[w];
        double w1 = A[w] + (sMax - rest) / uArr[w];
        if (w0 > w1)
        {
          std::swap(w0, w1);
        }
        const int lo = std::max(wLimitLo,
          static_cast<int>(std::ceil((w0 - this->Spec.origin_mm[w]) / this->Spec.spacing_mm[w])));
        const int hi = std::min(wLimitHi,
          static_cast<int>(std::floor((w1 - this->Spec.origin_mm[w]) / this->Spec.spacing_mm[w])));
        for (idx[w] = lo; idx[w] <= hi; ++idx[w])
        {
          const Vec3 p = this->world(idx[0], idx[1], idx[2]);
          const Vec3 ap = p - c.a;
          const double s = ap.dot(u);
          const Vec3 perp = ap - u * s;
          if (perp.dot(perp) > cut2)
          {
            continue;
          }
          const double t = std::clamp(s / length, 0.0, 1.0);
          this->visitVoxel(
            c, p, out[(static_cast<std::size_t>(idx[2]) * d[1] + idx[1]) * d[0] + idx[0]], t);
        }
      }
    }
  }

  void splatColumn(float* out, int k0, int k1) const
  {
    const auto& d = this->Spec.dimensions;
    for (int k = k0; k < k1; ++k)
      for (int j = d[1] / 2 - 2; j < d[1] / 2 + 2; ++j)
        for (int i = d[0] / 2 - 2; i < d[0] / 2 + 2; ++i)
        {
          out[(static_cast<std::size_t>(k) * d[1] + j) * d[0] + i] = 1.0f;
        }
  }

  const PhantomSpec& Spec;
  double MinSpacing = 1.0;
  double EdgeWidth_mm = 0.5;
  std::vector<Chord> Chords;
  std::vector<Roughness> PathRoughness;
};

template<typename T>
T toVoxel(double v)
{
  if constexpr (std::is_integral_v<T>)
  {
    return static_cast<T>(
      std::clamp(std::lround(v), 0L, static_cast<long>(std::numeric_limits<T>::max())));
  }
  else
  {
    return static_cast<T>(v);
  }
}

} // namespace

template<typename T>
bool PhantomGenerator::fillT(T* voxels, const std::function<bool(double)>& progress) const
{
  if (!this->ok() || voxels == nullptr)
  {
    return false;
  }
  const PhantomSpec& spec = this->Spec;
  const auto& d = spec.dimensions;
  const std::size_t slice = static_cast<std::size_t>(d[0]) * d[1];
  // The raw angiogram has its own partial-volume rasterizer (tissue, clutter, bias, noise).
  std::optional<AngiogramRasterizer> angiogram;
  std::optional<Rasterizer> rasterizer;
  if (spec.shape == PhantomShape::RawAngiogram)
  {
    angiogram.emplace(spec, this->Centerline);
  }
  else
  {
    rasterizer.emplace(spec, this->Centerline);
  }

  // Workers accumulate the profile in float slabs and turn them into intensities + noise; the
  // calling thread only reports progress, so callbacks (e.g. VTK's UpdateProgress) stay on it.
  const int threads = std::clamp(static_cast<int>(std::thread::hardware_concurrency()), 1, 8);
  const int slabDepth = std::max(1, std::min(16, (d[2] + threads - 1) / threads));
  const int slabCount = (d[2] + slabDepth - 1) / slabDepth;
  std::atomic<int> nextSlab{ 0 };
  std::atomic<int> doneSlabs{ 0 };
  std::atomic<bool> aborted{ false };
  if (progress && !progress(0.0))
  {
    return false;
  }

  auto work = [&]()
  {
    std::vector<float> profile(slice * slabDepth);
    for (;;)
    {
      const int s = nextSlab.fetch_add(1);
      if (s >= slabCount || aborted.load())
      {
        return;
      }
      const int k0 = s * slabDepth;
      const int k1 = std::min(d[2], k0 + slabDepth);
      std::fill(profile.begin(), profile.end(), 0.0f);
      float* base = profile.data() - static_cast<std::size_t>(k0) * slice;
      if (angiogram)
      {
        angiogram->fillSlab(base, k0, k1);
        for (std::size_t n = static_cast<std::size_t>(k0) * slice;
             n < static_cast<std::size_t>(k1) * slice;
             ++n)
        {
          voxels[n] = toVoxel<T>(base[n]);
        }
        doneSlabs.fetch_add(1);
        continue;
      }
      rasterizer->splat(base, k0, k1);
      const double contrast = spec.peakIntensity - spec.backgroundIntensity;
      for (std::size_t n = static_cast<std::size_t>(k0) * slice;
           n < static_cast<std::size_t>(k1) * slice;
           ++n)
      {
        double v = spec.backgroundIntensity + contrast * base[n];
        if (spec.noiseStdDev > 0.0)
        {
          v += spec.noiseStdDev * gaussianNoise(spec.seed, n);
        }
        voxels[n] = toVoxel<T>(v);
      }
      doneSlabs.fetch_add(1);
    }
  };
  std::vector<std::thread> workers;
  for (int t = 0; t < threads; ++t)
  {
    workers.emplace_back(work);
  }
  while (doneSlabs.load() < slabCount && !aborted.load())
  {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    const int done = doneSlabs.load();
    if (progress && done < slabCount && !progress(static_cast<double>(done) / slabCount))
    {
      aborted.store(true);
    }
  }
  for (std::thread& t : workers)
  {
    t.join();
  }
  if (!aborted.load() && progress)
  {
    progress(1.0);
  }
  return !aborted.load();
}

bool PhantomGenerator::fill(float* voxels, const std::function<bool(double)>& progress) const
{
  return this->fillT(voxels, progress);
}

bool PhantomGenerator::fill(std::uint16_t* voxels,
  const std::function<bool(double)>& progress) const
{
  return this->fillT(voxels, progress);
}

double PhantomGenerator::intensityAt(const Vec3& p) const
{
  if (!this->ok())
  {
    return 0.0;
  }
  if (this->Spec.shape == PhantomShape::RawAngiogram)
  {
    // Noise-, bias- and texture-free: the vessel intensity inside a vessel, tissue outside.
    double radius = 0.0;
    const double d = this->distanceToCenterline_mm(p, &radius);
    return d <= radius ? this->Spec.peakIntensity : this->Spec.tissueIntensity;
  }
  // The union of the vessels: the brightest of the per-vessel profiles (as fill() does), not the
  // profile of the nearest centerline, which differ where vessels of different radii meet.
  const double minSpacing =
    std::min({ this->Spec.spacing_mm[0], this->Spec.spacing_mm[1], this->Spec.spacing_mm[2] });
  const bool flat = this->Spec.profile == PhantomSpec::Profile::Flat;
  double profile = 0.0;
  forEachFineSegment(this->Centerline,
    [&](const SkeletonPoint& a, const SkeletonPoint& b)
    {
      const double t = segmentParameter(p, a.position_World_mm, b.position_World_mm);
      const Vec3 q = a.position_World_mm + (b.position_World_mm - a.position_World_mm) * t;
      const double d = (p - q).norm();
      const double r = a.radius_mm + (b.radius_mm - a.radius_mm) * t;
      const double value =
        flat ? 0.5 * std::erfc((d - r) / (0.5 * minSpacing)) : std::exp2(-(d / r) * (d / r));
      profile = std::max(profile, value);
    });
  return this->Spec.backgroundIntensity +
         (this->Spec.peakIntensity - this->Spec.backgroundIntensity) * profile;
}

} // namespace vtouch

#include "vtouchAngiogramRasterizer.h"

#include "vtouchPhantomRandom.h"

#include <algorithm>
#include <bitset>
#include <cmath>

namespace vtouch
{
namespace
{
constexpr double kPi = 3.14159265358979323846;
constexpr std::uint64_t kFull = ~0ull;

double gaussian(std::uint64_t seed, std::uint64_t index, double& second)
{
  const std::uint64_t a = PhantomRandom::mix(seed * 0xD1B54A32D192ED03ull + 2 * index);
  const std::uint64_t b = PhantomRandom::mix(seed * 0xD1B54A32D192ED03ull + 2 * index + 1);
  const double u1 = (static_cast<double>(a >> 11) + 1.0) * (1.0 / 9007199254740993.0);
  const double u2 = static_cast<double>(b >> 11) * (1.0 / 9007199254740992.0);
  const double m = std::sqrt(-2.0 * std::log(u1));
  second = m * std::sin(2.0 * kPi * u2);
  return m * std::cos(2.0 * kPi * u2);
}

double distanceToSegment(const Vec3& p, const Vec3& a, const Vec3& b)
{
  const Vec3 ab = b - a;
  const double len2 = ab.dot(ab);
  const double t = len2 > 0.0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (p - (a + ab * t)).norm();
}
} // namespace

AngiogramRasterizer::AngiogramRasterizer(const PhantomSpec& spec, const QSkeleton& tree)
  : Spec(spec)
  , Clutter(spec, tree)
{
  const auto& s = spec.spacing_mm;
  this->HalfDiagonal_mm = 0.5 * std::sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
  int n = 0;
  for (int c = 0; c < 4; ++c)
    for (int b = 0; b < 4; ++b)
      for (int a = 0; a < 4; ++a)
      {
        this->SubOffsets[n++] = {
          (a - 1.5) * 0.25 * s[0], (b - 1.5) * 0.25 * s[1], (c - 1.5) * 0.25 * s[2]
        };
      }
  // Capsules one voxel long (chord error of a curve bent to 8 radii: below 0.02 voxel).
  const double voxel = std::min({ s[0], s[1], s[2] });
  for (const SkeletonPath& path : tree.paths)
  {
    const auto& pts = path.points;
    std::size_t i = 0;
    while (i + 1 < pts.size())
    {
      std::size_t j = i + 1;
      while (j + 1 < pts.size() &&
             (pts[j + 1].position_World_mm - pts[i].position_World_mm).norm() <= voxel)
      {
        ++j;
      }
      Capsule c;
      c.a = pts[i].position_World_mm;
      c.b = pts[j].position_World_mm;
      c.radius_mm = std::max(pts[i].radius_mm, pts[j].radius_mm);
      const double reach = c.radius_mm + this->HalfDiagonal_mm;
      c.zLo_mm = std::min(c.a.z, c.b.z) - reach;
      c.zHi_mm = std::max(c.a.z, c.b.z) + reach;
      this->Capsules.push_back(c);
      i = j;
    }
  }
  this->Bias = this->makeField(0xB1A5u + 31ull * spec.seed, 1.0, 2.0);
  this->Texture = this->makeField(0x7E87u + 37ull * spec.seed, 0.3, 0.6);
}

AngiogramRasterizer::SmoothField AngiogramRasterizer::makeField(std::uint64_t seed,
  double minWavelength,
  double maxWavelength) const
{
  PhantomRandom random(seed);
  SmoothField f;
  for (int term = 0; term < 3; ++term)
  {
    for (int axis = 0; axis < 3; ++axis)
    {
      const int n = this->Spec.dimensions[axis];
      const double extent = std::max(1.0, (n - 1) * this->Spec.spacing_mm[axis]);
      const double k = 2.0 * kPi / (random.uniform(minWavelength, maxWavelength) * extent);
      const double phase = random.uniform(0.0, 2.0 * kPi);
      auto& t = f.table[term * 3 + axis];
      t.resize(n);
      for (int i = 0; i < n; ++i)
      {
        t[i] = static_cast<float>(std::cos(k * i * this->Spec.spacing_mm[axis] + phase));
      }
    }
  }
  return f;
}

double AngiogramRasterizer::SmoothField::at(int i, int j, int k) const
{
  double s = 0.0;
  for (int term = 0; term < 3; ++term)
  {
    s += static_cast<double>(this->table[term * 3][i]) * this->table[term * 3 + 1][j] *
         this->table[term * 3 + 2][k];
  }
  return s / 3.0;
}

Vec3 AngiogramRasterizer::world(int i, int j, int k) const
{
  const auto& o = this->Spec.origin_mm;
  const auto& s = this->Spec.spacing_mm;
  return { o[0] + i * s[0], o[1] + j * s[1], o[2] + k * s[2] };
}

void AngiogramRasterizer::rasterizeCapsule(const Capsule& c,
  std::vector<std::uint64_t>& bits,
  int k0,
  int k1) const
{
  const auto& d = this->Spec.dimensions;
  const auto& o = this->Spec.origin_mm;
  const auto& s = this->Spec.spacing_mm;
  const double reach = c.radius_mm + this->HalfDiagonal_mm;
  int lo[3];
  int hi[3];
  const double* A = &c.a.x;
  const double* B = &c.b.x;
  for (int a = 0; a < 3; ++a)
  {
    lo[a] = std::max(0, static_cast<int>(std::ceil((std::min(A[a], B[a]) - reach - o[a]) / s[a])));
    hi[a] = std::min(
      d[a] - 1, static_cast<int>(std::floor((std::max(A[a], B[a]) + reach - o[a]) / s[a])));
  }
  lo[2] = std::max(lo[2], k0);
  hi[2] = std::min(hi[2], k1 - 1);
  const double r = c.radius_mm;
  const double h = this->HalfDiagonal_mm;
  for (int k = lo[2]; k <= hi[2]; ++k)
    for (int j = lo[1]; j <= hi[1]; ++j)
      for (int i = lo[0]; i <= hi[0]; ++i)
      {
        std::uint64_t& word = bits[(static_cast<std::size_t>(k - k0) * d[1] + j) * d[0] + i];
        if (word == kFull)
        {
          continue;
        }
        const Vec3 p = this->world(i, j, k);
        const double dist = distanceToSegment(p, c.a, c.b);
        if (dist <= r - h)
        {
          word = kFull;
        }
        else if (dist < r + h)
        {
          for (int n = 0; n < 64; ++n)
          {
            if (!(word >> n & 1u) && distanceToSegment(p + this->SubOffsets[n], c.a, c.b) <= r)
            {
              word |= 1ull << n;
            }
          }
        }
      }
}

void AngiogramRasterizer::rasterizeObject(const PhantomClutter::Object& ob,
  std::vector<std::uint64_t>& bits,
  int k0,
  int k1) const
{
  const auto& d = this->Spec.dimensions;
  const auto& o = this->Spec.origin_mm;
  const auto& s = this->Spec.spacing_mm;
  Vec3 boxLo, boxHi;
  ob.bounds(boxLo, boxHi);
  const double* L = &boxLo.x;
  const double* H = &boxHi.x;
  int lo[3];
  int hi[3];
  for (int a = 0; a < 3; ++a)
  {
    lo[a] = std::max(0, static_cast<int>(std::ceil((L[a] - 0.5 * s[a] - o[a]) / s[a])));
    hi[a] = std::min(d[a] - 1, static_cast<int>(std::floor((H[a] + 0.5 * s[a] - o[a]) / s[a])));
  }
  lo[2] = std::max(lo[2], k0);
  hi[2] = std::min(hi[2], k1 - 1);
  const double h = this->HalfDiagonal_mm;
  for (int k = lo[2]; k <= hi[2]; ++k)
    for (int j = lo[1]; j <= hi[1]; ++j)
      for (int i = lo[0]; i <= hi[0]; ++i)
      {
        std::uint64_t& word = bits[(static_cast<std::size_t>(k - k0) * d[1] + j) * d[0] + i];
        if (word == kFull)
        {
          continue;
        }
        const Vec3 p = this->world(i, j, k);
        const double bound = ob.signedDistanceBound_mm(p);
        if (bound <= -h)
        {
          word = kFull;
        }
        else if (bound < h)
        {
          for (int n = 0; n < 64; ++n)
          {
            if (!(word >> n & 1u) && ob.contains(p + this->SubOffsets[n]))
            {
              word |= 1ull << n;
            }
          }
        }
      }
}

void AngiogramRasterizer::occupancy(std::vector<std::uint64_t>& bits, int k0, int k1) const
{
  const auto& d = this->Spec.dimensions;
  bits.assign(static_cast<std::size_t>(d[0]) * d[1] * (k1 - k0), 0);
  const double zLo = this->Spec.origin_mm[2] + (k0 - 0.5) * this->Spec.spacing_mm[2];
  const double zHi = this->Spec.origin_mm[2] + (k1 - 0.5) * this->Spec.spacing_mm[2];
  for (const Capsule& c : this->Capsules)
  {
    if (c.zHi_mm >= zLo && c.zLo_mm <= zHi)
    {
      this->rasterizeCapsule(c, bits, k0, k1);
    }
  }
  for (const PhantomClutter::Object& ob : this->Clutter.objects())
  {
    this->rasterizeObject(ob, bits, k0, k1);
  }
}

void AngiogramRasterizer::fractions(float* out, int k0, int k1) const
{
  std::vector<std::uint64_t> bits;
  this->occupancy(bits, k0, k1);
  const std::size_t first =
    static_cast<std::size_t>(k0) * this->Spec.dimensions[0] * this->Spec.dimensions[1];
  for (std::size_t n = 0; n < bits.size(); ++n)
  {
    out[first + n] = static_cast<float>(std::bitset<64>(bits[n]).count()) / 64.0f;
  }
}

void AngiogramRasterizer::fillSlab(float* out, int k0, int k1) const
{
  std::vector<std::uint64_t> bits;
  this->occupancy(bits, k0, k1);
  const PhantomSpec& spec = this->Spec;
  const auto& d = spec.dimensions;
  const double sigma = spec.noiseStdDev;
  const bool rician = spec.noiseModel == PhantomSpec::NoiseModel::Rician;
  const std::uint64_t noiseSeed = PhantomRandom::mix(0x401Eu + spec.seed);
  std::size_t n = 0;
  for (int k = k0; k < k1; ++k)
    for (int j = 0; j < d[1]; ++j)
      for (int i = 0; i < d[0]; ++i, ++n)
      {
        const double f = static_cast<double>(std::bitset<64>(bits[n]).count()) / 64.0;
        const double base = spec.tissueIntensity * (1.0 + 0.1 * this->Texture.at(i, j, k));
        const double bias = 1.0 + spec.biasAmplitude * this->Bias.at(i, j, k);
        double v = bias * (base + (spec.peakIntensity - base) * f);
        if (sigma > 0.0)
        {
          const std::size_t index = (static_cast<std::size_t>(k) * d[1] + j) * d[0] + i;
          double second = 0.0;
          const double first = gaussian(noiseSeed, index, second);
          v = rician ? std::hypot(v + sigma * first, sigma * second) : v + sigma * first;
        }
        out[(static_cast<std::size_t>(k) * d[1] + j) * d[0] + i] = static_cast<float>(v);
      }
}

} // namespace vtouch

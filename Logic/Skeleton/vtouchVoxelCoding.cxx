#include "vtouchVoxelCoding.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>

namespace vtouch
{

namespace
{
using P3 = std::array<double, 3>;
constexpr std::uint8_t kDone = 1;      // finalized in the current propagation
constexpr std::uint8_t kComponent = 2; // belongs to a component already handled
constexpr std::uint8_t kRegion = 4;    // scratch flag (extremity region)
constexpr std::uint8_t kSkeleton = 8;  // on a traced path
constexpr std::uint32_t kLabelled = 0x80000000U;
constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr int kHalf = 13; // the first 13 offsets precede the voxel: each pair visited once

/// Circular bucket queue (Dial). With a bucket width no larger than the shortest edge, popping a
/// bucket in any order is exact Dijkstra; each push and pop is O(1), so propagation is linear.
class BucketQueue
{
public:
  BucketQueue(double width, double maxStep)
    : Width(width)
    , Buckets(static_cast<std::size_t>(std::ceil(maxStep / width)) + 3)
  {
  }
  void push(std::uint32_t lin, double key)
  {
    const double b = std::floor(key / this->Width);
    std::uint64_t bucket = b > 0.0 ? static_cast<std::uint64_t>(b) : 0;
    bucket = std::max(bucket, this->Current);
    this->Buckets[bucket % this->Buckets.size()].push_back(lin);
    ++this->Size;
    this->Peak = std::max(this->Peak, this->Size);
  }
  bool pop(std::uint32_t& lin)
  {
    while (this->Size > 0)
    {
      std::vector<std::uint32_t>& b = this->Buckets[this->Current % this->Buckets.size()];
      if (!b.empty())
      {
        lin = b.back();
        b.pop_back();
        --this->Size;
        return true;
      }
      ++this->Current;
    }
    return false;
  }
  std::size_t peak() const { return this->Peak; }

private:
  double Width;
  std::vector<std::vector<std::uint32_t>> Buckets;
  std::uint64_t Current = 0;
  std::size_t Size = 0;
  std::size_t Peak = 0;
};

struct Cluster
{
  std::uint32_t band = 0;
  std::uint32_t count = 0;
  double sum[3] = { 0.0, 0.0, 0.0 };
  float maxBs = 0.0F;
  std::vector<std::uint32_t> lower;  // adjacent clusters of lower bands
  std::vector<std::uint32_t> higher; // adjacent clusters of higher bands
  int path = -1;                     // path and point that represent this cluster
  int point = -1;
  std::uint32_t bestVoxel = 0; // voxel of largest BS code
  bool onBorder = false;       // touches the volume border (an end cut by the field of view)
  std::array<double, 3> centroid() const
  {
    return { sum[0] / count, sum[1] / count, sum[2] / count };
  }
};

void addUnique(std::vector<std::uint32_t>& v, std::uint32_t c)
{
  if (std::find(v.begin(), v.end(), c) == v.end())
  {
    v.push_back(c);
  }
}

double distance(const std::array<double, 3>& a, const std::array<double, 3>& b)
{
  return std::sqrt(
    (a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}
} // namespace

struct VoxelCoder::Impl
{
  const SparseVesselMask& mask;
  VoxelCodingParameters par;
  const std::function<bool(double)>& progress;
  std::int64_t nx, ny, nz;
  std::uint32_t nx32, ny32;
  double sp[3];
  double minSpacing, maxSpacing, bandWidth;
  int off[26][3];
  std::int64_t offLin[26];
  double offLen[26];

  std::vector<float> bs;          // boundary-seeded code: distance to the nearest background, mm
  std::vector<float> ss;          // single-seed code: geodesic distance from the root, mm
  std::vector<std::uint32_t> aux; // BS sources, then union-find / cluster labels
  std::vector<std::uint8_t> flags;
  std::vector<std::uint32_t> order; // one component in SS order
  std::vector<std::uint32_t> scratch;
  std::vector<Cluster> clusters;
  std::unordered_map<std::uint32_t, std::pair<int, int>> skeletonVoxel; // lin -> (path, point)
  RawSkeleton out;
  std::vector<std::array<bool, 2>> closedEnd; // per path: head/tail end is a rounded vessel end
  std::uint64_t work = 0;
  std::uint64_t totalWork = 1;
  std::size_t peakQueue = 0;

  Impl(const SparseVesselMask& m,
    const VoxelCodingParameters& p,
    const std::function<bool(double)>& cb)
    : mask(m)
    , par(p)
    , progress(cb)
  {
    nx = m.dims()[0];
    ny = m.dims()[1];
    nz = m.dims()[2];
    nx32 = static_cast<std::uint32_t>(nx);
    ny32 = static_cast<std::uint32_t>(ny);
    for (int a = 0; a < 3; ++a)
    {
      sp[a] = p.spacing_mm[a];
    }
    minSpacing = std::min({ sp[0], sp[1], sp[2] });
    maxSpacing = std::max({ sp[0], sp[1], sp[2] });
    bandWidth = p.clusterWidth_mm > 0.0 ? p.clusterWidth_mm : maxSpacing;
    int n = 0;
    for (int dk = -1; dk <= 1; ++dk)
      for (int dj = -1; dj <= 1; ++dj)
        for (int di = -1; di <= 1; ++di)
        {
          if (di == 0 && dj == 0 && dk == 0)
          {
            continue;
          }
          off[n][0] = di;
          off[n][1] = dj;
          off[n][2] = dk;
          offLin[n] = di + nx * (dj + ny * dk);
          offLen[n] =
            std::sqrt(di * di * sp[0] * sp[0] + dj * dj * sp[1] * sp[1] + dk * dk * sp[2] * sp[2]);
          ++n;
        }
  }

  void coords(std::uint64_t lin, std::int64_t c[3]) const
  {
    // Linear indices fit 32 bits (checked in the constructor): 32-bit division is much cheaper.
    const auto l = static_cast<std::uint32_t>(lin);
    const std::uint32_t r = l / nx32;
    c[0] = static_cast<std::int64_t>(l - r * nx32);
    const std::uint32_t k = r / ny32;
    c[1] = static_cast<std::int64_t>(r - k * ny32);
    c[2] = static_cast<std::int64_t>(k);
  }

  /// Calls f(neighbourLin, neighbourIndex) for every 26-neighbour inside the volume
  /// (`count` = kHalf: only the 13 that precede it in scan order).
  template<typename F>
  void forNeighbours(std::uint64_t lin, F&& f, int count = 26) const
  {
    std::int64_t c[3];
    coords(lin, c);
    const bool interior =
      c[0] > 0 && c[0] < nx - 1 && c[1] > 0 && c[1] < ny - 1 && c[2] > 0 && c[2] < nz - 1;
    for (int n = 0; n < count; ++n)
    {
      if (!interior)
      {
        const std::int64_t i = c[0] + off[n][0], j = c[1] + off[n][1], k = c[2] + off[n][2];
        if (i < 0 || j < 0 || k < 0 || i >= nx || j >= ny || k >= nz)
        {
          continue;
        }
      }
      f(static_cast<std::uint64_t>(static_cast<std::int64_t>(lin) + offLin[n]), n);
    }
  }

  void tick(std::uint64_t amount = 1)
  {
    work += amount;
    if ((work & 0xFFFF) < amount && progress)
    {
      if (!progress(std::min(1.0, static_cast<double>(work) / static_cast<double>(totalWork))))
      {
        throw VoxelCodingAborted();
      }
    }
  }

  // ---- boundary-seeded code: Euclidean distance to the nearest background voxel centre, by
  // propagating the nearest background site (vector propagation) with a bucket queue.
  std::uint32_t padded(std::int64_t i, std::int64_t j, std::int64_t k) const
  {
    return static_cast<std::uint32_t>((i + 1) + (nx + 2) * ((j + 1) + (ny + 2) * (k + 1)));
  }
  void unpad(std::uint32_t p, std::int64_t c[3]) const
  {
    c[0] = static_cast<std::int64_t>(p % static_cast<std::uint64_t>(nx + 2)) - 1;
    const std::uint64_t r = p / static_cast<std::uint64_t>(nx + 2);
    c[1] = static_cast<std::int64_t>(r % static_cast<std::uint64_t>(ny + 2)) - 1;
    c[2] = static_cast<std::int64_t>(r / static_cast<std::uint64_t>(ny + 2)) - 1;
  }

  void computeBoundaryCode()
  {
    BucketQueue queue(minSpacing, maxSpacing * 2.0);
    mask.forEach(
      [&](std::uint64_t lin)
      {
        std::int64_t c[3];
        coords(lin, c);
        double best = kInf;
        std::uint32_t bestSite = 0;
        for (int n = 0; n < 26; ++n)
        {
          const std::int64_t i = c[0] + off[n][0], j = c[1] + off[n][1], k = c[2] + off[n][2];
          // Outside the volume is not background: a vessel cut by the field of view goes on.
          const bool outside = i < 0 || j < 0 || k < 0 || i >= nx || j >= ny || k >= nz;
          if (!outside &&
              !mask.test(static_cast<std::uint64_t>(static_cast<std::int64_t>(lin) + offLin[n])) &&
              offLen[n] < best)
          {
            best = offLen[n];
            bestSite = padded(i, j, k);
          }
        }
        if (best < kInf)
        {
          const std::uint32_t r = mask.rank(lin);
          bs[r] = static_cast<float>(best);
          aux[r] = bestSite;
          queue.push(static_cast<std::uint32_t>(lin), best);
        }
        tick();
      });
    std::uint32_t lin = 0;
    while (queue.pop(lin))
    {
      const std::uint32_t r = mask.rank(lin);
      const std::uint32_t site = aux[r];
      std::int64_t s[3];
      unpad(site, s);
      std::int64_t cv[3];
      coords(lin, cv);
      forNeighbours(lin,
        [&](std::uint64_t u, int n)
        {
          if (!mask.test(u))
          {
            return;
          }
          const std::uint32_t ru = mask.rank(u);
          const std::int64_t c[3] = { cv[0] + off[n][0], cv[1] + off[n][1], cv[2] + off[n][2] };
          const double dx = (c[0] - s[0]) * sp[0], dy = (c[1] - s[1]) * sp[1],
                       dz = (c[2] - s[2]) * sp[2];
          const float d = static_cast<float>(std::sqrt(dx * dx + dy * dy + dz * dz));
          if (d < bs[ru])
          {
            bs[ru] = d;
            aux[ru] = site;
            queue.push(static_cast<std::uint32_t>(u), d);
          }
        });
      tick();
    }
    peakQueue = std::max(peakQueue, queue.peak());
  }

  // ---- single-seed code: exact geodesic (26-neighbour, metric edge lengths) Dijkstra.
  void propagate(const std::vector<std::uint32_t>& sources)
  {
    BucketQueue queue(minSpacing, maxSpacing * std::sqrt(3.0));
    order.clear();
    for (std::uint32_t s : sources)
    {
      ss[mask.rank(s)] = 0.0F;
      queue.push(s, 0.0);
    }
    std::uint32_t lin = 0;
    while (queue.pop(lin))
    {
      const std::uint32_t r = mask.rank(lin);
      if (flags[r] & kDone)
      {
        continue;
      }
      flags[r] |= kDone;
      order.push_back(lin);
      const float d = ss[r];
      forNeighbours(lin,
        [&](std::uint64_t u, int n)
        {
          if (!mask.test(u))
          {
            return;
          }
          const std::uint32_t ru = mask.rank(u);
          const float nd = d + static_cast<float>(offLen[n]);
          if (!(flags[ru] & kDone) && nd < ss[ru])
          {
            ss[ru] = nd;
            queue.push(static_cast<std::uint32_t>(u), nd);
          }
        });
      tick();
    }
    peakQueue = std::max(peakQueue, queue.peak());
  }

  void resetPropagation()
  {
    for (std::uint32_t lin : order)
    {
      const std::uint32_t r = mask.rank(lin);
      flags[r] &= static_cast<std::uint8_t>(~kDone);
      ss[r] = kInf;
    }
  }

  /// The automatic root: the cluster of voxels farthest from an arbitrary start (double
  /// propagation), reduced to the voxel at its centroid (the end cap is centred on the axis).
  std::vector<std::uint32_t> extremityRegion()
  {
    const std::uint32_t far = order.back();
    const float threshold = ss[mask.rank(far)] - static_cast<float>(bandWidth);
    std::vector<std::uint32_t> region{ far };
    flags[mask.rank(far)] |= kRegion;
    for (std::size_t q = 0; q < region.size(); ++q)
    {
      forNeighbours(region[q],
        [&](std::uint64_t u, int)
        {
          if (!mask.test(u))
          {
            return;
          }
          const std::uint32_t ru = mask.rank(u);
          if (!(flags[ru] & kRegion) && ss[ru] >= threshold)
          {
            flags[ru] |= kRegion;
            region.push_back(static_cast<std::uint32_t>(u));
          }
        });
    }
    double sum[3] = { 0.0, 0.0, 0.0 };
    for (std::uint32_t lin : region)
    {
      flags[mask.rank(lin)] &= static_cast<std::uint8_t>(~kRegion);
      const std::array<double, 3> c = centerOf(lin);
      for (int a = 0; a < 3; ++a)
      {
        sum[a] += c[a] / static_cast<double>(region.size());
      }
    }
    // One root voxel at the centre of the end cap when it is vessel: every trace converges there.
    std::int64_t v[3];
    for (int a = 0; a < 3; ++a)
    {
      v[a] = std::clamp<std::int64_t>(std::llround(sum[a] / sp[a]),
        0,
        (a == 0    ? nx
          : a == 1 ? ny
                   : nz) -
          1);
    }
    const std::uint64_t centre = static_cast<std::uint64_t>(v[0] + nx * (v[1] + ny * v[2]));
    if (mask.test(centre))
    {
      return { static_cast<std::uint32_t>(centre) };
    }
    return region;
  }

  std::uint32_t band(std::uint32_t r) const
  {
    return static_cast<std::uint32_t>(ss[r] / bandWidth);
  }

  std::uint32_t find(std::uint32_t r)
  {
    while (aux[r] != r)
    {
      aux[r] = aux[aux[r]];
      r = aux[r];
    }
    return r;
  }

  // ---- clusters: connected parts of equal SS band, and the cluster graph.
  void buildClusters()
  {
    for (std::uint32_t lin : order)
    {
      const std::uint32_t r = mask.rank(lin);
      aux[r] = r;
    }
    for (std::uint32_t lin : order)
    {
      const std::uint32_t r = mask.rank(lin);
      const std::uint32_t b = band(r);
      forNeighbours(
        lin,
        [&](std::uint64_t u, int)
        {
          if (!mask.test(u))
          {
            return;
          }
          const std::uint32_t ru = mask.rank(u);
          if (band(ru) == b)
          {
            const std::uint32_t a = find(r), c = find(ru);
            if (a != c)
            {
              aux[std::max(a, c)] = std::min(a, c);
            }
          }
        },
        kHalf);
      tick();
    }
    for (std::uint32_t lin : order)
    {
      const std::uint32_t r = mask.rank(lin);
      aux[r] = find(r);
    }
    clusters.clear();
    for (std::uint32_t lin : order)
    {
      const std::uint32_t r = mask.rank(lin);
      if (aux[r] == r)
      {
        aux[r] = kLabelled | static_cast<std::uint32_t>(clusters.size());
        clusters.emplace_back();
        clusters.back().band = band(r);
      }
    }
    for (std::uint32_t lin : order)
    {
      const std::uint32_t r = mask.rank(lin);
      if (!(aux[r] & kLabelled))
      {
        aux[r] = aux[aux[r]];
      }
      Cluster& c = clusters[aux[r] & ~kLabelled];
      std::int64_t x[3];
      coords(lin, x);
      ++c.count;
      c.onBorder = c.onBorder || x[0] == 0 || x[1] == 0 || x[2] == 0 || x[0] == nx - 1 ||
                   x[1] == ny - 1 || x[2] == nz - 1;
      for (int a = 0; a < 3; ++a)
      {
        c.sum[a] += static_cast<double>(x[a]) * sp[a];
      }
      if (bs[r] > c.maxBs || c.count == 1)
      {
        c.maxBs = bs[r];
        c.bestVoxel = lin;
      }
    }
    for (std::uint32_t lin : order)
    {
      const std::uint32_t r = mask.rank(lin);
      const std::uint32_t c = aux[r] & ~kLabelled;
      forNeighbours(
        lin,
        [&](std::uint64_t u, int)
        {
          if (!mask.test(u))
          {
            return;
          }
          const std::uint32_t cu = aux[mask.rank(u)] & ~kLabelled;
          if (cu == c || clusters[cu].band == clusters[c].band)
          {
            return;
          }
          const std::uint32_t hi = clusters[cu].band > clusters[c].band ? cu : c;
          const std::uint32_t lo = hi == c ? cu : c;
          addUnique(clusters[hi].lower, lo);
          addUnique(clusters[lo].higher, hi);
        },
        kHalf);
      tick();
    }
  }

  /// Appends a voxel and its centre to the path, filling the gap from the previous point with a
  /// 26-connected voxel line whose positions interpolate the two centres. Returns the point index.
  int appendPoint(RawSkeletonPath& path,
    const std::array<std::int64_t, 3>& target,
    const std::array<double, 3>& center,
    double radius)
  {
    if (!path.voxels.empty())
    {
      std::array<std::int64_t, 3> cur = path.voxels.back();
      if (cur == target)
      {
        return static_cast<int>(path.voxels.size()) - 1;
      }
      const std::int64_t steps = std::max({ std::abs(target[0] - cur[0]),
        std::abs(target[1] - cur[1]),
        std::abs(target[2] - cur[2]) });
      const std::array<double, 3> from = path.center_mm.back();
      const double r0 = path.radius_mm.back();
      for (std::int64_t s = 1; s < steps; ++s)
      {
        for (int a = 0; a < 3; ++a)
        {
          cur[a] += (target[a] > cur[a]) - (target[a] < cur[a]);
        }
        const double t = static_cast<double>(s) / static_cast<double>(steps);
        path.voxels.push_back(cur);
        path.center_mm.push_back({ from[0] + t * (center[0] - from[0]),
          from[1] + t * (center[1] - from[1]),
          from[2] + t * (center[2] - from[2]) });
        path.radius_mm.push_back(r0 + t * (radius - r0));
      }
    }
    path.voxels.push_back(target);
    path.center_mm.push_back(center);
    path.radius_mm.push_back(radius);
    return static_cast<int>(path.voxels.size()) - 1;
  }

  std::uint32_t clusterOf(std::uint32_t lin) const { return aux[mask.rank(lin)] & ~kLabelled; }

  double radiusAt(std::uint32_t lin) const
  {
    // BS is the distance to the nearest background voxel centre. The wall lies about half a voxel
    // before that centre, and the traced voxel sits up to half a voxel off the true axis (the
    // adjusted centre does not): the two biases cancel on average (calibrated on phantoms).
    return std::max(static_cast<double>(bs[mask.rank(lin)]), 0.5 * minSpacing);
  }

  std::array<std::int64_t, 3> voxelArray(std::uint32_t lin) const
  {
    std::int64_t c[3];
    coords(lin, c);
    return { c[0], c[1], c[2] };
  }

  std::array<double, 3> centerOf(std::uint32_t lin) const
  {
    std::int64_t c[3];
    coords(lin, c);
    return { c[0] * sp[0], c[1] * sp[1], c[2] * sp[2] };
  }

  /// Center adjustment: the centroid of the voxels of `lin`'s cluster (a slab of the SS code across
  /// the vessel) that lie within about one radius of it. Restricting the slab to the neighbourhood
  /// keeps the point in its own branch where a slab still spans two branches near a bifurcation.
  std::array<double, 3> adjustedCenter(std::uint32_t lin)
  {
    const std::uint32_t cluster = clusterOf(lin);
    const std::array<double, 3> c0 = centerOf(lin);
    const double reach = 1.25 * bs[mask.rank(lin)] + 0.5 * bandWidth;
    scratch.clear();
    scratch.push_back(lin);
    flags[mask.rank(lin)] |= kRegion;
    double sum[3] = { 0.0, 0.0, 0.0 };
    for (std::size_t q = 0; q < scratch.size(); ++q)
    {
      const std::array<double, 3> p = centerOf(scratch[q]);
      for (int a = 0; a < 3; ++a)
      {
        sum[a] += p[a];
      }
      forNeighbours(scratch[q],
        [&](std::uint64_t u, int)
        {
          if (!mask.test(u))
          {
            return;
          }
          const std::uint32_t ru = mask.rank(u);
          if (!(flags[ru] & kRegion) && (aux[ru] & ~kLabelled) == cluster &&
              distance(centerOf(static_cast<std::uint32_t>(u)), c0) <= reach)
          {
            flags[ru] |= kRegion;
            scratch.push_back(static_cast<std::uint32_t>(u));
          }
        });
    }
    for (std::uint32_t v : scratch)
    {
      flags[mask.rank(v)] &= static_cast<std::uint8_t>(~kRegion);
    }
    const double n = static_cast<double>(scratch.size());
    return { sum[0] / n, sum[1] / n, sum[2] / n };
  }

  struct Trace
  {
    std::vector<std::uint32_t> voxels; // from the start down, excluding the attachment point
    int path = -1;                     // attachment (path, point); -1 = free end (the root)
    int point = -1;
    double length = 0.0;
  };

  /// A skeleton voxel at or next to `lin`, as (path, point), or path -1.
  std::pair<int, int> touchedSkeleton(std::uint32_t lin) const
  {
    if (flags[mask.rank(lin)] & kSkeleton)
    {
      return skeletonVoxel.at(lin);
    }
    std::pair<int, int> hit{ -1, -1 };
    forNeighbours(lin,
      [&](std::uint64_t u, int)
      {
        if (hit.first < 0 && mask.test(u) && (flags[mask.rank(u)] & kSkeleton))
        {
          hit = skeletonVoxel.at(static_cast<std::uint32_t>(u));
        }
      });
    return hit;
  }

  /// Center-adjusted back-tracing: from `start`, step to the 26-neighbour of lower SS code with the
  /// largest BS code (the ridge of the distance map, i.e. the vessel centre) until the trace
  /// touches the skeleton already traced, or reaches the root. Touches are ignored while the SS
  /// code is above `ignoreAbove` (a loop closure starts next to the skeleton). If the trace runs
  /// alongside the skeleton through more than `patience` clusters already on it without touching,
  /// it attaches to the current cluster's point.
  Trace descend(std::uint32_t start, float ignoreAbove, std::size_t patience) const
  {
    Trace t;
    std::uint32_t v = start;
    std::uint32_t lastCluster = std::numeric_limits<std::uint32_t>::max();
    std::size_t markedRun = 0;
    while (true)
    {
      const std::uint32_t rv = mask.rank(v);
      if (ss[rv] <= ignoreAbove)
      {
        const std::pair<int, int> hit = touchedSkeleton(v);
        if (hit.first >= 0)
        {
          t.path = hit.first;
          t.point = hit.second;
          break;
        }
      }
      if (!t.voxels.empty())
      {
        t.length += distance(centerOf(t.voxels.back()), centerOf(v));
      }
      t.voxels.push_back(v);
      const std::uint32_t c = clusterOf(v);
      if (c != lastCluster)
      {
        lastCluster = c;
        markedRun = clusters[c].path >= 0 ? markedRun + 1 : 0;
        if (markedRun > patience && ss[rv] <= ignoreAbove)
        {
          t.path = clusters[c].path;
          t.point = clusters[c].point;
          break;
        }
      }
      std::uint32_t best = v;
      float bestBs = -1.0F;
      float bestSs = ss[rv];
      forNeighbours(v,
        [&](std::uint64_t u, int)
        {
          if (!mask.test(u))
          {
            return;
          }
          const std::uint32_t ru = mask.rank(u);
          if (ss[ru] < ss[rv] && (bs[ru] > bestBs || (bs[ru] == bestBs && ss[ru] < bestSs)))
          {
            best = static_cast<std::uint32_t>(u);
            bestBs = bs[ru];
            bestSs = ss[ru];
          }
        });
      if (best == v)
      {
        break; // no lower neighbour: the root
      }
      v = best;
    }
    return t;
  }

  void markPoint(int path, int point, std::uint32_t lin)
  {
    const std::uint32_t r = mask.rank(lin);
    if (!(flags[r] & kSkeleton))
    {
      flags[r] |= kSkeleton;
      skeletonVoxel[lin] = { path, point };
    }
    Cluster& c = clusters[clusterOf(lin)];
    if (c.path < 0)
    {
      c.path = path;
      c.point = point;
    }
  }

  /// Makes a path of `t` reversed: head at the attachment (or the root), tail at the start voxel,
  /// or, with `tailPath` >= 0, at point (tailPath, tailPoint) of the skeleton (a loop closure).
  void emitPath(const Trace& t, bool startOnBorder, int tailPath, int tailPoint)
  {
    const int id = static_cast<int>(out.paths.size());
    out.paths.emplace_back();
    closedEnd.push_back({ false, tailPath < 0 && !startOnBorder });
    if (t.path >= 0)
    {
      const RawSkeletonPath& parent = out.paths[t.path];
      const auto voxel = parent.voxels[t.point];
      const auto center = parent.center_mm[t.point];
      const double radius = parent.radius_mm[t.point];
      RawSkeletonPath& path = out.paths[id];
      path.voxels.push_back(voxel);
      path.center_mm.push_back(center);
      path.radius_mm.push_back(radius);
      out.junctions.push_back({ id, false, t.path, t.point });
      path.headJunction = static_cast<int>(out.junctions.size()) - 1;
    }
    else
    {
      closedEnd.back()[0] = !clusters[clusterOf(t.voxels.back())].onBorder;
    }
    for (std::size_t i = t.voxels.size(); i-- > 0;)
    {
      const std::uint32_t lin = t.voxels[i];
      const int point =
        appendPoint(out.paths[id], voxelArray(lin), adjustedCenter(lin), radiusAt(lin));
      markPoint(id, point, lin);
    }
    if (tailPath >= 0)
    {
      RawSkeletonPath& path = out.paths[id];
      const RawSkeletonPath& parent = out.paths[tailPath];
      appendPoint(
        path, parent.voxels[tailPoint], parent.center_mm[tailPoint], parent.radius_mm[tailPoint]);
      out.junctions.push_back({ id, true, tailPath, tailPoint });
      path.tailJunction = static_cast<int>(out.junctions.size()) - 1;
    }
  }

  /// A vessel that ends inside the volume ends in a rounded cap; the medial axis stops where the
  /// inscribed sphere touches the cap's apex, so drop the points whose radius reaches the apex.
  /// Points that other paths attach to are kept.
  void trimClosedEnds(std::size_t firstPath)
  {
    std::vector<char> pinned;
    for (std::size_t p = firstPath; p < out.paths.size(); ++p)
    {
      RawSkeletonPath& path = out.paths[p];
      pinned.assign(path.voxels.size(), 0);
      for (const RawJunction& j : out.junctions)
      {
        if (j.parentPath == static_cast<int>(p))
        {
          pinned[j.parentPoint] = 1;
        }
      }
      // Drop the end points that lie inside the inscribed ball of a point further in.
      const auto trimCount = [&](bool fromTail)
      {
        const std::size_t n = path.voxels.size();
        const auto at = [&](std::size_t k) { return fromTail ? n - 1 - k : k; };
        const std::array<double, 3> end = path.center_mm[at(0)];
        const double tolerance = 0.5 * minSpacing + 0.1 * path.radius_mm[at(n / 2)];
        std::size_t best = 0;
        for (std::size_t k = 1; k + 1 < n && !pinned[at(k - 1)]; ++k)
        {
          const double d = distance(path.center_mm[at(k)], end);
          if (d > 3.0 * (path.radius_mm[at(k)] + tolerance))
          {
            break;
          }
          if (d <= path.radius_mm[at(k)] + tolerance)
          {
            best = k;
          }
        }
        return best;
      };
      if (closedEnd[p][1] && path.tailJunction < 0)
      {
        const std::size_t k = trimCount(true);
        path.voxels.resize(path.voxels.size() - k);
        path.center_mm.resize(path.center_mm.size() - k);
        path.radius_mm.resize(path.radius_mm.size() - k);
      }
      if (closedEnd[p][0] && path.headJunction < 0)
      {
        const std::size_t k = trimCount(false);
        path.voxels.erase(
          path.voxels.begin(), path.voxels.begin() + static_cast<std::ptrdiff_t>(k));
        path.center_mm.erase(
          path.center_mm.begin(), path.center_mm.begin() + static_cast<std::ptrdiff_t>(k));
        path.radius_mm.erase(
          path.radius_mm.begin(), path.radius_mm.begin() + static_cast<std::ptrdiff_t>(k));
        for (RawJunction& j : out.junctions)
        {
          if (j.parentPath == static_cast<int>(p))
          {
            j.parentPoint -= static_cast<int>(k);
          }
        }
      }
    }
  }

  void traceComponent()
  {
    // Tips: clusters without higher neighbours (local maxima of the SS code), farthest first.
    std::vector<std::uint32_t> tips;
    std::uint32_t root = 0;
    for (std::uint32_t c = 0; c < clusters.size(); ++c)
    {
      if (clusters[c].higher.empty() && clusters[c].band > 0)
      {
        tips.push_back(c);
      }
      if (clusters[c].band == 0)
      {
        root = c;
      }
    }
    std::sort(tips.begin(),
      tips.end(),
      [&](std::uint32_t a, std::uint32_t b) {
        return clusters[a].band != clusters[b].band ? clusters[a].band > clusters[b].band : a < b;
      });
    const std::size_t firstPath = out.paths.size();
    for (std::uint32_t tip : tips)
    {
      if (clusters[tip].path >= 0)
      {
        continue;
      }
      const std::size_t patience = patienceFor(clusters[tip]);
      Trace t = descend(tipStart(clusters[tip]), kInf, patience);
      if (t.path < 0 && out.paths.size() > firstPath)
      {
        t.path = clusters[root].path; // reached the root beside the first path
        t.point = clusters[root].point;
      }
      if (t.voxels.empty())
      {
        continue;
      }
      if (t.path >= 0)
      {
        const double radius = nearbyRadius(t.path, t.point);
        const double tipToJunction =
          t.length + distance(centerOf(t.voxels.back()), out.paths[t.path].center_mm[t.point]);
        if (tipToJunction < std::max(par.minimumBranchLength * radius, 2.0 * bandWidth))
        {
          continue; // a spur
        }
      }
      else if (t.voxels.size() < 2)
      {
        continue;
      }
      emitPath(t, clusters[tip].onBorder, -1, -1);
    }
    if (out.paths.size() > firstPath)
    {
      closeLoops();
      trimClosedEnds(firstPath);
    }
  }

  /// Where a branch trace starts: the voxel at the tip cluster's centroid when it is vessel (the
  /// last band at a flat or rounded end is a ring or cap centred on the axis), else the cluster's
  /// most central voxel.
  std::uint32_t tipStart(const Cluster& c) const
  {
    const std::array<double, 3> m = c.centroid();
    std::int64_t v[3];
    for (int a = 0; a < 3; ++a)
    {
      v[a] = std::clamp<std::int64_t>(std::llround(m[a] / sp[a]),
        0,
        (a == 0    ? nx
          : a == 1 ? ny
                   : nz) -
          1);
    }
    const std::uint64_t lin = static_cast<std::uint64_t>(v[0] + nx * (v[1] + ny * v[2]));
    return mask.test(lin) ? static_cast<std::uint32_t>(lin) : c.bestVoxel;
  }

  /// The largest radius of a path within one radius of a point: near an end cap or a junction
  /// the radius at the point itself underestimates the vessel a spur grows from.
  double nearbyRadius(int path, int point) const
  {
    const RawSkeletonPath& p = out.paths[path];
    const double r0 = p.radius_mm[point];
    double r = r0;
    for (int step : { -1, 1 })
    {
      for (int i = point + step; i >= 0 && i < static_cast<int>(p.radius_mm.size()); i += step)
      {
        if (distance(p.center_mm[i], p.center_mm[point]) > r0)
        {
          break;
        }
        r = std::max(r, p.radius_mm[i]);
      }
    }
    return r;
  }

  /// Distance from a point to the nearest skeleton point (brute force: used for a few loop
  /// candidates only).
  double distanceToSkeleton(const std::array<double, 3>& q) const
  {
    double best = std::numeric_limits<double>::infinity();
    for (const RawSkeletonPath& p : out.paths)
    {
      for (const auto& c : p.center_mm)
      {
        best = std::min(best, distance(c, q));
      }
    }
    return best;
  }

  std::size_t patienceFor(const Cluster& c) const
  {
    return static_cast<std::size_t>(
             std::ceil(4.0 * std::max(1.0, static_cast<double>(c.maxBs)) / bandWidth)) +
           3;
  }

  /// Where two fronts of the SS propagation meet, a cluster touches two or more lower clusters. A
  /// lower one not yet on the skeleton may be the other front: trace down from it (B) and, if the
  /// cluster itself is not on the skeleton, from the cluster too (A), and join the two traces into
  /// one path attached at both ends: a loop. A trace B that meets the skeleton as soon as touches
  /// count is one front split by noise, not a loop.
  void closeLoops()
  {
    const std::size_t clusterCount = clusters.size();
    for (std::uint32_t c = 0; c < clusterCount; ++c)
    {
      if (clusters[c].lower.size() < 2)
      {
        continue;
      }
      const std::vector<std::uint32_t> lower = clusters[c].lower;
      for (std::uint32_t p : lower)
      {
        if (clusters[p].path >= 0)
        {
          continue;
        }
        // Side A: the cluster itself when it is on the skeleton, else another lower neighbour
        // already on it, else a trace down through another lower neighbour.
        Trace a;
        if (clusters[c].path >= 0)
        {
          a.path = clusters[c].path;
          a.point = clusters[c].point;
        }
        else
        {
          for (std::uint32_t q : lower)
          {
            if (q != p && clusters[q].path >= 0 && a.path < 0)
            {
              a.path = clusters[q].path;
              a.point = clusters[q].point;
              a.voxels.push_back(clusters[c].bestVoxel);
            }
          }
          for (std::uint32_t q : lower)
          {
            if (q != p && a.path < 0)
            {
              a = descend(clusters[q].bestVoxel, kInf, patienceFor(clusters[q]));
              a.voxels.insert(a.voxels.begin(), clusters[c].bestVoxel);
            }
          }
          if (a.path < 0)
          {
            continue;
          }
        }
        const P3 aEnd =
          a.voxels.empty() ? out.paths[a.path].center_mm[a.point] : centerOf(a.voxels.front());
        const double radius =
          std::max(out.paths[a.path].radius_mm[a.point], static_cast<double>(clusters[c].maxBs));
        const std::uint32_t start = clusters[p].bestVoxel;
        const double margin = 2.0 * radius + 2.0 * bandWidth;
        const float ignoreAbove = ss[mask.rank(start)] - static_cast<float>(margin);
        const Trace b = descend(start, ignoreAbove, patienceFor(clusters[p]));
        if (b.path < 0 || b.voxels.empty())
        {
          continue;
        }
        const double drop = ss[mask.rank(start)] - ss[mask.rank(b.voxels.back())];
        const double length = a.length + b.length + distance(aEnd, centerOf(start));
        // Both sides arriving at one place of the skeleton are one front too.
        const double apart =
          distance(out.paths[a.path].center_mm[a.point], out.paths[b.path].center_mm[b.point]);
        if (drop < margin + std::max(3.0 * bandWidth, radius) || apart < margin ||
            length < par.minimumBranchLength * radius)
        {
          continue;
        }
        // The other side of a real loop runs away from the skeleton; a trace alongside it (inside
        // a thick vessel) is the same lumen.
        const std::uint32_t middle = b.voxels[b.voxels.size() / 2];
        if (distanceToSkeleton(centerOf(middle)) <= radiusAt(middle) + bandWidth)
        {
          continue;
        }
        Trace joined;
        joined.path = a.path;
        joined.point = a.point;
        joined.voxels.assign(b.voxels.rbegin(), b.voxels.rend());
        joined.voxels.insert(joined.voxels.end(), a.voxels.begin(), a.voxels.end());
        emitPath(joined, false, b.path, b.point);
        ++out.loops;
      }
    }
  }

  /// Any extremity gives a valid SS code, but back-tracing toward a thin end cuts the corners of
  /// the bifurcations on the way (the geodesic hugs the inner wall of a sharp turn). Rooting the
  /// code at the thickest extremity (the inflow trunk of a vascular tree) makes every trace enter
  /// the trunk at an obtuse angle. Costs one more propagation.
  void rootAtThickestEnd()
  {
    // Thickness of an end: the largest BS code within a few bands of it (the end cluster itself
    // is a cap whose BS is small).
    constexpr std::uint32_t kBands = 8;
    const auto thickness = [&](std::uint32_t c)
    {
      float t = clusters[c].maxBs;
      for (std::uint32_t k = 0; k < kBands && !clusters[c].lower.empty(); ++k)
      {
        std::uint32_t next = clusters[c].lower.front();
        for (std::uint32_t l : clusters[c].lower)
        {
          next = clusters[l].count > clusters[next].count ? l : next;
        }
        c = next;
        t = std::max(t, clusters[c].maxBs);
      }
      return t;
    };
    float rootBs = 0.0F;
    std::int64_t best = -1;
    float bestBs = 0.0F;
    for (std::uint32_t c = 0; c < clusters.size(); ++c)
    {
      if (clusters[c].band <= kBands)
      {
        rootBs = std::max(rootBs, clusters[c].maxBs);
      }
      else if (clusters[c].higher.empty())
      {
        const float t = thickness(c);
        if (best < 0 || t > bestBs)
        {
          best = c;
          bestBs = t;
        }
      }
    }
    if (best < 0 || bestBs <= 1.2F * rootBs)
    {
      return;
    }
    // One root voxel at the centre of the end cap: every trace then converges to one point.
    const std::vector<std::uint32_t> root{ tipStart(clusters[best]) };
    resetPropagation();
    propagate(root);
    buildClusters();
  }

  RawSkeleton run()
  {
    const std::uint64_t n = mask.vesselCount();
    out.vesselVoxels = n;
    totalWork = std::max<std::uint64_t>(1, n * 6);
    bs.assign(n, kInf);
    aux.assign(n, 0);
    flags.assign(n, 0);
    computeBoundaryCode();
    ss.assign(n, kInf);
    order.reserve(n);

    const auto handle = [&](const std::vector<std::uint32_t>& sources, bool chooseRoot)
    {
      propagate(sources);
      buildClusters();
      if (chooseRoot)
      {
        rootAtThickestEnd();
      }
      traceComponent();
      ++out.components;
    };
    if (par.hasSeed)
    {
      const std::int64_t* s = par.seedIndex.data();
      const std::uint64_t lin = static_cast<std::uint64_t>(s[0] + nx * (s[1] + ny * s[2]));
      handle({ static_cast<std::uint32_t>(lin) }, false);
    }
    else
    {
      mask.forEach(
        [&](std::uint64_t lin)
        {
          if (flags[mask.rank(lin)] & kComponent)
          {
            return;
          }
          propagate({ static_cast<std::uint32_t>(lin) });
          for (std::uint32_t v : order)
          {
            flags[mask.rank(v)] |= kComponent;
          }
          if (order.size() < par.minimumComponentSize)
          {
            resetPropagation();
            return;
          }
          const std::vector<std::uint32_t> region = extremityRegion();
          resetPropagation();
          handle(region, true);
          for (std::uint32_t v : order)
          {
            flags[mask.rank(v)] |= kComponent;
          }
        });
    }
    std::size_t clusterBytes = clusters.capacity() * sizeof(Cluster);
    out.peakBytes = n * (2 * sizeof(float) + sizeof(std::uint32_t) + 1) +
                    order.capacity() * sizeof(std::uint32_t) + peakQueue * sizeof(std::uint32_t) +
                    clusterBytes;
    if (progress && !progress(1.0))
    {
      throw VoxelCodingAborted();
    }
    return std::move(out);
  }
};

VoxelCoder::VoxelCoder(const SparseVesselMask& mask, const VoxelCodingParameters& parameters)
  : Mask(mask)
  , Parameters(parameters)
{
  for (double s : parameters.spacing_mm)
  {
    if (!(s > 0.0) || !std::isfinite(s))
    {
      throw std::invalid_argument("voxel spacing must be positive and finite");
    }
  }
  const auto& d = mask.dims();
  if (static_cast<double>(d[0] + 2) * static_cast<double>(d[1] + 2) *
        static_cast<double>(d[2] + 2) >=
      4294967295.0)
  {
    throw std::invalid_argument("volume too large for 32-bit voxel indices (at most ~4e9 voxels)");
  }
  if (mask.vesselCount() >= 0x7FFFFFFFULL)
  {
    throw std::invalid_argument("too many vessel voxels (at most 2^31 - 1)");
  }
  if (!(parameters.minimumBranchLength >= 0.0) || !std::isfinite(parameters.minimumBranchLength))
  {
    throw std::invalid_argument("minimum branch length must be finite and >= 0");
  }
  if (parameters.hasSeed)
  {
    const auto& s = parameters.seedIndex;
    for (int a = 0; a < 3; ++a)
    {
      if (s[a] < 0 || s[a] >= d[a])
      {
        throw std::invalid_argument("seed outside the volume");
      }
    }
    if (!mask.test(static_cast<std::uint64_t>(s[0] + d[0] * (s[1] + d[1] * s[2]))))
    {
      throw std::invalid_argument("seed outside any vessel");
    }
  }
}

RawSkeleton VoxelCoder::run(const std::function<bool(double)>& progress)
{
  Impl impl(this->Mask, this->Parameters, progress);
  return impl.run();
}

} // namespace vtouch

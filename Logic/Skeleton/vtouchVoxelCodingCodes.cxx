// Voxel coding stages 2-4: BS code, SS code, clusters and the cluster graph, root choice.
#include "vtouchVoxelCodingImpl.h"

namespace vtouch
{

void VoxelCoder::Impl::computeBoundaryCode()
{
  const StageTimer timer{ *this, "bs" };
  BucketQueue queue(minSpacing, maxSpacing * 2.0);
  mask.forEach(
    [&](std::uint64_t lin)
    {
      std::int64_t c[3];
      coords(lin, c);
      if (c[0] > 0 && c[0] < nx - 1 && c[1] > 0 && c[1] < ny - 1 && c[2] > 0 && c[2] < nz - 1)
      {
        bool full = true;
        for (int q = 0; q < 9 && full; ++q)
        {
          full = mask.window3(static_cast<std::uint64_t>(
                   static_cast<std::int64_t>(lin) + rowOffset[q] - 1)) == 7U;
        }
        if (full)
        {
          tick();
          return; // not a boundary voxel
        }
      }
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
    // A voxel improved while queued has several entries: expand it once per improvement.
    if (flags[r] & kDone)
    {
      continue;
    }
    flags[r] |= kDone;
    const std::uint32_t site = aux[r];
    std::int64_t s[3];
    unpad(site, s);
    std::int64_t cv[3];
    coords(lin, cv);
    const double base[3] = { static_cast<double>(cv[0] - s[0]) * sp[0],
      static_cast<double>(cv[1] - s[1]) * sp[1],
      static_cast<double>(cv[2] - s[2]) * sp[2] };
    forNeighbours(lin,
      [&](std::uint64_t u, int n, std::uint32_t ru)
      {
        const double dx = base[0] + offMm[n][0], dy = base[1] + offMm[n][1],
                     dz = base[2] + offMm[n][2];
        const double d2 = dx * dx + dy * dy + dz * dz;
        const double current = bs[ru];
        if (d2 < current * current) // no square root unless it improves
        {
          const auto d = static_cast<float>(std::sqrt(d2));
          if (d < bs[ru])
          {
            bs[ru] = d;
            aux[ru] = site;
            flags[ru] &= static_cast<std::uint8_t>(~kDone);
            queue.push(static_cast<std::uint32_t>(u), d);
          }
        }
      });
    tick();
  }
  for (std::uint8_t& f : flags)
  {
    f &= static_cast<std::uint8_t>(~kDone);
  }
  peakQueue = std::max(peakQueue, queue.peak());
}

void VoxelCoder::Impl::propagate(const std::vector<std::uint32_t>& sources, bool unite)
{
  const StageTimer timer{ *this, "ss" };
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
    const std::uint32_t b = band(r);
    std::uint32_t rootR = r;
    if (unite)
    {
      aux[r] = r;
    }
    forNeighbours(lin,
      [&](std::uint64_t u, int n, std::uint32_t ru)
      {
        if (flags[ru] & kDone)
        {
          // Each pair of neighbours is joined once: when the second of the two is finalized.
          if (unite && band(ru) == b)
          {
            // Only this voxel's set changes during its expansion: its root is tracked.
            const std::uint32_t y = find(ru);
            if (y != rootR)
            {
              aux[std::max(rootR, y)] = std::min(rootR, y);
              rootR = std::min(rootR, y);
            }
          }
          return;
        }
        const float nd = d + offLenF[n];
        if (nd < ss[ru])
        {
          ss[ru] = nd;
          queue.push(static_cast<std::uint32_t>(u), nd);
        }
      });
    tick();
  }
  peakQueue = std::max(peakQueue, queue.peak());
}

void VoxelCoder::Impl::resetPropagation()
{
  for (std::uint32_t lin : order)
  {
    const std::uint32_t r = mask.rank(lin);
    flags[r] &= static_cast<std::uint8_t>(~kDone);
    ss[r] = kInf;
  }
}

std::vector<std::uint32_t> VoxelCoder::Impl::extremityRegion()
{
  const std::uint32_t far = order.back();
  const float threshold = ss[mask.rank(far)] - static_cast<float>(bandWidth);
  std::vector<std::uint32_t> region{ far };
  flags[mask.rank(far)] |= kRegion;
  for (std::size_t q = 0; q < region.size(); ++q)
  {
    forNeighbours(region[q],
      [&](std::uint64_t u, int, std::uint32_t ru)
      {
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

void VoxelCoder::Impl::buildClusters()
{
  const StageTimer timer{ *this, "clusters" };
  // The union of equal-band neighbours was done by propagate(..., true).
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
    // Most neighbours of another band belong to one or two clusters: skip repeats cheaply.
    std::uint32_t linked[2] = { c, c };
    forNeighbours(
      lin,
      [&](std::uint64_t, int, std::uint32_t ru)
      {
        const std::uint32_t cu = aux[ru] & ~kLabelled;
        if (cu == linked[0] || cu == linked[1] || clusters[cu].band == clusters[c].band)
        {
          return;
        }
        linked[1] = linked[0];
        linked[0] = cu;
        const std::uint32_t hi = clusters[cu].band > clusters[c].band ? cu : c;
        const std::uint32_t lo = hi == c ? cu : c;
        addUnique(clusters[hi].lower, lo);
        addUnique(clusters[lo].higher, hi);
      },
      kHalf);
    tick();
  }
}

void VoxelCoder::Impl::rootAtThickestEnd()
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
  propagate(root, true);
  buildClusters();
}

} // namespace vtouch

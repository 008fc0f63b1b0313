// Voxel coding stages 3-4: SS code, clusters and the cluster graph, root choice.
#include "vtouchVoxelCodingImpl.h"

namespace vtouch
{

void VoxelCoder::Impl::propagate(const std::vector<std::uint32_t>& sources)
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
  std::uint32_t pops = 0;
  while (queue.pop(lin))
  {
    if ((++pops & 0xFFFF) == 0)
    {
      checkpoint(); // stale entries are not work, but they take time
    }
    const std::uint32_t r = mask.rank(lin);
    if (flags[r] & kDone)
    {
      continue; // a stale entry of a voxel improved while queued
    }
    flags[r] |= kDone;
    order.push_back(lin);
    const float d = ss[r];
    // No test of the neighbours' kDone flags (a cache miss each): a finalized neighbour u left a
    // bucket at or below the current one, so ss[u] < d + bucket width <= d + any edge, and the
    // comparison below already rejects it.
    forNeighbours(lin,
      [&](std::uint64_t u, int n, std::uint32_t ru)
      {
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

std::uint32_t VoxelCoder::Impl::coarseExtremity(std::uint32_t lin)
{
  // Below this the exact exploration costs little; the block mask would not pay for itself.
  constexpr std::uint64_t kCoarseFrom = std::uint64_t{ 1 } << 17;
  if (mask.vesselCount() < kCoarseFrom || nx < 2 || ny < 2 || nz < 2)
  {
    return kNoVoxel;
  }
  const StageTimer timer{ *this, "explore" };
  if (!explorer)
  {
    coarseMask = std::make_unique<SparseVesselMask>(mask.downsampled(2));
    VoxelCodingParameters coarse = par;
    coarse.spacing_mm = { 2.0 * sp[0], 2.0 * sp[1], 2.0 * sp[2] };
    coarse.hasSeed = false;
    explorer = std::make_unique<Impl>(*coarseMask, coarse, noProgress);
    explorer->ss.assign(coarseMask->vesselCount(), kInf);
    explorer->flags.assign(coarseMask->vesselCount(), 0);
  }
  std::int64_t c[3];
  coords(lin, c);
  const auto blockOf = [&](const std::int64_t* v)
  {
    return static_cast<std::uint32_t>(
      v[0] / 2 + explorer->nx * (v[1] / 2 + explorer->ny * (v[2] / 2)));
  };
  const std::uint32_t start = blockOf(c);
  if (explorer->flags[coarseMask->rank(start)] & kComponent)
  {
    // Its blocks touch a component already explored (small blobs beside a vessel): the exact
    // search costs the blob's size, another block propagation would cost the vessel's.
    return kNoVoxel;
  }
  explorer->propagate({ start });
  const std::vector<std::uint32_t> region = explorer->extremityRegion();
  for (const std::uint32_t b : explorer->order)
  {
    explorer->flags[coarseMask->rank(b)] |= kComponent;
  }
  double centre[3] = { 0.0, 0.0, 0.0 }; // in fine voxel indices; a block's centre is 2 I + 0.5
  for (const std::uint32_t b : region)
  {
    std::int64_t bc[3];
    explorer->coords(b, bc);
    for (int a = 0; a < 3; ++a)
    {
      centre[a] += (2.0 * static_cast<double>(bc[a]) + 0.5) / static_cast<double>(region.size());
    }
  }
  explorer->resetPropagation();
  // The vessel voxel nearest the end cap's centre, within the blocks around it.
  std::uint32_t best = kNoVoxel;
  double bestDistance = std::numeric_limits<double>::infinity();
  const std::int64_t dims[3] = { nx, ny, nz };
  std::int64_t lo[3], hi[3];
  for (int a = 0; a < 3; ++a)
  {
    lo[a] = std::max<std::int64_t>(0, static_cast<std::int64_t>(std::floor(centre[a])) - 2);
    hi[a] =
      std::min<std::int64_t>(dims[a] - 1, static_cast<std::int64_t>(std::ceil(centre[a])) + 2);
  }
  for (std::int64_t k = lo[2]; k <= hi[2]; ++k)
    for (std::int64_t j = lo[1]; j <= hi[1]; ++j)
      for (std::int64_t i = lo[0]; i <= hi[0]; ++i)
      {
        const auto v = static_cast<std::uint64_t>(i + nx * (j + ny * k));
        const double d = (i - centre[0]) * (i - centre[0]) * sp[0] * sp[0] +
                         (j - centre[1]) * (j - centre[1]) * sp[1] * sp[1] +
                         (k - centre[2]) * (k - centre[2]) * sp[2] * sp[2];
        if (d < bestDistance && mask.test(v))
        {
          bestDistance = d;
          best = static_cast<std::uint32_t>(v);
        }
      }
  return best;
}

void VoxelCoder::Impl::buildClusters()
{
  awaitBoundaryCode(); // the clusters read bs
  const StageTimer timer{ *this, "clusters" };
  // The passes visit each voxel's neighbourhood: in scan (rank) order the arrays are
  // read nearly sequentially, in SS order every access is a cache miss (2-3x slower). Scan order
  // needs the whole mask to be this component (the usual case); otherwise the SS order is kept.
  const bool whole = order.size() == mask.vesselCount();
  const auto visit = [&](auto&& f)
  {
    if (whole)
    {
      std::uint32_t r = 0;
      mask.forEach([&](std::uint64_t lin) { f(static_cast<std::uint32_t>(lin), r++); });
    }
    else
    {
      for (std::uint32_t lin : order)
      {
        f(lin, mask.rank(lin));
      }
    }
  };
  // Union-find (in aux, the smaller rank is the root) of the 26-neighbours in the same SS band;
  // each pair is joined once, from the later of the two in scan order.
  if (!whole)
  {
    for (std::uint32_t lin : order)
    {
      const std::uint32_t r = mask.rank(lin);
      aux[r] = r;
    }
  }
  std::uint32_t visited = 0;
  visit(
    [&](std::uint32_t lin, std::uint32_t r)
    {
      if ((++visited & 0xFFFF) == 0)
      {
        checkpoint(); // the union-find pass is not counted as work: a check point of its own
      }
      if (whole)
      {
        aux[r] = r;
      }
      const std::uint32_t b = band(r);
      std::uint32_t rootR = find(r);
      forNeighbours(
        lin,
        [&](std::uint64_t, int, std::uint32_t ru)
        {
          if (band(ru) == b)
          {
            // Only this voxel's set changes here: its root is tracked.
            const std::uint32_t y = find(ru);
            if (y != rootR)
            {
              aux[std::max(rootR, y)] = std::min(rootR, y);
              rootR = std::min(rootR, y);
            }
          }
        },
        kHalf);
    });
  // The roots become the clusters, numbered in SS order (the order of the tips' tie-breaks).
  clusters.clear();
  visited = 0;
  for (std::uint32_t lin : order)
  {
    if ((++visited & 0xFFFF) == 0)
    {
      checkpoint();
    }
    const std::uint32_t r = mask.rank(lin);
    if (aux[r] == r)
    {
      aux[r] = kLabelled | static_cast<std::uint32_t>(clusters.size());
      clusters.emplace_back();
      clusters.back().band = band(r);
    }
  }
  // Label of each voxel (its set's cluster) and the cluster sums.
  const auto resolve = [&](std::uint32_t lin, std::uint32_t r)
  {
    if (!(aux[r] & kLabelled))
    {
      // Union parents precede their children in rank order, so in scan order the parent is
      // already labelled; in SS order, follow the chain.
      std::uint32_t x = aux[r];
      while (!(aux[x] & kLabelled))
      {
        x = aux[x];
      }
      aux[r] = aux[x];
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
    // Ties of BS go to the lower SS code, whatever the visiting order.
    if (c.count == 1 || bs[r] > c.maxBs || (bs[r] == c.maxBs && ss[r] < ss[mask.rank(c.bestVoxel)]))
    {
      c.maxBs = bs[r];
      c.bestVoxel = lin;
    }
  };
  // Cluster graph: clusters of different bands that touch.
  const auto link = [&](std::uint32_t lin, std::uint32_t r)
  {
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
  };
  if (whole)
  {
    // One pass: in scan order the 13 neighbours before a voxel are already resolved.
    visit(
      [&](std::uint32_t lin, std::uint32_t r)
      {
        resolve(lin, r);
        link(lin, r);
      });
  }
  else
  {
    visit(resolve);
    visit(link);
  }
  // Neighbour lists in cluster (SS) order, independent of the visiting order.
  for (Cluster& c : clusters)
  {
    std::sort(c.lower.begin(), c.lower.end());
    std::sort(c.higher.begin(), c.higher.end());
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
  // The root's end measured the same way, walking up from the root's cluster (the first in SS
  // order): a ball of kBands around a rounded cap's apex would see only the cap, and a vessel of
  // one calibre (a helix) would then always be re-rooted, at the cost of a second SS code.
  float rootBs = clusters.empty() ? 0.0F : clusters[0].maxBs;
  for (std::uint32_t c = 0, k = 0; k < kBands && c < clusters.size() && !clusters[c].higher.empty();
       ++k)
  {
    std::uint32_t next = clusters[c].higher.front();
    for (std::uint32_t h : clusters[c].higher)
    {
      next = clusters[h].count > clusters[next].count ? h : next;
    }
    c = next;
    rootBs = std::max(rootBs, clusters[c].maxBs);
  }
  std::int64_t best = -1;
  float bestBs = 0.0F;
  for (std::uint32_t c = 0; c < clusters.size(); ++c)
  {
    if (clusters[c].band > kBands && clusters[c].higher.empty())
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

} // namespace vtouch

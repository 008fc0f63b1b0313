#include "vtouchVoxelCoding.h"

#include "vtouchVoxelCodingImpl.h"

#include <memory>

namespace vtouch
{

VoxelCoder::Impl::Impl(const SparseVesselMask& m,
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
  inverseNx = 1.0 / static_cast<double>(nx32);
  inverseNy = 1.0 / static_cast<double>(ny32);
  for (int a = 0; a < 3; ++a)
  {
    sp[a] = p.spacing_mm[a];
  }
  minSpacing = std::min({ sp[0], sp[1], sp[2] });
  maxSpacing = std::max({ sp[0], sp[1], sp[2] });
  bandWidth = p.clusterWidth_mm > 0.0 ? p.clusterWidth_mm : maxSpacing;
  inverseBandWidth = static_cast<float>(1.0 / bandWidth);
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
        offLenF[n] = static_cast<float>(offLen[n]);
        offMm[n][0] = di * sp[0];
        offMm[n][1] = dj * sp[1];
        offMm[n][2] = dk * sp[2];
        ++n;
      }
  for (int q = 0; q < 9; ++q)
  {
    rowOffset[q] = nx * ((q % 3 - 1) + ny * (q / 3 - 1));
  }
}

RawSkeleton VoxelCoder::Impl::run()
{
  std::unique_ptr<StageTimer> timer(new StageTimer{ *this, "coder(all)" });
  const std::uint64_t n = mask.vesselCount();
  out.vesselVoxels = n;
  totalWork = std::max<std::uint64_t>(1, n * 6);
  // The codes' arrays (17 bytes per vessel voxel): their first touch takes a while on large
  // masks, a check point after each.
  bs.assign(n, kInf);
  checkpoint();
  aux.assign(n, 0);
  checkpoint();
  flags.assign(n, 0);
  ss.assign(n, kInf);
  checkpoint();
  order.reserve(n);
  // The BS code runs beside the first propagation(s); buildClusters() waits for it.
  startBoundaryCode();

  // `sources` empty: the SS code from the root is already propagated.
  const auto handle = [&](const std::vector<std::uint32_t>& sources, bool chooseRoot)
  {
    if (!sources.empty())
    {
      propagate(sources);
    }
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
        const std::uint32_t root = coarseExtremity(static_cast<std::uint32_t>(lin));
        if (root != kNoVoxel && !(flags[mask.rank(root)] & kComponent))
        {
          propagate({ root });
          if (ss[mask.rank(lin)] != kInf) // else the blocks joined two components: exact search
          {
            for (std::uint32_t v : order)
            {
              flags[mask.rank(v)] |= kComponent;
            }
            if (order.size() < par.minimumComponentSize)
            {
              resetPropagation();
              return;
            }
            handle({}, true);
            for (std::uint32_t v : order)
            {
              flags[mask.rank(v)] |= kComponent;
            }
            return;
          }
          resetPropagation();
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
  awaitBoundaryCode(); // no component was large enough: nothing waited for it yet
  std::size_t clusterBytes = clusters.capacity() * sizeof(Cluster);
  if (explorer)
  {
    // The block mask and the explorer's codes live until the end of the run.
    clusterBytes += coarseMask->memoryBytes() + explorer->ss.capacity() * (sizeof(float) + 1) +
                    explorer->order.capacity() * sizeof(std::uint32_t) +
                    explorer->peakQueue * sizeof(std::uint32_t);
  }
  // While the BS code runs, its scratch coexists with the first propagation's queue.
  out.peakBytes = n * (2 * sizeof(float) + sizeof(std::uint32_t) + 1) +
                  order.capacity() * sizeof(std::uint32_t) +
                  std::max(peakQueue * sizeof(std::uint32_t) + clusterBytes,
                    boundaryScratchBytes + peakQueue * sizeof(std::uint32_t));
  if (progress && !progress(1.0))
  {
    throw VoxelCodingAborted();
  }
  timer.reset();
  return std::move(out);
}

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

// Multi-scale Hessian tubularity of bright tubes (Frangi et al. 1998, §3: the vesselness from the
// eigenvalues |l1| <= |l2| <= |l3| of the scale-normalised Hessian, maximum over scales), measured
// only where it is needed: at the medial voxels of a candidate region (depth no smaller than any
// neighbour's), at the few scales their depth calls for, on tiles of the volume that hold such
// voxels, and for the coarse scales on a coarse grid (block means of F^3 voxels, F a power of two
// with a coarse voxel no larger than the scale): the time grows with the region, not with the
// volume. Each tile is smoothed at each scale it needs by ITK's
// SmoothingRecursiveGaussianImageFilter (Deriche's recursive Gaussian); the scale-normalised
// Hessian (sigma^2 times the central second differences, as ITK's Hessian filters normalise
// across scale), its eigen-analysis (itk::SymmetricSecondRankTensor) and the measure are computed
// at the medial voxels only (on the raw CTA 0.43 s against 2.4 s with ITK's Hessian filter).
// The other voxels of the region keep tubularity 0: TubeNeckCutter reaches them from the medial
// cores.
//
// The tiles and the coarse grids lie on the WHOLE volume's lattice (Lattice: the volume may be one
// rank's piece of a larger one, issue 19 item 2): tile n covers coarse voxels [n t, (n + 1) t) of
// the whole volume, a coarse voxel the whole volume's block [i F, (i + 1) F). A tile's smoothed box
// (the tile and 3 sigma + 1 coarse voxels around it, clamped to the whole volume) is read from the
// volume where the volume holds it and from `BlockMeans` (another rank's block means) elsewhere,
// so that a piece's measure at every site equals the single run's bit for bit.
//
// Departures from Frangi et al. (named in Docs/CENTERLINES.md): c, the structureness scale, is a
// fraction of the vessel contrast from IntensityRangeEstimator instead of half the image's
// largest Hessian norm (a region-independent, unit-free measure); alpha = beta = 0.5 as theirs.
#pragma once

#include "vtouchProgress.h"
#include "vtouchSparseVesselMask.h"
#include "vtouchVolumeView.h"

#include <itkSmoothingRecursiveGaussianImageFilter.h>
#include <itkSymmetricSecondRankTensor.h>
#include <itkImage.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <vector>

namespace vtouch
{

class RestrictedTubularity
{
public:
  struct Parameters
  {
    double alpha = 0.5;         ///< plate versus line (Frangi's alpha)
    double beta = 0.5;          ///< blob versus line (Frangi's beta)
    double structureness = 1.0; ///< Frangi's c, intensity units (caller: a contrast fraction)
    double sigmaMinimum_voxels = 0.75;
    double sigmaMaximum_mm = 4.0; ///< the largest expected radius
    int tile_voxels = 24;         ///< tile side on each grid
    /// A medial voxel of depth D (RegionDepth, voxels) is measured at the scales in
    /// [windowLow, windowHigh] * D * smallest spacing (the nearest scale when none is), since a
    /// tube of radius r responds most near sigma = r / sqrt(2)... r (Frangi et al. 1998, §2).
    double windowLow = 0.4;
    double windowHigh = 1.2;
  };
  struct Result
  {
    std::vector<float> tubularity; ///< [0, 1], indexed by region.rank()
    std::vector<float> sigma_mm;   ///< the scale of the maximum
    std::vector<double> scales_mm;
    std::uint64_t hessianVoxels = 0; ///< tile voxels the Hessian was computed on, all scales
    std::uint64_t sites = 0;         ///< medial voxels measured (the others stay 0)
    /// Block means of a tile's box the volume does not hold and BlockMeans did not give (the
    /// mean of the held part used instead: not the single run's). 0 in a single run.
    std::uint64_t blocksNotExact = 0;
  };
  /// Where the volume lies in the whole volume whose lattice the tiles and coarse grids follow:
  /// `origin` (voxels) is the volume's first voxel in the whole volume, `wholeDims` the whole
  /// volume's size (0: the volume is the whole volume).
  struct Lattice
  {
    std::array<std::int64_t, 3> origin{ 0, 0, 0 };
    std::array<std::int64_t, 3> wholeDims{ 0, 0, 0 };
  };
  /// A medial voxel to measure: its linear index in the volume, its rank in the region, and the
  /// scales in its window (bit s: scales_mm[s]).
  struct Site
  {
    std::uint64_t lin;
    std::uint32_t rank;
    std::uint32_t scales;
  };
  /// One coarse grid: the scales [first, last) with block side `factor` voxels, and the
  /// smoothing's padding around a tile on each axis (coarse voxels: 3 sigma + 1).
  struct Level
  {
    std::int64_t factor = 1;
    std::size_t first = 0, last = 0;
    std::uint32_t bits = 0;
    std::array<std::int64_t, 3> pad{ 0, 0, 0 };
    std::array<std::int64_t, 3> coarseDims{ 0, 0, 0 }; ///< the whole volume's coarse grid
    std::array<std::int64_t, 3> tiles{ 0, 0, 0 };      ///< tiles per axis on it
  };
  /// A tile to smooth: its level, its index on the level's tile grid, its box [lo, hi) (whole
  /// coarse voxels) and its sites (indices into Plan::sites).
  struct Tile
  {
    std::size_t level = 0;
    std::int64_t index = 0;
    std::array<std::int64_t, 3> lo{ 0, 0, 0 }, hi{ 0, 0, 0 };
    std::vector<std::uint32_t> sites;
    /// Whether its sites must be the single run's (a block it lacks counts in blocksNotExact);
    /// false: a distributed caller's tile whose sites decide no voxel the rank owns.
    bool exact = true;
  };
  struct Plan
  {
    Lattice lattice; ///< wholeDims set
    std::vector<double> scales_mm;
    std::vector<Site> sites;
    std::vector<Level> levels;
    std::vector<Tile> tiles; ///< by level, then tile index; only tiles with sites
  };
  /// The block mean of whole coarse voxel `coarse` at `factor` for a block the volume does not
  /// hold whole: true and `mean` set, or false (unknown).
  using BlockMeans = std::function<
    bool(std::int64_t factor, const std::array<std::int64_t, 3>& coarse, float& mean)>;

  /// Scales from sigmaMinimum_voxels (smallest spacing) to sigmaMaximum_mm, ratio sqrt(2).
  static std::vector<double> scales(const std::array<double, 3>& spacing_mm, const Parameters& p);
  /// Frangi's measure for one Hessian's eigenvalues (bright tubes: l2, l3 < 0).
  static double measure(double l1, double l2, double l3, const Parameters& p);
  /// The coarse grids of `scales_mm` on a whole volume of `wholeDims` (factor F = the largest
  /// power of two with F * smallest spacing <= sigma, at most a quarter of the largest side).
  static std::vector<Level> levels(const std::vector<double>& scales_mm,
    const std::array<double, 3>& spacing_mm,
    const std::array<std::int64_t, 3>& wholeDims,
    int tile_voxels);
  /// The mean of the whole volume's block `coarse` at `factor`, from the voxels `volume` (at
  /// `lattice`) holds (all of them when `whole`: then bit for bit the single run's); the sum in
  /// the single run's order (z, y, x). `whole` is set to whether the volume holds the block.
  template<typename T>
  static float blockMean(const VolumeView<T>& volume,
    const Lattice& lattice,
    std::int64_t factor,
    const std::array<std::int64_t, 3>& coarse,
    bool& whole);

  /// The sites, levels and tiles (step one of compute()). `progress`: the sites' search.
  template<typename T>
  static Plan plan(const VolumeView<T>& volume,
    const SparseVesselMask& region,
    const std::vector<std::uint16_t>& depth,
    const Parameters& p,
    const Lattice& lattice = Lattice(),
    const ProgressSpan& progress = ProgressSpan());
  /// Smooths the plan's tiles and measures the sites (step two). Blocks of a tile's box the
  /// volume does not hold come from `others` (when set). `progress`: a check point per tile.
  template<typename T>
  static Result run(const VolumeView<T>& volume,
    const SparseVesselMask& region,
    const Plan& plan,
    const Parameters& p,
    const BlockMeans& others = BlockMeans(),
    const ProgressSpan& progress = ProgressSpan());

  /// plan() and run() on a whole volume. `progress`: a check point per tile (may throw
  /// Cancelled).
  template<typename T>
  static Result compute(const VolumeView<T>& volume,
    const SparseVesselMask& region,
    const std::vector<std::uint16_t>& depth,
    const Parameters& p,
    const ProgressSpan& progress = ProgressSpan())
  {
    const Plan pl = plan(volume, region, depth, p, Lattice(), progress.part(0.0, 0.1));
    return run(volume, region, pl, p, BlockMeans(), progress.part(0.1, 1.0));
  }

private:
  /// The Hessian's measure at one site of a smoothed box (`g`, box size `b`, the site at `q`).
  static double siteMeasure(const float* g,
    const std::array<std::int64_t, 3>& b,
    const std::array<std::int64_t, 3>& q,
    const double spacing[3],
    double sigma,
    const Parameters& p);
};

template<typename T>
float RestrictedTubularity::blockMean(const VolumeView<T>& volume,
  const Lattice& lattice,
  std::int64_t f,
  const std::array<std::int64_t, 3>& coarse,
  bool& whole)
{
  const auto& D = lattice.wholeDims;
  const auto& o = lattice.origin;
  double sum = 0.0;
  int count = 0;
  whole = true;
  for (std::int64_t z = coarse[2] * f; z < std::min(D[2], coarse[2] * f + f); ++z)
    for (std::int64_t y = coarse[1] * f; y < std::min(D[1], coarse[1] * f + f); ++y)
      for (std::int64_t x = coarse[0] * f; x < std::min(D[0], coarse[0] * f + f); ++x)
      {
        if (!volume.inside(x - o[0], y - o[1], z - o[2]))
        {
          whole = false;
          continue;
        }
        sum += volume.at(x - o[0], y - o[1], z - o[2]);
        ++count;
      }
  return static_cast<float>(sum / std::max(1, count));
}

template<typename T>
RestrictedTubularity::Plan RestrictedTubularity::plan(const VolumeView<T>& volume,
  const SparseVesselMask& region,
  const std::vector<std::uint16_t>& depth,
  const Parameters& p,
  const Lattice& lattice,
  const ProgressSpan& progress)
{
  Plan out;
  out.lattice = lattice;
  if (out.lattice.wholeDims == std::array<std::int64_t, 3>{ 0, 0, 0 })
  {
    out.lattice.wholeDims = volume.dims;
  }
  out.scales_mm = scales(volume.spacing_mm, p);
  const std::vector<double>& sc = out.scales_mm;
  const double minSpacing = *std::min_element(volume.spacing_mm.begin(), volume.spacing_mm.end());
  // The medial voxels (depth no smaller than any neighbour's) and the scales each needs.
  ProgressCounter siteCounter(progress, region.vesselCount());
  region.forEach(
    [&](std::uint64_t lin)
    {
      siteCounter.tick();
      const std::uint32_t r = region.rank(lin);
      const auto c = volume.index(lin);
      for (std::int64_t dk = -1; dk <= 1; ++dk)
        for (std::int64_t dj = -1; dj <= 1; ++dj)
          for (std::int64_t di = -1; di <= 1; ++di)
          {
            const std::int64_t i = c[0] + di, j = c[1] + dj, k = c[2] + dk;
            if (volume.inside(i, j, k) && region.test(volume.linear(i, j, k)) &&
                depth[region.rank(volume.linear(i, j, k))] > depth[r])
            {
              return;
            }
          }
      const double radius_mm = depth[r] * minSpacing;
      std::uint32_t bits = 0;
      for (std::size_t s = 0; s < sc.size() && s < 32; ++s)
      {
        if (sc[s] >= p.windowLow * radius_mm && sc[s] <= p.windowHigh * radius_mm)
        {
          bits |= 1U << s;
        }
      }
      if (bits == 0) // below the smallest or beyond the largest scale: the nearest one
      {
        bits = sc[0] > p.windowHigh * radius_mm
                 ? 1U
                 : 1U << static_cast<unsigned>(std::min<std::size_t>(sc.size(), 32) - 1);
      }
      out.sites.push_back({ lin, r, bits });
    });
  out.levels = levels(sc, volume.spacing_mm, out.lattice.wholeDims, p.tile_voxels);
  const std::int64_t t = p.tile_voxels;
  const auto& o = out.lattice.origin;
  for (std::size_t L = 0; L < out.levels.size(); ++L)
  {
    const Level& level = out.levels[L];
    const std::int64_t f = level.factor;
    // The sites of each tile of this grid that need one of its scales (whole coarse index).
    std::vector<std::vector<std::uint32_t>> tileSites(
      static_cast<std::size_t>(level.tiles[0] * level.tiles[1] * level.tiles[2]));
    for (std::uint32_t n = 0; n < out.sites.size(); ++n)
    {
      if (out.sites[n].scales & level.bits)
      {
        const auto c = volume.index(out.sites[n].lin);
        const std::array<std::int64_t, 3> w{ c[0] + o[0], c[1] + o[1], c[2] + o[2] };
        tileSites[static_cast<std::size_t>(
                    w[0] / f / t +
                    level.tiles[0] * (w[1] / f / t + level.tiles[1] * (w[2] / f / t)))]
          .push_back(n);
      }
    }
    for (std::size_t tile = 0; tile < tileSites.size(); ++tile)
    {
      if (tileSites[tile].empty())
      {
        continue;
      }
      Tile x;
      x.level = L;
      x.index = static_cast<std::int64_t>(tile);
      const std::array<std::int64_t, 3> t0{ (x.index % level.tiles[0]) * t,
        ((x.index / level.tiles[0]) % level.tiles[1]) * t,
        (x.index / (level.tiles[0] * level.tiles[1])) * t };
      for (int a = 0; a < 3; ++a)
      {
        x.lo[a] = std::max<std::int64_t>(0, t0[a] - level.pad[a]);
        x.hi[a] = std::min(level.coarseDims[a], t0[a] + t + level.pad[a]);
      }
      x.sites = std::move(tileSites[tile]);
      out.tiles.push_back(std::move(x));
    }
  }
  return out;
}

template<typename T>
RestrictedTubularity::Result RestrictedTubularity::run(const VolumeView<T>& volume,
  const SparseVesselMask& region,
  const Plan& pl,
  const Parameters& p,
  const BlockMeans& others,
  const ProgressSpan& progress)
{
  using Image = itk::Image<float, 3>;
  using Smoothing = itk::SmoothingRecursiveGaussianImageFilter<Image, Image>;
  Result result;
  result.tubularity.assign(region.vesselCount(), 0.0F);
  result.sigma_mm.assign(region.vesselCount(), 0.0F);
  result.scales_mm = pl.scales_mm;
  result.sites = pl.sites.size();
  const std::vector<double>& sc = pl.scales_mm;
  const auto& o = pl.lattice.origin;
  const auto runTile = [&](const Tile& tile)
  {
    const Level& level = pl.levels[tile.level];
    const std::int64_t f = level.factor;
    const auto& b0 = tile.lo;
    const auto& b1 = tile.hi;
    if (b1[0] - b0[0] < 4 || b1[1] - b0[1] < 4 || b1[2] - b0[2] < 4)
    {
      return std::uint64_t{ 0 }; // too small for the recursive Gaussian: left unmeasured (0)
    }
    std::uint32_t needed = 0;
    for (std::uint32_t n : tile.sites)
    {
      needed |= pl.sites[n].scales & level.bits;
    }
    auto image = Image::New();
    Image::RegionType box;
    box.SetSize({ { static_cast<itk::SizeValueType>(b1[0] - b0[0]),
      static_cast<itk::SizeValueType>(b1[1] - b0[1]),
      static_cast<itk::SizeValueType>(b1[2] - b0[2]) } });
    image->SetRegions(box);
    const double spacing[3] = {
      f * volume.spacing_mm[0], f * volume.spacing_mm[1], f * volume.spacing_mm[2]
    };
    image->SetSpacing(spacing);
    image->Allocate();
    float* out = image->GetBufferPointer();
    // Block means of the input voxels (another rank's where this volume lacks the block).
    for (std::int64_t k = b0[2]; k < b1[2]; ++k)
      for (std::int64_t j = b0[1]; j < b1[1]; ++j)
        for (std::int64_t i = b0[0]; i < b1[0]; ++i)
        {
          bool whole = true;
          float mean = blockMean(volume, pl.lattice, f, { i, j, k }, whole);
          if (!whole && !(others && others(f, { i, j, k }, mean)) && tile.exact)
          {
            ++result.blocksNotExact;
          }
          *out++ = mean;
        }
    std::uint64_t computed = 0;
    const std::array<std::int64_t, 3> bs{ b1[0] - b0[0], b1[1] - b0[1], b1[2] - b0[2] };
    for (std::size_t s = level.first; s < level.last; ++s)
    {
      if (!(needed & (1U << s)))
      {
        continue;
      }
      auto smooth = Smoothing::New();
      smooth->SetInput(image);
      smooth->SetSigma(sc[s]);
      smooth->SetNormalizeAcrossScale(false);
      smooth->Update();
      computed += static_cast<std::uint64_t>(box.GetNumberOfPixels());
      const float* g = smooth->GetOutput()->GetBufferPointer();
      for (std::uint32_t n : tile.sites)
      {
        if (!(pl.sites[n].scales & (1U << s)))
        {
          continue;
        }
        const auto c = volume.index(pl.sites[n].lin);
        const std::array<std::int64_t, 3> q{
          (c[0] + o[0]) / f - b0[0], (c[1] + o[1]) / f - b0[1], (c[2] + o[2]) / f - b0[2]
        };
        const double v = siteMeasure(g, bs, q, spacing, sc[s], p);
        const std::uint32_t r = pl.sites[n].rank;
        if (v > result.tubularity[r])
        {
          result.tubularity[r] = static_cast<float>(v);
          result.sigma_mm[r] = static_cast<float>(sc[s]);
        }
      }
    }
    return computed;
  };
  // One tile after another; ITK smooths each tile on its own thread pool. (Tiles on two
  // threads of our own, each with a one-work-unit ITK filter, lost tiles' results now and then
  // on large trees: not done.) A check point before each tile.
  const std::size_t levels = std::max<std::size_t>(1, pl.levels.size());
  const double levelShare = 1.0 / static_cast<double>(levels);
  std::vector<std::size_t> perLevel(levels, 0), doneInLevel(levels, 0);
  for (const Tile& tile : pl.tiles)
  {
    ++perLevel[tile.level];
  }
  for (const Tile& tile : pl.tiles)
  {
    const std::size_t L = tile.level;
    progress.part(levelShare * static_cast<double>(L), levelShare * static_cast<double>(L + 1))
      .report(static_cast<double>(doneInLevel[L]++) / static_cast<double>(perLevel[L]));
    result.hessianVoxels += runTile(tile);
  }
  return result;
}

} // namespace vtouch

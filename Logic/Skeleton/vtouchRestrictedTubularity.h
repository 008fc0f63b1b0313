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
  };

  /// Scales from sigmaMinimum_voxels (smallest spacing) to sigmaMaximum_mm, ratio sqrt(2).
  static std::vector<double> scales(const std::array<double, 3>& spacing_mm, const Parameters& p);
  /// Frangi's measure for one Hessian's eigenvalues (bright tubes: l2, l3 < 0).
  static double measure(double l1, double l2, double l3, const Parameters& p);

  /// `progress`: a check point per tile (may throw Cancelled).
  template<typename T>
  static Result compute(const VolumeView<T>& volume,
    const SparseVesselMask& region,
    const std::vector<std::uint16_t>& depth,
    const Parameters& p,
    const ProgressSpan& progress = ProgressSpan());
};

template<typename T>
RestrictedTubularity::Result RestrictedTubularity::compute(const VolumeView<T>& volume,
  const SparseVesselMask& region,
  const std::vector<std::uint16_t>& depth,
  const Parameters& p,
  const ProgressSpan& progress)
{
  using Image = itk::Image<float, 3>;
  using Smoothing = itk::SmoothingRecursiveGaussianImageFilter<Image, Image>;
  Result result;
  result.tubularity.assign(region.vesselCount(), 0.0F);
  result.sigma_mm.assign(region.vesselCount(), 0.0F);
  result.scales_mm = scales(volume.spacing_mm, p);
  const std::vector<double>& sc = result.scales_mm;
  const double minSpacing = *std::min_element(volume.spacing_mm.begin(), volume.spacing_mm.end());
  const auto& d = volume.dims;
  // The medial voxels (depth no smaller than any neighbour's) and the scales each needs.
  struct Site
  {
    std::uint64_t lin;
    std::uint32_t rank;
    std::uint32_t scales; // bit s: sc[s] lies in the voxel's window
  };
  std::vector<Site> sites;
  // The sites' search is a tenth of the work; the tiles the rest.
  ProgressCounter siteCounter(progress.part(0.0, 0.1), region.vesselCount());
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
      sites.push_back({ lin, r, bits });
    });
  result.sites = sites.size();
  // Group the scales by grid: factor F = the largest power of two with F * spacing <= sigma.
  std::vector<std::int64_t> factor(sc.size(), 1);
  for (std::size_t s = 0; s < sc.size(); ++s)
  {
    while (
      2 * factor[s] * minSpacing <= sc[s] && 2 * factor[s] <= std::max({ d[0], d[1], d[2] }) / 4)
    {
      factor[s] *= 2;
    }
  }
  const std::int64_t t = p.tile_voxels;
  // The grids (runs of scales with one factor), for the progress of each.
  std::size_t levels = 1;
  for (std::size_t s = 1; s < sc.size(); ++s)
  {
    levels += factor[s] != factor[s - 1] ? 1 : 0;
  }
  std::size_t level = 0;
  for (std::size_t first = 0; first < sc.size(); ++level)
  {
    const std::int64_t f = factor[first];
    std::size_t last = first;
    std::uint32_t levelBits = 0;
    while (last < sc.size() && factor[last] == f)
    {
      levelBits |= last < 32 ? 1U << last : 0U;
      ++last;
    }
    const std::array<std::int64_t, 3> cd{
      (d[0] + f - 1) / f, (d[1] + f - 1) / f, (d[2] + f - 1) / f
    };
    const std::array<std::int64_t, 3> tiles{
      (cd[0] + t - 1) / t, (cd[1] + t - 1) / t, (cd[2] + t - 1) / t
    };
    // The sites of each tile of this grid that need one of its scales.
    std::vector<std::vector<std::uint32_t>> tileSites(
      static_cast<std::size_t>(tiles[0] * tiles[1] * tiles[2]));
    for (std::uint32_t n = 0; n < sites.size(); ++n)
    {
      if (sites[n].scales & levelBits)
      {
        const auto c = volume.index(sites[n].lin);
        tileSites[static_cast<std::size_t>(
                    c[0] / f / t + tiles[0] * (c[1] / f / t + tiles[1] * (c[2] / f / t)))]
          .push_back(n);
      }
    }
    const double sigmaMax = sc[last - 1];
    std::array<std::int64_t, 3> pad;
    for (int a = 0; a < 3; ++a)
    {
      pad[a] =
        static_cast<std::int64_t>(std::ceil(3.0 * sigmaMax / (f * volume.spacing_mm[a]))) + 1;
    }
    const auto runTile = [&](std::size_t tile)
    {
      const std::vector<std::uint32_t>& here = tileSites[tile];
      std::uint32_t needed = 0;
      for (std::uint32_t n : here)
      {
        needed |= sites[n].scales & levelBits;
      }
      const auto ti = static_cast<std::int64_t>(tile);
      const std::array<std::int64_t, 3> t0{
        (ti % tiles[0]) * t, ((ti / tiles[0]) % tiles[1]) * t, (ti / (tiles[0] * tiles[1])) * t
      };
      std::array<std::int64_t, 3> b0, b1;
      for (int a = 0; a < 3; ++a)
      {
        b0[a] = std::max<std::int64_t>(0, t0[a] - pad[a]);
        b1[a] = std::min(cd[a], t0[a] + t + pad[a]);
      }
      if (b1[0] - b0[0] < 4 || b1[1] - b0[1] < 4 || b1[2] - b0[2] < 4)
      {
        return std::uint64_t{ 0 }; // too small for the recursive Gaussian: left unmeasured (0)
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
      // Block means of the input voxels.
      for (std::int64_t k = b0[2]; k < b1[2]; ++k)
        for (std::int64_t j = b0[1]; j < b1[1]; ++j)
          for (std::int64_t i = b0[0]; i < b1[0]; ++i)
          {
            double sum = 0.0;
            int count = 0;
            for (std::int64_t z = k * f; z < std::min(d[2], k * f + f); ++z)
              for (std::int64_t y = j * f; y < std::min(d[1], j * f + f); ++y)
                for (std::int64_t x = i * f; x < std::min(d[0], i * f + f); ++x)
                {
                  sum += volume.at(x, y, z);
                  ++count;
                }
            *out++ = static_cast<float>(sum / std::max(1, count));
          }
      std::uint64_t computed = 0;
      for (std::size_t s = first; s < last; ++s)
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
        const std::int64_t bx = b1[0] - b0[0], by = b1[1] - b0[1], bz = b1[2] - b0[2];
        // Scale-normalised second derivatives (sigma^2, Lindeberg's gamma = 2, as ITK's
        // NormalizeAcrossScale) by central differences of the smoothed tile.
        const double norm = sc[s] * sc[s];
        for (std::uint32_t n : here)
        {
          if (!(sites[n].scales & (1U << s)))
          {
            continue;
          }
          const auto c = volume.index(sites[n].lin);
          const std::int64_t q[3] = { c[0] / f - b0[0], c[1] / f - b0[1], c[2] / f - b0[2] };
          const auto at = [&](int dx, int dy, int dz)
          {
            const std::int64_t x = std::clamp<std::int64_t>(q[0] + dx, 0, bx - 1);
            const std::int64_t y = std::clamp<std::int64_t>(q[1] + dy, 0, by - 1);
            const std::int64_t z = std::clamp<std::int64_t>(q[2] + dz, 0, bz - 1);
            return static_cast<double>(g[x + bx * (y + by * z)]);
          };
          itk::SymmetricSecondRankTensor<double, 3> tensor;
          const double centre = at(0, 0, 0);
          const int e3[3][3] = { { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 } };
          for (unsigned a = 0; a < 3; ++a)
          {
            const double h = spacing[a];
            tensor(a, a) = norm *
                           (at(e3[a][0], e3[a][1], e3[a][2]) - 2.0 * centre +
                             at(-e3[a][0], -e3[a][1], -e3[a][2])) /
                           (h * h);
            for (unsigned b = a + 1; b < 3; ++b)
            {
              const int u[3] = { e3[a][0] + e3[b][0], e3[a][1] + e3[b][1], e3[a][2] + e3[b][2] };
              const int v[3] = { e3[a][0] - e3[b][0], e3[a][1] - e3[b][1], e3[a][2] - e3[b][2] };
              tensor(a, b) = norm *
                             (at(u[0], u[1], u[2]) - at(v[0], v[1], v[2]) -
                               at(-v[0], -v[1], -v[2]) + at(-u[0], -u[1], -u[2])) /
                             (4.0 * spacing[a] * spacing[b]);
            }
          }
          itk::SymmetricSecondRankTensor<double, 3>::EigenValuesArrayType e;
          tensor.ComputeEigenValues(e);
          std::array<double, 3> l{ e[0], e[1], e[2] };
          std::sort(
            l.begin(), l.end(), [](double a, double b) { return std::abs(a) < std::abs(b); });
          const double v = measure(l[0], l[1], l[2], p);
          const std::uint32_t r = sites[n].rank;
          if (v > result.tubularity[r])
          {
            result.tubularity[r] = static_cast<float>(v);
            result.sigma_mm[r] = static_cast<float>(sc[s]);
          }
        }
      }
      return computed;
    };
    std::vector<std::size_t> work;
    for (std::size_t tile = 0; tile < tileSites.size(); ++tile)
    {
      if (!tileSites[tile].empty())
      {
        work.push_back(tile);
      }
    }
    // One tile after another; ITK smooths each tile on its own thread pool. (Tiles on two
    // threads of our own, each with a one-work-unit ITK filter, lost tiles' results now and then
    // on large trees: not done.) A check point before each tile.
    const double levelShare = 0.9 / static_cast<double>(levels);
    const ProgressSpan levelProgress = progress.part(0.1 + levelShare * static_cast<double>(level),
      0.1 + levelShare * static_cast<double>(level + 1));
    for (std::size_t w = 0; w < work.size(); ++w)
    {
      levelProgress.report(static_cast<double>(w) / static_cast<double>(work.size()));
      result.hessianVoxels += runTile(work[w]);
    }
    first = last;
  }
  return result;
}

} // namespace vtouch

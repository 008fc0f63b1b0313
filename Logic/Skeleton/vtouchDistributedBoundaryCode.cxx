// vtouch::DistributedBoundaryCode: the exact BS code on the owned voxels (see the header).
#include "vtouchDistributedBoundaryCode.h"

#include "vtouchSkeletonBoundaryCodeStage.h"
#include "vtouchSkeletonRunMeter.h"
#include "vtouchSkeletonVoxelCodes.h"
#include "vtouchSkeletonVoxelGrid.h"

#include <algorithm>
#include <cmath>
#include <functional>

namespace vtouch
{
namespace
{
using Index = std::array<std::int64_t, 3>;

/// The BS code of `mask`, a box whose first voxel is `origin_Whole`.
std::vector<float> boundaryCode(const SparseVesselMask& mask,
  const std::array<double, 3>& spacing_mm,
  const Index& origin_Whole)
{
  const skeleton::VoxelGrid grid(mask, spacing_mm, 0.0);
  const std::function<bool(double)> none;
  skeleton::RunMeter meter(none);
  std::vector<float> bs(mask.vesselCount(), skeleton::VoxelCodes::kInf);
  skeleton::BoundaryCodeStage stage(grid, meter, bs);
  stage.setOrigin(origin_Whole);
  stage.start();
  stage.await();
  return bs;
}

Index localIndex(const Index& dims, std::uint64_t lin)
{
  const auto l = static_cast<std::int64_t>(lin);
  return { l % dims[0], (l / dims[0]) % dims[1], l / (dims[0] * dims[1]) };
}

std::uint64_t linear(const Index& dims, const Index& local)
{
  return static_cast<std::uint64_t>(local[0] + dims[0] * (local[1] + dims[1] * local[2]));
}
} // namespace

DistributedBoundaryCode::Result DistributedBoundaryCode::compute(const PieceLayout& layout,
  const SparseVesselMask& pieceMask,
  const std::array<double, 3>& spacing_mm,
  RankCollectives& collectives)
{
  Result out;
  const auto me = static_cast<std::size_t>(layout.rank);
  const VoxelBox& held = layout.held[me];
  const VoxelBox& owned = layout.owned[me];
  const Index pieceDims = layout.pieceDims();
  // Step 1: the bound.
  out.bs_mm = boundaryCode(pieceMask, spacing_mm, held.lo);
  double bound = 0.0;
  pieceMask.forEach(
    [&](std::uint64_t lin)
    {
      if (owned.contains(layout.toWhole(localIndex(pieceDims, lin))))
      {
        bound = std::max(bound, static_cast<double>(out.bs_mm[pieceMask.rank(lin)]));
      }
    });
  const std::vector<std::vector<double>> bounds =
    collectives.allGather(std::vector<double>{ bound });
  ++out.exchanges;
  out.gatheredValues += bounds.size();
  std::vector<VoxelBox> extended(bounds.size());
  for (std::size_t r = 0; r < bounds.size(); ++r)
  {
    const double b = bounds[r].empty() ? 0.0 : bounds[r][0];
    if (!std::isfinite(b))
    {
      out.message = "DistributedBoundaryCode: rank " + std::to_string(r) +
                    "'s held box has no background voxel, so no bound of its BS code";
      out.bs_mm.clear();
      return out;
    }
    out.largestBound_mm = std::max(out.largestBound_mm, b);
    extended[r] = layout.owned[r];
    for (int a = 0; a < 3; ++a)
    {
      const auto grow = static_cast<std::int64_t>(std::ceil(b / spacing_mm[a]));
      extended[r].lo[a] = std::max<std::int64_t>(0, extended[r].lo[a] - grow);
      extended[r].hi[a] = std::min<std::int64_t>(layout.wholeDims[a] - 1, extended[r].hi[a] + grow);
    }
  }
  // Step 2: the owned voxels the others' extended boxes need and their held boxes lack.
  std::vector<std::vector<std::int64_t>> toRank(bounds.size());
  pieceMask.forEach(
    [&](std::uint64_t lin)
    {
      const Index w = layout.toWhole(localIndex(pieceDims, lin));
      if (!owned.contains(w))
      {
        return;
      }
      for (std::size_t r = 0; r < extended.size(); ++r)
      {
        if (r != me && extended[r].contains(w) && !layout.held[r].contains(w))
        {
          toRank[r].push_back(layout.wholeLinear(w));
        }
      }
    });
  std::vector<std::int64_t> mine;
  for (std::size_t r = 0; r < toRank.size(); ++r)
  {
    if (!toRank[r].empty())
    {
      mine.push_back(static_cast<std::int64_t>(r));
      mine.push_back(static_cast<std::int64_t>(toRank[r].size()));
      mine.insert(mine.end(), toRank[r].begin(), toRank[r].end());
    }
  }
  const std::vector<std::vector<std::int64_t>> all = collectives.allGather(mine);
  ++out.exchanges;
  const VoxelBox& e = extended[me];
  const Index eDims{ e.hi[0] - e.lo[0] + 1, e.hi[1] - e.lo[1] + 1, e.hi[2] - e.lo[2] + 1 };
  out.extendedVoxels = static_cast<std::uint64_t>(eDims[0] * eDims[1] * eDims[2]);
  const auto eLinear = [&](const Index& w) {
    return linear(eDims, { w[0] - e.lo[0], w[1] - e.lo[1], w[2] - e.lo[2] });
  };
  SparseVesselMask eMask(eDims);
  pieceMask.forEach(
    [&](std::uint64_t lin)
    {
      const Index w = layout.toWhole(localIndex(pieceDims, lin));
      if (e.contains(w))
      {
        eMask.set(eLinear(w));
      }
    });
  for (const std::vector<std::int64_t>& v : all)
  {
    out.gatheredValues += v.size();
    for (std::size_t p = 0; p + 1 < v.size();)
    {
      const auto count = static_cast<std::size_t>(v[p + 1]);
      out.sentVoxels += count;
      if (static_cast<std::size_t>(v[p]) == me)
      {
        for (std::size_t q = 0; q < count; ++q)
        {
          eMask.set(eLinear(layout.wholeIndex(v[p + 2 + q])));
        }
      }
      p += 2 + count;
    }
  }
  eMask.finalize();
  const std::vector<float> eBs = boundaryCode(eMask, spacing_mm, e.lo);
  pieceMask.forEach(
    [&](std::uint64_t lin)
    {
      const Index w = layout.toWhole(localIndex(pieceDims, lin));
      if (owned.contains(w))
      {
        out.bs_mm[pieceMask.rank(lin)] = eBs[eMask.rank(eLinear(w))];
      }
    });
  out.ok = true;
  return out;
}

} // namespace vtouch

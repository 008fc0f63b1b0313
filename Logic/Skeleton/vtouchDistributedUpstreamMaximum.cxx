// vtouch::DistributedUpstreamMaximum: the farthest tip above every voxel, in rounds (see the
// header for why exact).
#include "vtouchDistributedUpstreamMaximum.h"

#include "vtouchCollectiveRounds.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>

namespace vtouch
{
namespace
{
using Index = std::array<std::int64_t, 3>;
constexpr float kInf = std::numeric_limits<float>::infinity();

Index coordsOf(std::uint64_t lin, const Index& d)
{
  const auto l = static_cast<std::int64_t>(lin);
  return { l % d[0], (l / d[0]) % d[1], l / (d[0] * d[1]) };
}

/// `mask`'s vessel voxels with a finite SS, in decreasing SS (ties by index: any order settles).
std::vector<std::uint64_t> descending(const SparseVesselMask& mask, const std::vector<float>& ss)
{
  std::vector<std::uint64_t> order;
  mask.forEach(
    [&](std::uint64_t lin)
    {
      if (ss[mask.rank(lin)] != kInf)
      {
        order.push_back(lin);
      }
    });
  std::stable_sort(order.begin(),
    order.end(),
    [&](std::uint64_t a, std::uint64_t b) { return ss[mask.rank(a)] > ss[mask.rank(b)]; });
  return order;
}

/// One pass in decreasing SS over `order`: U(v) = max(U(v), U(w)) for every 26-neighbour w in
/// the mask with SS(w) > SS(v). `rose(lin)` is called for each voxel whose U it raised.
template<class Rose>
void risingPass(const SparseVesselMask& mask,
  const std::vector<float>& ss,
  const std::vector<std::uint64_t>& order,
  std::vector<float>& up,
  Rose&& rose)
{
  const Index d = mask.dims();
  for (const std::uint64_t lin : order)
  {
    const Index c = coordsOf(lin, d);
    const std::uint32_t r = mask.rank(lin);
    float best = up[r];
    for (std::int64_t dz = -1; dz <= 1; ++dz)
      for (std::int64_t dy = -1; dy <= 1; ++dy)
        for (std::int64_t dx = -1; dx <= 1; ++dx)
        {
          const Index n{ c[0] + dx, c[1] + dy, c[2] + dz };
          if (n[0] < 0 || n[1] < 0 || n[2] < 0 || n[0] >= d[0] || n[1] >= d[1] || n[2] >= d[2])
          {
            continue;
          }
          const auto w = static_cast<std::uint64_t>(n[0] + d[0] * (n[1] + d[1] * n[2]));
          if (mask.test(w))
          {
            const std::uint32_t rw = mask.rank(w);
            if (ss[rw] > ss[r] && ss[rw] != kInf)
            {
              best = std::max(best, up[rw]);
            }
          }
        }
    if (best > up[r])
    {
      up[r] = best;
      rose(lin);
    }
  }
}
} // namespace

DistributedUpstreamMaximum::DistributedUpstreamMaximum(PieceLayout layout,
  const SparseVesselMask& pieceMask,
  const std::vector<float>& ss_mm)
  : Layout(std::move(layout))
  , Mask(pieceMask)
  , Ss(ss_mm)
{
  this->Layout.check();
  if (this->Mask.dims() != this->Layout.pieceDims())
  {
    throw std::invalid_argument("DistributedUpstreamMaximum: the piece mask is not the held box");
  }
  if (this->Ss.size() != this->Mask.vesselCount())
  {
    throw std::invalid_argument("DistributedUpstreamMaximum: " + std::to_string(this->Ss.size()) +
                                " SS values for " + std::to_string(this->Mask.vesselCount()) +
                                " vessel voxels");
  }
  const VoxelBox& held = this->Layout.mine();
  const VoxelBox& owned = this->Layout.owned[static_cast<std::size_t>(this->Layout.rank)];
  for (int a = 0; a < 3; ++a)
  {
    const bool lowShared = owned.lo[a] > 0,
               highShared = owned.hi[a] < this->Layout.wholeDims[a] - 1;
    if ((lowShared && held.lo[a] > owned.lo[a] - 1) || (highShared && held.hi[a] < owned.hi[a] + 1))
    {
      throw std::invalid_argument("DistributedUpstreamMaximum: the held box must reach one voxel "
                                  "past the owned one on every shared face (a ghost layer)");
    }
  }
  this->Upstream = this->Ss;
  this->Descending = descending(this->Mask, this->Ss);
}

void DistributedUpstreamMaximum::pass(std::vector<std::uint64_t>& rose)
{
  const VoxelBox& owned = this->Layout.owned[static_cast<std::size_t>(this->Layout.rank)];
  const Index d = this->Mask.dims();
  risingPass(this->Mask,
    this->Ss,
    this->Descending,
    this->Upstream,
    [&](std::uint64_t lin)
    {
      if (owned.contains(this->Layout.toWhole(coordsOf(lin, d))))
      {
        rose.push_back(lin);
      }
    });
}

RoundsOutcome DistributedUpstreamMaximum::run(RankCollectives& collectives, int maximumRounds)
{
  const CollectiveRounds rounds({ "the farthest tips across the pieces",
                                  "a network whose rising paths cross between pieces that often "
                                  "is not a vessel tree",
                                  "extract on one rank" },
    CollectiveRounds::Payload::IndicesAndValues);
  const Index d = this->Mask.dims();
  const VoxelBox& held = this->Layout.mine();
  std::vector<VoxelBox> others;
  for (int r = 0; r < this->Layout.ranks(); ++r)
  {
    if (r != this->Layout.rank)
    {
      others.push_back(this->Layout.held[static_cast<std::size_t>(r)]);
    }
  }
  return rounds.run(
    collectives,
    [&](const CollectiveRounds::Exchange& previous)
    {
      // Take the owners' values of the voxels this rank holds.
      for (int r = 0; r < static_cast<int>(previous.indices.size()); ++r)
      {
        const auto ur = static_cast<std::size_t>(r);
        if (r == this->Layout.rank || previous.indices[ur].size() != previous.values[ur].size())
        {
          continue;
        }
        for (std::size_t q = 0; q < previous.indices[ur].size(); ++q)
        {
          const Index c = this->Layout.wholeIndex(previous.indices[ur][q]);
          if (!held.contains(c))
          {
            continue;
          }
          const Index l = this->Layout.toLocal(c);
          const auto lin = static_cast<std::uint64_t>(l[0] + d[0] * (l[1] + d[1] * l[2]));
          const auto value = static_cast<float>(previous.values[ur][q]);
          if (this->Mask.test(lin) && value > this->Upstream[this->Mask.rank(lin)])
          {
            this->Upstream[this->Mask.rank(lin)] = value;
          }
        }
      }
      std::vector<std::uint64_t> rose;
      this->pass(rose);
      std::sort(rose.begin(), rose.end());
      rose.erase(std::unique(rose.begin(), rose.end()), rose.end());
      CollectiveRounds::Report report;
      for (const std::uint64_t lin : rose)
      {
        const Index c = this->Layout.toWhole(coordsOf(lin, d));
        for (const VoxelBox& other : others)
        {
          if (other.contains(c))
          {
            report.indices.push_back(this->Layout.wholeLinear(c));
            report.values.push_back(static_cast<double>(this->Upstream[this->Mask.rank(lin)]));
            break;
          }
        }
      }
      return report;
    },
    maximumRounds);
}

std::vector<float> DistributedUpstreamMaximum::wholeVolume(const SparseVesselMask& mask,
  const std::vector<float>& ss_mm)
{
  if (ss_mm.size() != mask.vesselCount())
  {
    throw std::invalid_argument("DistributedUpstreamMaximum::wholeVolume: one SS value per vessel "
                                "voxel is needed");
  }
  std::vector<float> up = ss_mm;
  risingPass(mask, ss_mm, descending(mask, ss_mm), up, [](std::uint64_t) {});
  return up;
}

} // namespace vtouch

// vtouch::DistributedSeedCode: the SS code's rounds across pieces (see the header for why exact).
#include "vtouchDistributedSeedCode.h"

#include "vtouchCollectiveRounds.h"
#include "vtouchSkeletonRunMeter.h"
#include "vtouchSkeletonSeedCodeStage.h"
#include "vtouchSkeletonVoxelCodes.h"
#include "vtouchSkeletonVoxelGrid.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>

namespace vtouch
{
namespace
{
std::string boxText(const std::array<std::int64_t, 3>& c)
{
  return "(" + std::to_string(c[0]) + ", " + std::to_string(c[1]) + ", " + std::to_string(c[2]) +
         ")";
}

/// The SS code's loop: indices and their distances, the cap's words (the project rule in the
/// header).
CollectiveRounds roundsOfSsCode()
{
  return CollectiveRounds({ "the SS code across the pieces",
                            "a network whose shortest paths cross between pieces that often is "
                            "not a vessel tree",
                            "extract on one rank" },
    CollectiveRounds::Payload::IndicesAndValues);
}
} // namespace

/// The piece's grid, codes and stage (SeedCodeStage on the held box, no progress of its own).
struct DistributedSeedCode::Impl
{
  Impl(PieceLayout l, const SparseVesselMask& m, const std::array<double, 3>& spacing_mm)
    : layout(std::move(l))
    , mask(m)
    , grid(m, spacing_mm, 0.0)
    , meter(noProgress)
    , stage(grid, meter, codes, 0.0)
  {
    for (int r = 0; r < layout.ranks(); ++r)
    {
      if (r != layout.rank)
      {
        othersHeld.push_back(layout.held[static_cast<std::size_t>(r)]);
      }
    }
  }

  std::array<std::int64_t, 3> localIndex(std::uint64_t lin) const
  {
    std::int64_t c[3];
    grid.coords(lin, c);
    return { c[0], c[1], c[2] };
  }
  std::uint64_t localLinear(const std::array<std::int64_t, 3>& l) const
  {
    return grid.linOf(l[0], l[1], l[2]);
  }
  /// The voxels this rank owns whose SS fell this round and another rank holds.
  void report(std::vector<std::uint32_t>& lowered,
    std::vector<std::int64_t>& indices,
    std::vector<double>& values) const;
  /// The received voxels this rank holds whose SS they lower, as sources of the next round.
  std::vector<skeleton::SeedCodeStage::Source> received(
    const std::vector<std::vector<std::int64_t>>& indices,
    const std::vector<std::vector<double>>& values) const;

  PieceLayout layout;
  const SparseVesselMask& mask;
  std::vector<VoxelBox> othersHeld;
  skeleton::VoxelGrid grid;
  skeleton::VoxelCodes codes;
  std::function<bool(double)> noProgress;
  skeleton::RunMeter meter;
  skeleton::SeedCodeStage stage;
};

void DistributedSeedCode::Impl::report(std::vector<std::uint32_t>& lowered,
  std::vector<std::int64_t>& indices,
  std::vector<double>& values) const
{
  std::sort(lowered.begin(), lowered.end());
  lowered.erase(std::unique(lowered.begin(), lowered.end()), lowered.end());
  const VoxelBox& owned = layout.owned[static_cast<std::size_t>(layout.rank)];
  for (const std::uint32_t lin : lowered)
  {
    const std::array<std::int64_t, 3> c = layout.toWhole(localIndex(lin));
    if (!owned.contains(c))
    {
      continue; // its owner reports it
    }
    for (const VoxelBox& other : othersHeld)
    {
      if (other.contains(c))
      {
        indices.push_back(layout.wholeLinear(c));
        values.push_back(static_cast<double>(codes.ss[mask.rank(lin)])); // exact: float in double
        break;
      }
    }
  }
}

std::vector<skeleton::SeedCodeStage::Source> DistributedSeedCode::Impl::received(
  const std::vector<std::vector<std::int64_t>>& indices,
  const std::vector<std::vector<double>>& values) const
{
  std::vector<skeleton::SeedCodeStage::Source> sources;
  const VoxelBox& held = layout.mine();
  for (int r = 0; r < layout.ranks(); ++r)
  {
    const auto ur = static_cast<std::size_t>(r);
    if (r == layout.rank || indices[ur].size() != values[ur].size())
    {
      continue;
    }
    for (std::size_t q = 0; q < indices[ur].size(); ++q)
    {
      const std::array<std::int64_t, 3> c = layout.wholeIndex(indices[ur][q]);
      if (!held.contains(c))
      {
        continue;
      }
      const std::uint64_t lin = localLinear(layout.toLocal(c));
      const auto d = static_cast<float>(values[ur][q]);
      if (mask.test(lin) && d < codes.ss[mask.rank(lin)])
      {
        sources.push_back({ static_cast<std::uint32_t>(lin), d });
      }
    }
  }
  return sources;
}

DistributedSeedCode::DistributedSeedCode(PieceLayout layout,
  const SparseVesselMask& pieceMask,
  const std::array<double, 3>& spacing_mm)
{
  const auto fail = [](const std::string& what)
  { throw std::invalid_argument("DistributedSeedCode: " + what); };
  layout.check();
  for (double s : spacing_mm)
  {
    if (!(s > 0.0) || !std::isfinite(s))
    {
      fail("the voxel spacing must be positive and finite");
    }
  }
  if (pieceMask.dims() != layout.pieceDims())
  {
    fail("the piece mask's size is not the held box's");
  }
  const auto& d = pieceMask.dims();
  if (static_cast<double>(d[0] + 2) * static_cast<double>(d[1] + 2) *
        static_cast<double>(d[2] + 2) >=
      4294967295.0)
  {
    fail("the piece is too large for 32-bit voxel indices (at most ~4e9 voxels)");
  }
  // Every 26-neighbour step must lie inside one rank's box: the owner's.
  for (int r = 0; r < layout.ranks(); ++r)
  {
    const VoxelBox& o = layout.owned[static_cast<std::size_t>(r)];
    const VoxelBox& h = layout.held[static_cast<std::size_t>(r)];
    if (o.empty())
    {
      continue;
    }
    for (int a = 0; a < 3; ++a)
    {
      const bool loShort = o.lo[a] > 0 && h.lo[a] > o.lo[a] - 1;
      const bool hiShort = o.hi[a] < layout.wholeDims[a] - 1 && h.hi[a] < o.hi[a] + 1;
      if (loShort || hiShort)
      {
        fail("rank " + std::to_string(r) +
             " holds no ghost layer past its owned voxels: a ghost margin of at least one "
             "voxel is needed");
      }
    }
  }
  this->P = std::make_unique<Impl>(std::move(layout), pieceMask, spacing_mm);
}

DistributedSeedCode::~DistributedSeedCode() = default;

DistributedSeedCode::Outcome DistributedSeedCode::run(RankCollectives& collectives,
  const std::vector<std::array<std::int64_t, 3>>& roots_Whole,
  int maximumRounds)
{
  Impl& p = *this->P;
  const std::uint64_t n = p.mask.vesselCount();
  p.codes.ss.assign(n, skeleton::VoxelCodes::kInf);
  p.codes.flags.assign(n, 0);
  // The roots: checked by their owners, the verdict shared, so that every rank throws together.
  std::vector<skeleton::SeedCodeStage::Source> sources;
  std::vector<std::int64_t> bad;
  for (const std::array<std::int64_t, 3>& c : roots_Whole)
  {
    const int owner = p.layout.ownerOf(c);
    if (owner < 0)
    {
      throw std::invalid_argument(
        "DistributedSeedCode: the root " + boxText(c) + " lies outside the volume");
    }
    if (!p.layout.mine().contains(c))
    {
      continue;
    }
    const std::uint64_t lin = p.localLinear(p.layout.toLocal(c));
    if (p.mask.test(lin))
    {
      sources.push_back({ static_cast<std::uint32_t>(lin), 0.0F });
    }
    else if (owner == p.layout.rank)
    {
      bad.push_back(p.layout.wholeLinear(c));
    }
  }
  for (const std::vector<std::int64_t>& b : collectives.allGather(bad))
  {
    if (!b.empty())
    {
      throw std::invalid_argument("DistributedSeedCode: the root " +
                                  boxText(p.layout.wholeIndex(b.front())) +
                                  " is not a vessel voxel");
    }
  }
  return roundsOfSsCode().run(
    collectives,
    [&p, &sources](const CollectiveRounds::Exchange& previous)
    {
      std::vector<skeleton::SeedCodeStage::Source> from =
        previous.rounds == 0 ? std::move(sources) : p.received(previous.indices, previous.values);
      std::vector<std::uint32_t> lowered;
      p.stage.relax(std::move(from), lowered);
      CollectiveRounds::Report report;
      p.report(lowered, report.indices, report.values);
      return report;
    },
    maximumRounds);
}

const std::vector<float>& DistributedSeedCode::ss() const
{
  return this->P->codes.ss;
}

float DistributedSeedCode::ssAt(std::uint64_t localLinear) const
{
  const Impl& p = *this->P;
  if (localLinear >= p.mask.voxelCount() || !p.mask.test(localLinear) || p.codes.ss.empty())
  {
    return skeleton::VoxelCodes::kInf;
  }
  return p.codes.ss[p.mask.rank(localLinear)];
}

} // namespace vtouch

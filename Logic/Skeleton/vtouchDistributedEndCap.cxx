// vtouch::DistributedEndCap: the double propagation's end cap across pieces, grown in rounds.
#include "vtouchDistributedEndCap.h"

#include "vtouchSkeletonEndCapRule.h"
#include "vtouchSkeletonVoxelCodes.h"
#include "vtouchSkeletonVoxelGrid.h"

#include <algorithm>
#include <cmath>

namespace vtouch
{

bool DistributedEndCap::farVoxel(RankCollectives& collectives,
  const PieceLayout& layout,
  const SparseVesselMask& pieceMask,
  double bucketWidth_mm,
  const DistributedSeedCode& code,
  Cap& cap)
{
  // Two collective steps: the last bucket over the ranks, then its largest index, each rank
  // judging the voxels it owns (each voxel once).
  const VoxelBox& owned = layout.owned[static_cast<std::size_t>(layout.rank)];
  const std::array<std::int64_t, 3> d = layout.pieceDims();
  const auto forOwnedReached = [&](const auto& f)
  {
    pieceMask.forEach(
      [&](std::uint64_t lin)
      {
        const float s = code.ss()[pieceMask.rank(lin)];
        const auto l = static_cast<std::int64_t>(lin);
        const std::array<std::int64_t, 3> w =
          layout.toWhole({ l % d[0], (l / d[0]) % d[1], l / (d[0] * d[1]) });
        if (s != skeleton::VoxelCodes::kInf && owned.contains(w))
        {
          f(s, layout.wholeLinear(w));
        }
      });
  };
  std::vector<std::int64_t> mine;
  forOwnedReached(
    [&](float s, std::int64_t)
    {
      const auto b = static_cast<std::int64_t>(skeleton::farBucket(s, bucketWidth_mm));
      mine = { mine.empty() ? b : std::max(mine[0], b) };
    });
  std::int64_t top = -1;
  for (const std::vector<std::int64_t>& v : collectives.allGather(mine))
  {
    top = v.empty() ? top : std::max(top, v[0]);
  }
  if (top < 0)
  {
    return false;
  }
  std::vector<double> best; // { whole index, SS }
  forOwnedReached(
    [&](float s, std::int64_t w)
    {
      if (static_cast<std::int64_t>(skeleton::farBucket(s, bucketWidth_mm)) == top &&
          (best.empty() || static_cast<double>(w) > best[0]))
      {
        best = { static_cast<double>(w), static_cast<double>(s) }; // exact below 2^53
      }
    });
  double farLin = -1.0;
  for (const std::vector<double>& v : collectives.allGather(best))
  {
    if (!v.empty() && v[0] > farLin)
    {
      farLin = v[0];
      cap.farSs_mm = v[1];
    }
  }
  cap.far_Whole = layout.wholeIndex(static_cast<std::int64_t>(farLin));
  return true;
}

DistributedEndCap::Cap DistributedEndCap::find(RankCollectives& collectives,
  const PieceLayout& layout,
  const SparseVesselMask& pieceMask,
  const std::array<double, 3>& spacing_mm,
  const DistributedSeedCode& code,
  double bandWidth_mm,
  bool gatherVoxels,
  int maximumRounds)
{
  Cap cap;
  const skeleton::VoxelGrid grid(pieceMask, spacing_mm, 0.0);
  if (!farVoxel(collectives, layout, pieceMask, grid.minSpacing, code, cap))
  {
    return cap; // nothing reached: every rank sees the same
  }
  // The single run's float threshold (SeedCodeStage::extremityRegion).
  const float threshold = static_cast<float>(cap.farSs_mm) - static_cast<float>(bandWidth_mm);
  const VoxelBox& held = layout.mine();
  const VoxelBox& owned = layout.owned[static_cast<std::size_t>(layout.rank)];
  std::vector<std::uint8_t> inCap(pieceMask.vesselCount(), 0);
  const auto localLinear = [&](const std::array<std::int64_t, 3>& whole)
  {
    const std::array<std::int64_t, 3> l = layout.toLocal(whole);
    return grid.linOf(l[0], l[1], l[2]);
  };
  const auto joins = [&](std::uint64_t lin)
  {
    const float s = code.ssAt(lin);
    return s != skeleton::VoxelCodes::kInf && s >= threshold && !inCap[pieceMask.rank(lin)];
  };
  std::vector<std::uint32_t> frontier;
  if (held.contains(cap.far_Whole))
  {
    frontier.push_back(static_cast<std::uint32_t>(localLinear(cap.far_Whole)));
    inCap[pieceMask.rank(frontier.back())] = 1;
  }
  std::vector<std::int64_t> mineOwned; // every cap voxel this rank owns, all rounds
  while (true)
  {
    // Flood the held box from the frontier.
    std::vector<std::int64_t> report;
    for (std::size_t q = 0; q < frontier.size(); ++q)
    {
      const std::array<std::int64_t, 3> w = layout.toWhole(grid.voxelArray(frontier[q]));
      if (owned.contains(w))
      {
        report.push_back(layout.wholeLinear(w));
      }
      grid.forNeighbours(frontier[q],
        [&](std::uint64_t u, int, std::uint32_t ru)
        {
          if (joins(u))
          {
            inCap[ru] = 1;
            frontier.push_back(static_cast<std::uint32_t>(u));
          }
        });
    }
    mineOwned.insert(mineOwned.end(), report.begin(), report.end());
    const std::vector<std::vector<std::int64_t>> all = collectives.allGather(report);
    ++cap.rounds;
    frontier.clear();
    bool any = false;
    for (int r = 0; r < layout.ranks(); ++r)
    {
      const std::vector<std::int64_t>& theirs = all[static_cast<std::size_t>(r)];
      any = any || !theirs.empty();
      if (r == layout.rank)
      {
        continue;
      }
      for (const std::int64_t w : theirs)
      {
        const std::array<std::int64_t, 3> c = layout.wholeIndex(w);
        if (!held.contains(c))
        {
          continue;
        }
        const std::uint64_t lin = localLinear(c);
        if (pieceMask.test(lin) && joins(lin))
        {
          inCap[pieceMask.rank(lin)] = 1;
          frontier.push_back(static_cast<std::uint32_t>(lin));
        }
      }
    }
    if (!any)
    {
      break;
    }
    if (cap.rounds >= maximumRounds)
    {
      cap.settled = false;
      cap.message = "the end cap across the pieces did not settle in " +
                    std::to_string(maximumRounds) + " rounds: extract on one rank";
      return cap;
    }
  }
  // The owners' sums (each cap voxel is owned by one rank), exact in doubles below 2^53.
  std::vector<std::int64_t> sums{ 0, 0, 0, static_cast<std::int64_t>(mineOwned.size()) };
  for (const std::int64_t w : mineOwned)
  {
    const std::array<std::int64_t, 3> c = layout.wholeIndex(w);
    for (int a = 0; a < 3; ++a)
    {
      sums[static_cast<std::size_t>(a)] += c[static_cast<std::size_t>(a)];
    }
  }
  for (const std::vector<std::int64_t>& s : collectives.allGather(sums))
  {
    for (int a = 0; a < 3; ++a)
    {
      cap.indexSum[static_cast<std::size_t>(a)] += s[static_cast<std::size_t>(a)];
    }
    cap.count += static_cast<std::uint64_t>(s[3]);
  }
  if (gatherVoxels)
  {
    for (const std::vector<std::int64_t>& theirs : collectives.allGather(mineOwned))
    {
      cap.voxels_Whole.insert(cap.voxels_Whole.end(), theirs.begin(), theirs.end());
    }
    std::sort(cap.voxels_Whole.begin(), cap.voxels_Whole.end());
  }
  return cap;
}

} // namespace vtouch

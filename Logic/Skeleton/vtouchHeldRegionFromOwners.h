// One whole region from the ranks' pieces (issue 19 item 2): each rank decides its candidate
// region on its held piece, but the ranks holding a voxel of the ghost margin may decide it
// differently (the depth and the neck cut near a piece's edge see less of the volume there; the
// tubularity is the single run's wherever it can decide an owned voxel, DistributedTubularity). The automatic roots across the
// ranks (DistributedRootChoice) need every rank's held mask to be its part of ONE whole mask.
// Project rule: a voxel is what its owner decided (the owner sees at least the ghost margin
// around it); every rank takes its held, not owned voxels from their owners.
// Collective: one AllGather of the owned region voxels that lie in another rank's held box
// (whole-volume linear indices: sparse, never a mask).
#pragma once

#include "vtouchPieceLayout.h"
#include "vtouchRankCollectives.h"
#include "vtouchSparseVesselMask.h"

#include <algorithm>
#include <cstdint>
#include <iterator>
#include <vector>

namespace vtouch
{

class HeldRegionFromOwners
{
public:
  /// Replaces `mask`'s (this rank's region on its held box, local linear index) voxels that
  /// this rank does not own by their owners' decisions; returns how many held voxels changed
  /// (0 where the ranks already agree). `mask` is finalized again.
  static std::uint64_t adopt(SparseVesselMask& mask,
    const PieceLayout& layout,
    RankCollectives& collectives)
  {
    const VoxelBox& owned = layout.owned[static_cast<std::size_t>(layout.rank)];
    const VoxelBox& held = layout.mine();
    const std::array<std::int64_t, 3> d = layout.pieceDims();
    const auto localLinear = [&d](const std::array<std::int64_t, 3>& q)
    { return static_cast<std::uint64_t>(q[0] + d[0] * (q[1] + d[1] * q[2])); };
    std::vector<std::int64_t> report;    // owned voxels another rank holds (whole linear)
    std::vector<std::uint64_t> notOwned; // this rank's decisions on voxels others own
    if (!held.empty())
    {
      mask.forEach(
        [&](std::uint64_t lin)
        {
          const auto l = static_cast<std::int64_t>(lin);
          const std::array<std::int64_t, 3> w =
            layout.toWhole({ l % d[0], (l / d[0]) % d[1], l / (d[0] * d[1]) });
          if (!owned.contains(w))
          {
            notOwned.push_back(lin);
            return;
          }
          for (int r = 0; r < layout.ranks(); ++r)
          {
            if (r != layout.rank && layout.held[static_cast<std::size_t>(r)].contains(w))
            {
              report.push_back(layout.wholeLinear(w));
              return;
            }
          }
        });
    }
    const std::vector<std::vector<std::int64_t>> all = collectives.allGather(report);
    std::vector<std::uint64_t> fromOwners; // the owners' decisions on this rank's held box
    for (int r = 0; r < static_cast<int>(all.size()); ++r)
    {
      if (r == layout.rank)
      {
        continue;
      }
      for (const std::int64_t lin : all[static_cast<std::size_t>(r)])
      {
        const std::array<std::int64_t, 3> w = layout.wholeIndex(lin);
        if (held.contains(w))
        {
          fromOwners.push_back(localLinear(layout.toLocal(w)));
        }
      }
    }
    std::sort(fromOwners.begin(), fromOwners.end()); // notOwned is sorted (forEach's order)
    std::vector<std::uint64_t> changed;
    std::set_symmetric_difference(notOwned.begin(),
      notOwned.end(),
      fromOwners.begin(),
      fromOwners.end(),
      std::back_inserter(changed));
    for (const std::uint64_t lin : notOwned)
    {
      mask.reset(lin);
    }
    for (const std::uint64_t lin : fromOwners)
    {
      mask.set(lin);
    }
    mask.finalize();
    return changed.size();
  }
};

} // namespace vtouch

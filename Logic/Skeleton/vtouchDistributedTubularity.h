// RestrictedTubularity on one rank's piece of a distributed volume, equal to the single run's at
// every site the rank measures (issue 19 item 2, issue 16 item 1): the tiles and coarse grids on
// the whole volume's lattice (RestrictedTubularity::Lattice), and the block means of a tile's
// smoothed box that lie outside the rank's held piece taken from a rank that holds them whole.
//
// Why an exchange and not a wider ghost margin (Docs/CLIENT-SERVER.md, "The tubularity across the
// pieces"): a tile's box reaches F (t + pad) - 1 voxels past a site in it (t = 24 coarse voxels,
// pad = 3 sigma + 1 <= 7), 29 voxels on the finest grid but 61 on F = 2 and 123 on F = 4, the grid
// of a 4-voxel vessel's largest scales; a margin that wide would give every rank of a 112^3 volume
// the whole volume. The exchange sends only the blocks a rank lacks of the tiles that hold a site
// able to decide an owned voxel (a medial voxel within its reach, depth + 1 layers, of the owned
// box), F^3 times fewer values on the coarse grids. Project rule: a block is sent by the
// lowest rank whose held piece holds it whole (every rank computes the block mean the single run's
// way, so any holder gives the same bits); a block nobody holds whole (a ghost margin narrower
// than a coarse block, F - 1 voxels) is the mean of the requester's held part, counted in
// blocksNotExact.
//
// Collective: two AllGathers, the requests (7 integers a tile whose box leaves the piece) and the
// replies (4 integers a block: requester, factor, whole coarse linear index, the mean's bits).
#pragma once

#include "vtouchPieceLayout.h"
#include "vtouchRankCollectives.h"
#include "vtouchRestrictedTubularity.h"

#include <algorithm>
#include <cstring>
#include <unordered_map>
#include <unordered_set>
#include <vector>

namespace vtouch
{

class DistributedTubularity
{
public:
  struct Result
  {
    RestrictedTubularity::Result tube;
    std::uint64_t tilesRequested = 0; ///< this rank's tiles whose box leaves its piece
    std::uint64_t blocksReceived = 0; ///< block means this rank took from others
    std::uint64_t blocksSent = 0;     ///< block means this rank sent
  };

  /// `piece` is this rank's held box (layout.mine()), `region` and `depth` (RegionDepth) on it.
  /// Every rank calls it (a collective), also with an empty piece or region. The tubularity is
  /// the single run's at every site within its reach (depth + 1 layers) of an owned voxel, where
  /// the piece's depth is the single run's (the ghost margin covers the region's depth).
  template<typename T>
  static Result compute(const VolumeView<T>& piece,
    const PieceLayout& layout,
    const SparseVesselMask& region,
    const std::vector<std::uint16_t>& depth,
    const RestrictedTubularity::Parameters& p,
    RankCollectives& collectives);

  /// Whether rank `r` holds whole-volume coarse voxel `c`'s block at factor `f` whole.
  static bool holdsBlock(const PieceLayout& layout,
    int r,
    std::int64_t f,
    const std::array<std::int64_t, 3>& c)
  {
    const VoxelBox& h = layout.held[static_cast<std::size_t>(r)];
    for (int a = 0; a < 3; ++a)
    {
      const std::int64_t lo = c[a] * f;
      const std::int64_t hi = std::min(layout.wholeDims[a], lo + f) - 1;
      if (lo < h.lo[a] || hi > h.hi[a])
      {
        return false;
      }
    }
    return true;
  }

private:
  static std::int64_t key(std::int64_t f, std::int64_t coarseLinear)
  {
    // f: a power of two at most an eighth of the largest side (RestrictedTubularity::levels),
    // below 8192 for volumes up to 65536 voxels a side.
    return coarseLinear * 8192 + f;
  }
};

template<typename T>
DistributedTubularity::Result DistributedTubularity::compute(const VolumeView<T>& piece,
  const PieceLayout& layout,
  const SparseVesselMask& region,
  const std::vector<std::uint16_t>& depth,
  const RestrictedTubularity::Parameters& p,
  RankCollectives& collectives)
{
  Result out;
  RestrictedTubularity::Lattice lattice;
  lattice.origin =
    layout.mine().empty() ? std::array<std::int64_t, 3>{ 0, 0, 0 } : layout.mine().lo;
  lattice.wholeDims = layout.wholeDims;
  RestrictedTubularity::Plan plan = RestrictedTubularity::plan(piece, region, depth, p, lattice);
  // 1. Requests: the tiles whose box this piece does not hold whole, among those with a site
  // that may decide an owned voxel: a core reaches depth + 1 layers (TubeNeckCutter), so a site
  // farther from the owned box than that decides only voxels whose owners decide them
  // (HeldRegionFromOwners); its tile's missing blocks are the held part's means (as before h19t).
  const VoxelBox owned =
    layout.owned.empty() ? VoxelBox{} : layout.owned[static_cast<std::size_t>(layout.rank)];
  const auto decidesOwned = [&](const RestrictedTubularity::Site& site)
  {
    if (owned.empty())
    {
      return false;
    }
    const auto w = layout.toWhole(piece.index(site.lin));
    std::int64_t e = 0; // chessboard distance to the owned box
    for (int a = 0; a < 3; ++a)
    {
      e = std::max({ e, owned.lo[a] - w[a], w[a] - owned.hi[a] });
    }
    return e <= static_cast<std::int64_t>(depth[site.rank]) + 1;
  };
  std::vector<std::int64_t> requests;
  for (RestrictedTubularity::Tile& tile : plan.tiles)
  {
    tile.exact = std::any_of(tile.sites.begin(),
      tile.sites.end(),
      [&](std::uint32_t n) { return decidesOwned(plan.sites[n]); });
    if (!tile.exact)
    {
      continue;
    }
    const std::int64_t f = plan.levels[tile.level].factor;
    const VoxelBox& h = layout.mine();
    bool inside = !h.empty();
    for (int a = 0; a < 3 && inside; ++a)
    {
      inside =
        tile.lo[a] * f >= h.lo[a] && std::min(layout.wholeDims[a], tile.hi[a] * f) - 1 <= h.hi[a];
    }
    if (!inside)
    {
      requests.insert(requests.end(),
        { f, tile.lo[0], tile.lo[1], tile.lo[2], tile.hi[0], tile.hi[1], tile.hi[2] });
      ++out.tilesRequested;
    }
  }
  const std::vector<std::vector<std::int64_t>> asked = collectives.allGather(requests);
  // 2. Replies: the blocks this rank is the first whole holder of, for each requester that
  // does not hold them.
  std::vector<std::int64_t> replies;
  for (int q = 0; q < static_cast<int>(asked.size()); ++q)
  {
    if (q == layout.rank || layout.mine().empty())
    {
      continue;
    }
    std::unordered_set<std::int64_t> sent;
    const std::vector<std::int64_t>& boxes = asked[static_cast<std::size_t>(q)];
    for (std::size_t b = 0; b + 7 <= boxes.size(); b += 7)
    {
      const std::int64_t f = boxes[b];
      const std::array<std::int64_t, 3> cd{ (layout.wholeDims[0] + f - 1) / f,
        (layout.wholeDims[1] + f - 1) / f,
        (layout.wholeDims[2] + f - 1) / f };
      for (std::int64_t k = boxes[b + 3]; k < boxes[b + 6]; ++k)
        for (std::int64_t j = boxes[b + 2]; j < boxes[b + 5]; ++j)
          for (std::int64_t i = boxes[b + 1]; i < boxes[b + 4]; ++i)
          {
            const std::array<std::int64_t, 3> c{ i, j, k };
            if (holdsBlock(layout, q, f, c) || !holdsBlock(layout, layout.rank, f, c))
            {
              continue;
            }
            int first = 0;
            while (!holdsBlock(layout, first, f, c))
            {
              ++first;
            }
            const std::int64_t lin = i + cd[0] * (j + cd[1] * k);
            if (first != layout.rank || !sent.insert(key(f, lin)).second)
            {
              continue;
            }
            bool whole = true;
            const float mean = RestrictedTubularity::blockMean(piece, lattice, f, c, whole);
            std::uint32_t bits = 0;
            std::memcpy(&bits, &mean, sizeof bits);
            replies.insert(replies.end(), { q, f, lin, static_cast<std::int64_t>(bits) });
            ++out.blocksSent;
          }
    }
  }
  const std::vector<std::vector<std::int64_t>> answered = collectives.allGather(replies);
  std::unordered_map<std::int64_t, float> received;
  for (const std::vector<std::int64_t>& from : answered)
  {
    for (std::size_t e = 0; e + 4 <= from.size(); e += 4)
    {
      if (from[e] != layout.rank)
      {
        continue;
      }
      const auto bits = static_cast<std::uint32_t>(from[e + 3]);
      float mean = 0.0F;
      std::memcpy(&mean, &bits, sizeof mean);
      received[key(from[e + 1], from[e + 2])] = mean;
    }
  }
  out.blocksReceived = received.size();
  // 3. The tiles, each block from this piece or from its holder.
  const RestrictedTubularity::BlockMeans others =
    [&received, &layout](std::int64_t f, const std::array<std::int64_t, 3>& c, float& mean)
  {
    const std::int64_t cx = (layout.wholeDims[0] + f - 1) / f;
    const std::int64_t cy = (layout.wholeDims[1] + f - 1) / f;
    const auto found = received.find(key(f, c[0] + cx * (c[1] + cy * c[2])));
    if (found == received.end())
    {
      return false;
    }
    mean = found->second;
    return true;
  };
  out.tube = RestrictedTubularity::run(piece, region, plan, p, others);
  return out;
}

} // namespace vtouch

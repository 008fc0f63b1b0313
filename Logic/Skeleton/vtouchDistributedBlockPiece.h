// A rank's piece of the 2 x 2 x 2 block mask of the whole volume (issue 19 item 2, the automatic
// root's exploration on blocks, SeedCodeStage::coarseExtremity). The block grid is aligned to the
// whole volume's first voxel, as the single run's (its piece is the whole volume): block I covers
// voxels 2 I and 2 I + 1, and is vessel when one of them is.
//
// A rank holds the blocks whose voxels inside the volume it all holds (their value is then the
// single run's) and owns the blocks whose first voxel it owns (the owned boxes tile the block
// grid). The block SS code's rounds need one held block past the owned ones: the held box
// reaching 2 voxels below and 3 above the owned box always gives it (the executive's ghost
// margin of 2: its shared face layer adds one above); 1 does for some parities only (checked).
#pragma once

#include "vtouchPieceLayout.h"
#include "vtouchSparseVesselMask.h"

#include <array>
#include <cstdint>
#include <stdexcept>
#include <string>

namespace vtouch
{

struct DistributedBlockPiece
{
  /// The executive's ghost margin the block rounds always work with (the arithmetic above).
  static constexpr std::int64_t kMinimumMarginVoxels = 2;

  PieceLayout layout;    ///< the block grid's layout (same rank)
  SparseVesselMask mask; ///< this rank's held blocks (local block index), finalized

  /// Throws std::invalid_argument when a rank's held blocks do not reach one block past its owned
  /// blocks on a face that is not the volume's (every rank throws: the layout is shared).
  DistributedBlockPiece(const PieceLayout& fine, const SparseVesselMask& fineMask)
    : layout(blockLayout(fine))
    , mask(layout.pieceDims())
  {
    const VoxelBox& held = fine.mine();
    const VoxelBox& blocks = this->layout.mine();
    const std::array<std::int64_t, 3> fd = fine.pieceDims();
    const std::array<std::int64_t, 3> bd = this->layout.pieceDims();
    fineMask.forEach(
      [&](std::uint64_t lin)
      {
        const auto l = static_cast<std::int64_t>(lin);
        const std::array<std::int64_t, 3> w{
          l % fd[0] + held.lo[0], (l / fd[0]) % fd[1] + held.lo[1], l / (fd[0] * fd[1]) + held.lo[2]
        };
        const std::array<std::int64_t, 3> b{ w[0] / 2, w[1] / 2, w[2] / 2 };
        if (blocks.contains(b))
        {
          this->mask.set(static_cast<std::uint64_t>(
            (b[0] - blocks.lo[0]) +
            bd[0] * ((b[1] - blocks.lo[1]) + bd[1] * (b[2] - blocks.lo[2]))));
        }
      });
    this->mask.finalize();
  }

  static PieceLayout blockLayout(const PieceLayout& fine)
  {
    PieceLayout out;
    out.rank = fine.rank;
    for (int a = 0; a < 3; ++a)
    {
      out.wholeDims[static_cast<std::size_t>(a)] =
        (fine.wholeDims[static_cast<std::size_t>(a)] + 1) / 2;
    }
    for (int r = 0; r < fine.ranks(); ++r)
    {
      const VoxelBox& h = fine.held[static_cast<std::size_t>(r)];
      const VoxelBox& o = fine.owned[static_cast<std::size_t>(r)];
      VoxelBox bh, bo;
      for (std::size_t a = 0; a < 3; ++a)
      {
        const std::int64_t last = fine.wholeDims[a] - 1;
        // Held: blocks whose voxels in the volume are all held.
        bh.lo[a] = (h.lo[a] + 1) / 2;
        bh.hi[a] = h.hi[a] == last ? out.wholeDims[a] - 1 : (h.hi[a] >= 1 ? (h.hi[a] - 1) / 2 : -1);
        // Owned: blocks whose first voxel is owned.
        bo.lo[a] = o.empty() ? 0 : (o.lo[a] + 1) / 2;
        bo.hi[a] = o.empty() ? -1 : o.hi[a] / 2;
      }
      for (std::size_t a = 0; a < 3 && !bo.empty(); ++a)
      {
        // The block rounds need one held block past the owned ones (DistributedSeedCode).
        if ((bo.lo[a] > 0 && bh.lo[a] > bo.lo[a] - 1) ||
            (bo.hi[a] < out.wholeDims[a] - 1 && bh.hi[a] < bo.hi[a] + 1))
        {
          throw std::invalid_argument("the automatic root's exploration on 2x2x2 blocks needs a "
                                      "ghost margin of at least " +
                                      std::to_string(kMinimumMarginVoxels) + " voxels (rank " +
                                      std::to_string(r) + " holds fewer)");
        }
      }
      out.held.push_back(bh);
      out.owned.push_back(bo);
    }
    out.check();
    return out;
  }
};

} // namespace vtouch

// One rank's piece of a whole raw volume in the distributed tests (ranks as threads, issue 19
// item 2): a copy of the rank's held box, as a reader gives it, and the view of it. One place for
// the copy that vtouchDistributedRegionTest and vtouchDistributedRawUnseededTest each carried
// (duplicates --change).
#pragma once

#include "vtouchPieceLayout.h"
#include "vtouchVolumeView.h"

#include <array>
#include <cstdint>
#include <vector>

namespace vtouch::test
{

class RankPiece
{
public:
  /// `wholeVoxels`: the whole volume of `wholeDims`, x fastest.
  RankPiece(const std::vector<float>& wholeVoxels,
    const std::array<std::int64_t, 3>& wholeDims,
    const PieceLayout& l)
    : layout(l)
  {
    const VoxelBox& b = l.mine();
    for (std::int64_t k = b.lo[2]; k <= b.hi[2]; ++k)
    {
      for (std::int64_t j = b.lo[1]; j <= b.hi[1]; ++j)
      {
        for (std::int64_t i = b.lo[0]; i <= b.hi[0]; ++i)
        {
          voxels.push_back(
            wholeVoxels[static_cast<std::size_t>(i + wholeDims[0] * (j + wholeDims[1] * k))]);
        }
      }
    }
    view.voxels = voxels.data();
    view.dims = l.pieceDims();
  }
  RankPiece(const RankPiece&) = delete; // the view points into `voxels`
  RankPiece& operator=(const RankPiece&) = delete;

  /// The local linear index of whole-volume voxel `w` (held by the rank).
  std::uint64_t linear(const std::array<std::int64_t, 3>& w) const
  {
    const auto q = layout.toLocal(w);
    return view.linear(q[0], q[1], q[2]);
  }
  /// The growth's seeds on this rank: `seed`'s local index where the rank owns it, else none.
  std::vector<std::uint64_t> seedsOwned(const std::array<std::int64_t, 3>& seed) const
  {
    return layout.ownerOf(seed) == layout.rank ? std::vector<std::uint64_t>{ linear(seed) }
                                               : std::vector<std::uint64_t>{};
  }

  const PieceLayout& layout;
  std::vector<float> voxels;
  VolumeView<float> view;
};

} // namespace vtouch::test

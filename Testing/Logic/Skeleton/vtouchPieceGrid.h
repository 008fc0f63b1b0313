// Pieces of a whole volume for the distributed stages' tests and benchmarks: the executive's
// split into boxes per axis, a rank's part of a whole mask, and a skeleton's free ends and
// junctions in a rank's box.
#pragma once

#include "vtouchPieceLayout.h"
#include "vtouchSparseVesselMask.h"
#include "vtouchVoxelCoding.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <utility>
#include <vector>

namespace vtouch::test
{

/// `counts[a]` pieces along each axis, split by cells as the executive does (neighbours share a
/// face layer, owned by the upper piece); held boxes grown by `margin` voxels on shared faces.
inline std::vector<PieceLayout> layouts(const std::array<std::int64_t, 3>& dims,
  const std::array<int, 3>& counts,
  int margin)
{
  std::array<std::vector<std::pair<std::int64_t, std::int64_t>>, 3> splits;
  for (int a = 0; a < 3; ++a)
  {
    const std::int64_t cells = dims[a] - 1;
    for (int p = 0; p < counts[a]; ++p)
    {
      splits[a].emplace_back(cells * p / counts[a], cells * (p + 1) / counts[a]);
    }
  }
  PieceLayout base;
  base.wholeDims = dims;
  for (const auto& z : splits[2])
    for (const auto& y : splits[1])
      for (const auto& x : splits[0])
      {
        VoxelBox held, owned;
        held.lo = { x.first, y.first, z.first };
        held.hi = { x.second, y.second, z.second };
        owned = held;
        for (int a = 0; a < 3; ++a)
        {
          if (owned.hi[a] < dims[a] - 1)
          {
            owned.hi[a] -= 1; // the shared face layer belongs to the upper piece
            held.hi[a] = std::min(dims[a] - 1, held.hi[a] + margin);
          }
          held.lo[a] = std::max<std::int64_t>(0, held.lo[a] - margin);
        }
        base.held.push_back(held);
        base.owned.push_back(owned);
      }
  std::vector<PieceLayout> out;
  for (int r = 0; r < base.ranks(); ++r)
  {
    PieceLayout l = base;
    l.rank = r;
    out.push_back(l);
  }
  return out;
}

/// The whole mask restricted to rank `l`'s held box (local index), finalized.
inline SparseVesselMask pieceMask(const SparseVesselMask& whole, const PieceLayout& l)
{
  const VoxelBox& b = l.mine();
  const std::array<std::int64_t, 3> d = l.pieceDims();
  SparseVesselMask m(d);
  for (std::int64_t k = b.lo[2]; k <= b.hi[2]; ++k)
    for (std::int64_t j = b.lo[1]; j <= b.hi[1]; ++j)
      for (std::int64_t i = b.lo[0]; i <= b.hi[0]; ++i)
      {
        if (whole.test(static_cast<std::uint64_t>(l.wholeLinear({ i, j, k }))))
        {
          const auto q = l.toLocal({ i, j, k });
          m.set(static_cast<std::uint64_t>(q[0] + d[0] * (q[1] + d[1] * q[2])));
        }
      }
  m.finalize();
  return m;
}

/// Free ends and junctions of `skeleton` (voxels offset by `lo` into the whole index) inside
/// `box` shrunk by `inset` voxels on the faces that are not the volume's.
inline std::pair<int, int> endsAndJunctionsIn(const RawSkeleton& skeleton,
  const std::array<std::int64_t, 3>& lo,
  VoxelBox box,
  const std::array<std::int64_t, 3>& dims,
  int inset)
{
  for (int a = 0; a < 3; ++a)
  {
    box.lo[a] += box.lo[a] > 0 ? inset : 0;
    box.hi[a] -= box.hi[a] < dims[a] - 1 ? inset : 0;
  }
  const auto in = [&](const std::array<std::int64_t, 3>& v)
  { return box.contains(v[0] + lo[0], v[1] + lo[1], v[2] + lo[2]); };
  int ends = 0, junctions = 0;
  for (const RawSkeletonPath& p : skeleton.paths)
  {
    if (p.voxels.empty())
    {
      continue;
    }
    ends += p.headJunction < 0 && in(p.voxels.front());
    ends += p.tailJunction < 0 && p.voxels.size() > 1 && in(p.voxels.back());
  }
  for (const RawJunction& j : skeleton.junctions)
  {
    const RawSkeletonPath& parent = skeleton.paths[static_cast<std::size_t>(j.parentPath)];
    junctions += in(parent.voxels[static_cast<std::size_t>(j.parentPoint)]);
  }
  return { ends, junctions };
}

/// Free ends and junctions inside rank `l`'s owned box, `inset` voxels from its shared faces
/// (endsAndJunctionsIn), of: the single run's skeleton `single` (whole index), the piece `mask`
/// coded from roots of its own (the distributed coding without the global field), and the piece
/// coded with the global SS field `globalSs_mm` (VoxelCodingParameters::globalSs_mm); voxels of
/// `spacing_mm`. The measure of vtouchDistributedSeedCodeTest and vesseltouch-distributed-seedcode.
inline std::array<std::pair<int, int>, 3> ownedBoxTopology(const RawSkeleton& single,
  const PieceLayout& l,
  const SparseVesselMask& mask,
  const std::vector<float>& globalSs_mm,
  const std::array<double, 3>& spacing_mm,
  int inset)
{
  VoxelCodingParameters own;
  own.spacing_mm = spacing_mm;
  VoxelCodingParameters global = own;
  global.globalSs_mm = &globalSs_mm;
  const VoxelBox& owned = l.owned[static_cast<std::size_t>(l.rank)];
  return { endsAndJunctionsIn(single, { 0, 0, 0 }, owned, l.wholeDims, inset),
    endsAndJunctionsIn(VoxelCoder(mask, own).run(), l.mine().lo, owned, l.wholeDims, inset),
    endsAndJunctionsIn(VoxelCoder(mask, global).run(), l.mine().lo, owned, l.wholeDims, inset) };
}

/// The splits of the distributed tests and benchmarks: 2 pieces along z, 2 x 2 in y and z, and
/// 2 x 2 x 2 (`counts` of layouts).
inline const std::array<std::array<int, 3>, 3> kSplitsIn2And4And8{
  { { 1, 1, 2 }, { 1, 2, 2 }, { 2, 2, 2 } }
};

} // namespace vtouch::test

// Where one rank's piece lies in the whole volume, and which voxels each rank owns: the geometry
// the distributed raw-angiogram stages share (DistributedRegionGrowth, DistributedCandidateRegion).
// Plain voxel boxes of the whole volume's index grid (index 0 at the volume's first voxel), so
// that the stages need neither VTK nor the stitcher's ownership of skeleton points.
#pragma once

#include <array>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace vtouch
{

/// An inclusive voxel box: lo[a] <= index[a] <= hi[a]; empty when hi < lo on an axis.
struct VoxelBox
{
  std::array<std::int64_t, 3> lo{ 0, 0, 0 };
  std::array<std::int64_t, 3> hi{ -1, -1, -1 };
  bool contains(std::int64_t i, std::int64_t j, std::int64_t k) const
  {
    return i >= lo[0] && i <= hi[0] && j >= lo[1] && j <= hi[1] && k >= lo[2] && k <= hi[2];
  }
  bool contains(const std::array<std::int64_t, 3>& c) const
  {
    return this->contains(c[0], c[1], c[2]);
  }
  bool empty() const { return hi[0] < lo[0] || hi[1] < lo[1] || hi[2] < lo[2]; }
};

struct PieceLayout
{
  std::array<std::int64_t, 3> wholeDims{ 0, 0, 0 };
  int rank = 0;
  /// Each rank's grown piece (the extent it holds: its piece and the ghost margin).
  std::vector<VoxelBox> held;
  /// Each rank's owned voxels: disjoint, covering the whole volume (half-open on shared faces:
  /// the face layer pieces share belongs to the upper piece, as vtouch::PieceOwnership).
  std::vector<VoxelBox> owned;

  int ranks() const { return static_cast<int>(this->owned.size()); }
  const VoxelBox& mine() const { return this->held[static_cast<std::size_t>(this->rank)]; }
  std::array<std::int64_t, 3> pieceDims() const
  {
    const VoxelBox& b = this->mine();
    return { b.hi[0] - b.lo[0] + 1, b.hi[1] - b.lo[1] + 1, b.hi[2] - b.lo[2] + 1 };
  }
  /// Where rank `r` decides voxels exactly: its held box less its outermost layer on faces that
  /// are not the volume's (a voxel there has all 26 neighbours held, or outside the volume).
  VoxelBox evaluable(int r) const
  {
    VoxelBox b = this->held[static_cast<std::size_t>(r)];
    for (int a = 0; a < 3; ++a)
    {
      b.lo[a] += b.lo[a] > 0 ? 1 : 0;
      b.hi[a] -= b.hi[a] < this->wholeDims[a] - 1 ? 1 : 0;
    }
    return b;
  }
  /// The rank owning whole-volume voxel `c`, or -1 outside the volume.
  int ownerOf(const std::array<std::int64_t, 3>& c) const
  {
    for (int r = 0; r < this->ranks(); ++r)
    {
      if (this->owned[static_cast<std::size_t>(r)].contains(c))
      {
        return r;
      }
    }
    return -1;
  }
  std::int64_t wholeLinear(const std::array<std::int64_t, 3>& c) const
  {
    return c[0] + this->wholeDims[0] * (c[1] + this->wholeDims[1] * c[2]);
  }
  std::array<std::int64_t, 3> wholeIndex(std::int64_t lin) const
  {
    return { lin % this->wholeDims[0],
      (lin / this->wholeDims[0]) % this->wholeDims[1],
      lin / (this->wholeDims[0] * this->wholeDims[1]) };
  }
  /// This rank's local index (its held box from 0) of whole-volume voxel `c`.
  std::array<std::int64_t, 3> toLocal(const std::array<std::int64_t, 3>& c) const
  {
    const VoxelBox& b = this->mine();
    return { c[0] - b.lo[0], c[1] - b.lo[1], c[2] - b.lo[2] };
  }
  std::array<std::int64_t, 3> toWhole(const std::array<std::int64_t, 3>& local) const
  {
    const VoxelBox& b = this->mine();
    return { local[0] + b.lo[0], local[1] + b.lo[1], local[2] + b.lo[2] };
  }
  /// Throws std::invalid_argument unless the owned boxes tile the volume, each inside its
  /// rank's held box, and `rank` is one of them.
  void check() const
  {
    const auto fail = [](const std::string& what)
    { throw std::invalid_argument("PieceLayout: " + what); };
    if (this->held.size() != this->owned.size() || this->owned.empty())
    {
      fail("one held and one owned box per rank are needed");
    }
    if (this->rank < 0 || this->rank >= this->ranks())
    {
      fail("the rank is not one of the pieces");
    }
    std::int64_t total = 0;
    for (int r = 0; r < this->ranks(); ++r)
    {
      const VoxelBox& o = this->owned[static_cast<std::size_t>(r)];
      const VoxelBox& h = this->held[static_cast<std::size_t>(r)];
      if (o.empty())
      {
        continue;
      }
      if (!h.contains(o.lo) || !h.contains(o.hi))
      {
        fail("rank " + std::to_string(r) + " does not hold the voxels it owns");
      }
      total += (o.hi[0] - o.lo[0] + 1) * (o.hi[1] - o.lo[1] + 1) * (o.hi[2] - o.lo[2] + 1);
    }
    if (total != this->wholeDims[0] * this->wholeDims[1] * this->wholeDims[2])
    {
      fail("the owned boxes do not tile the volume");
    }
  }
};

} // namespace vtouch

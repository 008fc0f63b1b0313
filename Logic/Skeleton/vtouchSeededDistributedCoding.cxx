// vtouch::SeededDistributedCoding: the agreement, the root and the SS rounds for one rank's coder
// (see the header for why every rank takes the same steps).
#include "vtouchSeededDistributedCoding.h"

#include "vtouchSeedVoxel.h"

#include <limits>
#include <memory>

namespace vtouch
{
namespace
{
std::string voxelText(const std::array<std::int64_t, 3>& c)
{
  return "(" + std::to_string(c[0]) + ", " + std::to_string(c[1]) + ", " + std::to_string(c[2]) +
         ")";
}

/// What a rank tells the others before the rounds (one AllGather).
enum Slot : std::size_t
{
  kUsable = 0,   ///< 1: it can take part
  kProposal = 1, ///< 0: none, 1: a root, 2: its seed block holds no vessel voxel
  kRoot = 2,     ///< the root's whole linear index
  kOwner = 3,    ///< 1: it owns the seed voxel
  kSlots = 4
};
} // namespace

std::uint64_t clearOuterLayer(SparseVesselMask& mask, const PieceLayout& layout)
{
  const VoxelBox evaluable = layout.evaluable(layout.rank);
  const std::array<std::int64_t, 3> d = mask.dims();
  std::vector<std::uint64_t> outside;
  mask.forEach(
    [&](std::uint64_t lin)
    {
      const auto l = static_cast<std::int64_t>(lin);
      if (!evaluable.contains(layout.toWhole({ l % d[0], (l / d[0]) % d[1], l / (d[0] * d[1]) })))
      {
        outside.push_back(lin);
      }
    });
  for (const std::uint64_t lin : outside)
  {
    mask.reset(lin);
  }
  mask.finalize();
  return outside.size();
}

SeededDistributedCoding::SeededDistributedCoding(RankCollectives& collectives,
  PieceLayout layout,
  const std::array<double, 3>& spacing_mm,
  bool hasSeed,
  const std::array<std::int64_t, 3>& seed_Whole,
  const Settings& settings)
  : Collectives(collectives)
  , Layout(std::move(layout))
  , Spacing_mm(spacing_mm)
  , HasSeed(hasSeed)
  , Seed_Whole(seed_Whole)
  , Options(settings)
{
}

std::vector<float> SeededDistributedCoding::code(SparseVesselMask& mask)
{
  return this->take(mask, true);
}

void SeededDistributedCoding::join()
{
  const bool held = !this->Layout.mine().empty();
  SparseVesselMask empty(held ? this->Layout.pieceDims() : std::array<std::int64_t, 3>{ 1, 1, 1 });
  empty.finalize();
  this->take(empty, held);
}

std::vector<float> SeededDistributedCoding::take(SparseVesselMask& mask, bool usable)
{
  if (this->Joined)
  {
    throw std::logic_error("SeededDistributedCoding: a rank joins the SS rounds once per run");
  }
  this->Joined = true;
  const PieceLayout& layout = this->Layout;
  // The layout is the same on every rank (gathered): so is this verdict, without an exchange.
  try
  {
    layout.check();
  }
  catch (const std::invalid_argument& e)
  {
    throw SeededDistributedCodingError(
      std::string("VesselCenterline (distributed): the ranks' pieces do not cover the volume (") +
      e.what() + "); extract on one rank.");
  }
  // This rank's state: can it take part (every check DistributedSeedCode makes, made here so
  // that a failing rank says so in the agreement instead of leaving the others waiting)?
  std::unique_ptr<DistributedSeedCode> rounds;
  std::string reason;
  if (usable && mask.dims() != layout.pieceDims())
  {
    usable = false;
    reason = "its mask's size is not its piece's";
  }
  if (usable)
  {
    try
    {
      if (this->Options.clearOuterLayer)
      {
        this->Result.clearedVoxels = clearOuterLayer(mask, layout);
      }
      rounds = std::make_unique<DistributedSeedCode>(layout, mask, this->Spacing_mm);
    }
    catch (const std::exception& e)
    {
      usable = false;
      reason = e.what();
    }
  }
  std::vector<std::int64_t> mine(kSlots, 0);
  mine[kUsable] = usable ? 1 : 0;
  if (usable && this->HasSeed && layout.mine().contains(this->Seed_Whole))
  {
    const std::array<std::int64_t, 3> root =
      nearestVesselVoxel(mask, layout.toLocal(this->Seed_Whole));
    mine[kProposal] = root[0] >= 0 ? 1 : 2;
    mine[kRoot] = root[0] >= 0 ? layout.wholeLinear(layout.toWhole(root)) : 0;
    mine[kOwner] = layout.ownerOf(this->Seed_Whole) == layout.rank ? 1 : 0;
  }
  const std::vector<std::vector<std::int64_t>> all = this->Collectives.allGather(mine);
  // The verdict, from the same data on every rank.
  int chosen = -1;
  for (int r = 0; r < static_cast<int>(all.size()); ++r)
  {
    const std::vector<std::int64_t>& theirs = all[static_cast<std::size_t>(r)];
    if (theirs.size() != kSlots || theirs[kUsable] != 1)
    {
      throw SeededDistributedCodingError(
        "VesselCenterline (distributed): rank " + std::to_string(r) +
        " cannot take part in the SS code across the pieces" +
        (r == layout.rank && !reason.empty() ? " (" + reason + ")" : std::string()) +
        "; extract on one rank.");
    }
    const bool better =
      chosen < 0 || (theirs[kOwner] == 1 && all[static_cast<std::size_t>(chosen)][kOwner] == 0);
    if (theirs[kProposal] != 0 && better)
    {
      chosen = r;
    }
  }
  if (chosen < 0)
  {
    throw SeededDistributedCodingError("VesselCenterline (distributed): the seed voxel " +
                                       voxelText(this->Seed_Whole) +
                                       " lies on no rank's piece: it is outside the volume.");
  }
  const std::vector<std::int64_t>& proposal = all[static_cast<std::size_t>(chosen)];
  if (proposal[kProposal] != 1)
  {
    throw SeededDistributedCodingError("VesselCenterline (distributed): the seed voxel " +
                                       voxelText(this->Seed_Whole) +
                                       " is not inside any vessel (no vessel voxel within one "
                                       "voxel of it).");
  }
  this->Result.root_Whole = layout.wholeIndex(proposal[kRoot]);
  try
  {
    const DistributedSeedCode::Outcome o =
      rounds->run(this->Collectives, { this->Result.root_Whole }, this->Options.maximumRounds);
    this->Result.rounds = o.rounds;
    this->Result.reportedVoxels = o.reportedVoxels;
    if (!o.settled)
    {
      throw SeededDistributedCodingError("VesselCenterline (distributed): " + o.message + ".");
    }
  }
  catch (const std::invalid_argument& e)
  {
    throw SeededDistributedCodingError(std::string("VesselCenterline (distributed): ") + e.what());
  }
  return rounds->ss();
}

} // namespace vtouch

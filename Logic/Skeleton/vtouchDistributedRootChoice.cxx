// vtouch::DistributedRootChoice: the single run's automatic root, collectively (see the header).
#include "vtouchDistributedRootChoice.h"

#include "vtouchDistributedBlockPiece.h"
#include "vtouchDistributedBoundaryCode.h"
#include "vtouchDistributedClusterGraph.h"
#include "vtouchDistributedEndCap.h"
#include "vtouchSkeletonEndCapRule.h"
#include "vtouchSkeletonSeedCodeStage.h"
#include "vtouchSkeletonThickerEnd.h"
#include "vtouchSkeletonVoxelCodes.h"
#include "vtouchSkeletonVoxelGrid.h"

#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>

namespace vtouch
{
namespace
{
constexpr float kInf = skeleton::VoxelCodes::kInf;
using Index = std::array<std::int64_t, 3>;

/// The first rank's message among the ranks' `mine` ("" when every rank's is empty): the
/// verdict every rank reaches together.
std::string agree(RankCollectives& c, const std::string& mine)
{
  const std::vector<std::int64_t> chars(mine.begin(), mine.end());
  const std::vector<std::vector<std::int64_t>> all = c.allGather(chars);
  for (std::size_t r = 0; r < all.size(); ++r)
  {
    if (!all[r].empty())
    {
      return std::string(all[r].begin(), all[r].end()) + " (rank " + std::to_string(r) + ")";
    }
  }
  return {};
}

/// The answer of the rank that owns a voxel (`iOwn`) to a yes/no question about it, on every rank.
bool ownersAnswer(RankCollectives& c, bool iOwn, bool answer)
{
  std::vector<std::int64_t> mine;
  if (iOwn)
  {
    mine.push_back(answer ? 1 : 0);
  }
  for (const std::vector<std::int64_t>& v : c.allGather(mine))
  {
    if (!v.empty())
    {
      return v[0] != 0;
    }
  }
  return false;
}

/// A round cap or an unusable setup, the same on every rank.
struct Stop
{
  std::string message;
};

/// One choice: the piece, its codes and the single run's steps, collectively.
class Chooser
{
public:
  Chooser(const PieceLayout& l,
    const SparseVesselMask& m,
    const std::array<double, 3>& sp,
    RankCollectives& c,
    const DistributedRootChoice::Parameters& p)
    : layout(l)
    , mask(m)
    , spacing_mm(sp)
    , collectives(c)
    , par(p)
  {
  }

  /// Builds the codes (throws std::invalid_argument on an unusable setup, on this rank).
  void prepare();
  /// The components' roots and the field (throws Stop, on every rank together).
  void chooseAll(DistributedRootChoice::Result& result);

private:
  Index wholeOf(std::uint64_t localLin) const
  {
    const Index d = layout.pieceDims();
    const auto l = static_cast<std::int64_t>(localLin);
    return layout.toWhole({ l % d[0], (l / d[0]) % d[1], l / (d[0] * d[1]) });
  }
  std::uint64_t localOf(const Index& whole) const
  {
    const Index d = layout.pieceDims();
    const Index l = layout.toLocal(whole);
    return static_cast<std::uint64_t>(l[0] + d[0] * (l[1] + d[1] * l[2]));
  }
  bool owns(const Index& whole) const
  {
    return layout.owned[static_cast<std::size_t>(layout.rank)].contains(whole);
  }
  /// The next component's start (whole linear index), or -1: every voxel explored.
  std::int64_t nextStart();
  void propagate(DistributedSeedCode& code, const std::vector<Index>& roots_Whole);
  /// Flags the fine code's reached voxels explored; returns the component's size (all ranks).
  std::uint64_t markExplored();
  /// The exploration on blocks (SeedCodeStage::coarseExtremity): the root, or none.
  std::optional<Index> blockRoot(const Index& start);
  /// The exact double propagation's root voxel(s) (SeedCodeStage::extremityRegion), from the
  /// fine code's last propagation (from the start).
  std::vector<Index> exactRoots();
  void keepField(DistributedRootChoice::Result& result) const;
  /// The single run's move to the thickest end (ClusterStage::thickerRoot) of the component
  /// the fine code holds; propagates again when it moves.
  void moveToThickest(DistributedRootChoice::ComponentRoot& component);
  /// Records a coded component: its move, then its field.
  void addComponent(DistributedRootChoice::Result& result,
    const std::vector<Index>& roots,
    std::uint64_t size,
    bool fromBlocks);

  const PieceLayout& layout;
  const SparseVesselMask& mask;
  std::array<double, 3> spacing_mm;
  RankCollectives& collectives;
  DistributedRootChoice::Parameters par;
  std::unique_ptr<DistributedSeedCode> fine;
  std::unique_ptr<DistributedBlockPiece> blocks; // only on volumes explored on blocks
  std::unique_ptr<DistributedSeedCode> blockCode;
  double bandWidth_mm = 0.0, blockBandWidth_mm = 0.0;
  float inverseBandWidth = 0.0F;
  std::unique_ptr<DistributedBoundaryCode::Result> boundary; // once, at the first component
  int moveExchanges = 0;
  std::uint64_t moveValues = 0;
  std::vector<std::uint32_t> ownedVessel; // local indices, scan order
  std::size_t cursor = 0;
  std::vector<std::uint8_t> explored;      // per piece vessel voxel (rank)
  std::vector<std::uint8_t> blockExplored; // per held vessel block (rank)
  bool onBlocks = false;
  int propagations = 0;
  int rounds = 0;
};

void Chooser::prepare()
{
  if (!(par.clusterWidth_mm >= 0.0) || !std::isfinite(par.clusterWidth_mm))
  {
    throw std::invalid_argument("the cluster width must be finite and >= 0");
  }
  if (par.maximumRounds < 1)
  {
    throw std::invalid_argument("the round cap must be at least 1");
  }
  fine = std::make_unique<DistributedSeedCode>(layout, mask, spacing_mm);
  const skeleton::VoxelGrid grid(mask, spacing_mm, par.clusterWidth_mm);
  bandWidth_mm = grid.bandWidth;
  inverseBandWidth = grid.inverseBandWidth;
  explored.assign(mask.vesselCount(), 0);
  mask.forEach(
    [&](std::uint64_t lin)
    {
      if (owns(wholeOf(lin)))
      {
        ownedVessel.push_back(static_cast<std::uint32_t>(lin));
      }
    });
}

std::int64_t Chooser::nextStart()
{
  while (cursor < ownedVessel.size() && explored[mask.rank(ownedVessel[cursor])])
  {
    ++cursor;
  }
  std::int64_t start = -1;
  std::vector<std::int64_t> mine;
  if (cursor < ownedVessel.size())
  {
    mine.push_back(layout.wholeLinear(wholeOf(ownedVessel[cursor])));
  }
  for (const std::vector<std::int64_t>& v : collectives.allGather(mine))
  {
    if (!v.empty() && (start < 0 || v[0] < start))
    {
      start = v[0];
    }
  }
  return start;
}

void Chooser::propagate(DistributedSeedCode& code, const std::vector<Index>& roots_Whole)
{
  const DistributedSeedCode::Outcome o = code.run(collectives, roots_Whole, par.maximumRounds);
  ++propagations;
  rounds += o.rounds;
  if (!o.settled)
  {
    throw Stop{ o.message };
  }
}

std::uint64_t Chooser::markExplored()
{
  const std::vector<float>& ss = fine->ss();
  double owned = 0.0;
  mask.forEach(
    [&](std::uint64_t lin)
    {
      const std::uint32_t r = mask.rank(lin);
      if (ss[r] != kInf)
      {
        explored[r] = 1;
        owned += owns(wholeOf(lin)) ? 1.0 : 0.0;
      }
    });
  return static_cast<std::uint64_t>(collectives.sum(owned));
}

std::optional<Index> Chooser::blockRoot(const Index& start)
{
  const PieceLayout& bl = blocks->layout;
  const SparseVesselMask& bm = blocks->mask;
  const Index startBlock{ start[0] / 2, start[1] / 2, start[2] / 2 };
  const bool iOwnStart = bl.owned[static_cast<std::size_t>(bl.rank)].contains(startBlock);
  const auto blockLocal = [&](const Index& b)
  {
    const Index d = bl.pieceDims();
    const Index l = bl.toLocal(b);
    return static_cast<std::uint64_t>(l[0] + d[0] * (l[1] + d[1] * l[2]));
  };
  // Its blocks touch a component already explored (small blobs beside a vessel): exact search.
  if (ownersAnswer(
        collectives, iOwnStart, iOwnStart && blockExplored[bm.rank(blockLocal(startBlock))]))
  {
    return std::nullopt;
  }
  propagate(*blockCode, { startBlock });
  const std::vector<float>& bss = blockCode->ss();
  for (std::size_t r = 0; r < bss.size(); ++r)
  {
    blockExplored[r] = blockExplored[r] || bss[r] != kInf;
  }
  const DistributedEndCap::Cap cap = DistributedEndCap::find(collectives,
    bl,
    bm,
    { 2 * spacing_mm[0], 2 * spacing_mm[1], 2 * spacing_mm[2] },
    *blockCode,
    blockBandWidth_mm,
    false,
    par.maximumRounds);
  rounds += cap.rounds;
  if (!cap.settled)
  {
    throw Stop{ cap.message };
  }
  // The cap's centre block when it is vessel, else the whole cap (SeedCodeStage::extremityRegion).
  const Index centreBlock =
    skeleton::nearestIndex(skeleton::indexCentroid(cap.indexSum, cap.count), bl.wholeDims);
  const bool iOwnCentre = bl.owned[static_cast<std::size_t>(bl.rank)].contains(centreBlock);
  const bool centreVessel =
    ownersAnswer(collectives, iOwnCentre, iOwnCentre && bm.test(blockLocal(centreBlock)));
  const std::array<double, 3> centre = centreVessel
                                         ? skeleton::blockCentre(centreBlock, 1)
                                         : skeleton::blockCentre(cap.indexSum, cap.count);
  // The vessel voxel nearest that centre: the owners' candidates, ties to the smaller index.
  const skeleton::CentreWindow window(centre, layout.wholeDims);
  double best = std::numeric_limits<double>::infinity();
  std::int64_t bestLin = -1;
  const VoxelBox& owned = layout.owned[static_cast<std::size_t>(layout.rank)];
  for (std::int64_t k = std::max(window.lo[2], owned.lo[2]);
       k <= std::min(window.hi[2], owned.hi[2]);
       ++k)
    for (std::int64_t j = std::max(window.lo[1], owned.lo[1]);
         j <= std::min(window.hi[1], owned.hi[1]);
         ++j)
      for (std::int64_t i = std::max(window.lo[0], owned.lo[0]);
           i <= std::min(window.hi[0], owned.hi[0]);
           ++i)
      {
        const double d = skeleton::CentreWindow::distance2_mm2(centre, spacing_mm.data(), i, j, k);
        if (d < best && mask.test(localOf({ i, j, k })))
        {
          best = d;
          bestLin = layout.wholeLinear({ i, j, k });
        }
      }
  std::vector<double> mine;
  if (bestLin >= 0)
  {
    mine = { best, static_cast<double>(bestLin) };
  }
  best = std::numeric_limits<double>::infinity();
  bestLin = -1;
  for (const std::vector<double>& v : collectives.allGather(mine))
  {
    const auto lin = v.empty() ? -1 : static_cast<std::int64_t>(v[1]);
    if (!v.empty() && (v[0] < best || (v[0] == best && lin < bestLin)))
    {
      best = v[0];
      bestLin = lin;
    }
  }
  if (bestLin < 0)
  {
    return std::nullopt;
  }
  return layout.wholeIndex(bestLin);
}

std::vector<Index> Chooser::exactRoots()
{
  const DistributedEndCap::Cap cap = DistributedEndCap::find(
    collectives, layout, mask, spacing_mm, *fine, bandWidth_mm, true, par.maximumRounds);
  rounds += cap.rounds;
  if (!cap.settled)
  {
    throw Stop{ cap.message };
  }
  const Index centre =
    skeleton::nearestIndex(skeleton::indexCentroid(cap.indexSum, cap.count), layout.wholeDims);
  const bool iOwnCentre = owns(centre);
  if (ownersAnswer(collectives, iOwnCentre, iOwnCentre && mask.test(localOf(centre))))
  {
    return { centre };
  }
  std::vector<Index> roots; // the whole cap, as the single run's propagate(region)
  for (const std::int64_t w : cap.voxels_Whole)
  {
    roots.push_back(layout.wholeIndex(w));
  }
  return roots;
}

void Chooser::keepField(DistributedRootChoice::Result& result) const
{
  const std::vector<float>& ss = fine->ss();
  for (std::size_t r = 0; r < ss.size(); ++r)
  {
    if (ss[r] != kInf)
    {
      result.ss_mm[r] = ss[r];
    }
  }
}

void Chooser::moveToThickest(DistributedRootChoice::ComponentRoot& component)
{
  if (!boundary)
  {
    boundary = std::make_unique<DistributedBoundaryCode::Result>(
      DistributedBoundaryCode::compute(layout, mask, spacing_mm, collectives));
    moveExchanges += boundary->exchanges;
    moveValues += boundary->gatheredValues;
    if (!boundary->ok)
    {
      throw Stop{ boundary->message };
    }
  }
  const DistributedClusterGraph::Graph graph = DistributedClusterGraph::build(
    layout, mask, spacing_mm, inverseBandWidth, fine->ss(), boundary->bs_mm, collectives);
  moveExchanges += graph.exchanges;
  moveValues += graph.gatheredValues;
  std::vector<std::uint32_t> keyOrder(graph.clusters.size());
  for (std::uint32_t c = 0; c < keyOrder.size(); ++c)
  {
    keyOrder[c] = c; // the graph comes in the key order
  }
  const std::optional<std::uint32_t> end = skeleton::thickerEnd(graph.clusters, keyOrder);
  if (!end)
  {
    return;
  }
  // ClusterStage::thickerRoot's voxel: at the end cluster's integer centroid when vessel, else
  // its voxel of largest BS.
  const skeleton::Cluster& c = graph.clusters[*end];
  const Index centre = skeleton::nearestIndex(
    skeleton::indexCentroid({ c.indexSum[0], c.indexSum[1], c.indexSum[2] }, c.count),
    layout.wholeDims);
  const bool iOwnCentre = owns(centre);
  const bool centreVessel =
    ownersAnswer(collectives, iOwnCentre, iOwnCentre && mask.test(localOf(centre)));
  const Index root = centreVessel ? centre : layout.wholeIndex(graph.bestVoxel_Whole[*end]);
  propagate(*fine, { root });
  component.moved = true;
  component.roots_Whole = { root };
}

void Chooser::addComponent(DistributedRootChoice::Result& result,
  const std::vector<Index>& roots,
  std::uint64_t size,
  bool fromBlocks)
{
  DistributedRootChoice::ComponentRoot component;
  component.roots_Whole = roots;
  component.extremity_Whole = roots;
  component.voxels = size;
  component.fromBlocks = fromBlocks;
  moveToThickest(component);
  result.components.push_back(std::move(component));
  keepField(result);
}

void Chooser::chooseAll(DistributedRootChoice::Result& result)
{
  result.ss_mm.assign(mask.vesselCount(), kInf);
  const double vessel = collectives.sum(static_cast<double>(ownedVessel.size()));
  onBlocks = vessel >= static_cast<double>(skeleton::SeedCodeStage::kCoarseFromVoxels) &&
             layout.wholeDims[0] >= 2 && layout.wholeDims[1] >= 2 && layout.wholeDims[2] >= 2;
  if (onBlocks)
  {
    std::string error;
    try
    {
      blocks = std::make_unique<DistributedBlockPiece>(layout, mask);
      const std::array<double, 3> blockSpacing{
        2 * spacing_mm[0], 2 * spacing_mm[1], 2 * spacing_mm[2]
      };
      blockCode = std::make_unique<DistributedSeedCode>(blocks->layout, blocks->mask, blockSpacing);
      blockBandWidth_mm =
        skeleton::VoxelGrid(blocks->mask, blockSpacing, par.clusterWidth_mm).bandWidth;
      blockExplored.assign(blocks->mask.vesselCount(), 0);
    }
    catch (const std::invalid_argument& e)
    {
      error = e.what();
    }
    if (const std::string verdict = agree(collectives, error); !verdict.empty())
    {
      throw Stop{ verdict };
    }
  }
  for (std::int64_t s = nextStart(); s >= 0; s = nextStart())
  {
    const Index start = layout.wholeIndex(s);
    if (onBlocks)
    {
      if (const std::optional<Index> root = blockRoot(start))
      {
        const bool iOwnRoot = owns(*root);
        const bool rootExplored =
          ownersAnswer(collectives, iOwnRoot, iOwnRoot && explored[mask.rank(localOf(*root))]);
        if (!rootExplored)
        {
          propagate(*fine, { *root });
          const bool iOwnStart = owns(start);
          if (ownersAnswer(collectives, iOwnStart, iOwnStart && fine->ssAt(localOf(start)) != kInf))
          {
            const std::uint64_t size = markExplored();
            if (size >= par.minimumComponentSize)
            {
              addComponent(result, { *root }, size, true);
            }
            continue;
          } // else the blocks joined two components: the exact search
        }
      }
    }
    propagate(*fine, { start });
    const std::uint64_t size = markExplored();
    if (size < par.minimumComponentSize)
    {
      continue;
    }
    const std::vector<Index> roots = exactRoots();
    propagate(*fine, roots);
    addComponent(result, roots, size, false);
  }
  result.propagations = propagations;
  result.rounds = rounds;
  result.moveExchanges = moveExchanges;
  result.moveValues = moveValues;
  result.boundBs_mm = boundary ? boundary->largestBound_mm : 0.0;
}

} // namespace

DistributedRootChoice::Result DistributedRootChoice::choose(const PieceLayout& layout,
  const SparseVesselMask& pieceMask,
  const std::array<double, 3>& spacing_mm,
  RankCollectives& collectives,
  const Parameters& parameters)
{
  Result result;
  Chooser chooser(layout, pieceMask, spacing_mm, collectives, parameters);
  std::string error;
  try
  {
    chooser.prepare();
  }
  catch (const std::invalid_argument& e)
  {
    error = e.what();
  }
  result.message = agree(collectives, error);
  if (!result.message.empty())
  {
    result.message = "DistributedRootChoice: " + result.message;
    return result;
  }
  try
  {
    chooser.chooseAll(result);
  }
  catch (const Stop& stop)
  {
    result.message = "DistributedRootChoice: " + stop.message;
    result.components.clear();
    result.ss_mm.clear();
    return result;
  }
  result.ok = true;
  return result;
}

} // namespace vtouch

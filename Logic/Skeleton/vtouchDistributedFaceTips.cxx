// vtouch::DistributedFaceTips: the true tips' traces followed across the pieces, and each face
// tip's answer from them (see the header for the rule and why the chains agree across ranks).
#include "vtouchDistributedFaceTips.h"

#include "vtouchCollectiveRounds.h"
#include "vtouchDistributedTipOrder.h"
#include "vtouchSkeletonClusterStage.h"
#include "vtouchSkeletonTracer.h"

#include <algorithm>
#include <array>
#include <cstddef>
#include <limits>
#include <memory>
#include <string>
#include <unordered_map>
#include <utility>

namespace vtouch
{
namespace
{
/// A message's kind: a chain handed over to the owner of its next voxel, or a voxel a chain
/// crossed in the sender's owned box, told to a rank that holds it.
constexpr std::int64_t kContinue = 0;
constexpr std::int64_t kCrossed = 1;

/// How far a face tip's own descent is searched for a crossing chain: this many bands plus two
/// local radii of where the descent leaves the face (project rule: the slab a chain crosses where
/// it enters the piece lies within a radius of the face, and a step of at most sqrt(3) voxels
/// skips at most one band of the largest spacing; a band more absorbs the face's cut slabs).
/// Beyond it a chain met on the descent came from elsewhere (a branch joining below the face).
///
/// The descent is still at the face while its voxel lies within a radius of a cut face (h19k)
/// or in a cluster a shared face cuts (h19j), and the radius is the vessel's, the largest BS of
/// the clusters the descent has crossed so far, two causes found on the scaling trees (27 Nov):
/// - an oblique entry (h19k): the face tip's own cluster is only the slab's part inside the
///   piece, and where a vessel crosses the face obliquely that part is a sliver at the wall (BS
///   about a voxel), whose descent runs along the face across the vessel to its ridge: a window
///   of the sliver's BS ended it short of the chain there (the 512 x 512 x 256 tree on 2 pieces,
///   a branch entering at 45 degrees, radius 6.4 voxels: "none", traced as a loop's side, 1.47
///   voxels off at its junction); where the vessel runs nearly along the face (the same tree
///   split in z, a branch ~74 degrees from the face's normal) its axis stays outside the held
///   box for several radii and the descent runs beside it along the face;
/// - a graze (h19j, the 256^3 tree's junction at (138, 137, 138)): a vessel running just outside
///   the held box has only its wall inside, cut lengthwise by the face; the chain on its axis
///   enters the piece only where the vessel turns in, as far down the descent as the vessel
///   grazes the face (0.5 mm beyond the window from the start there: the leg was traced last
///   as a loop's side, and 29 points up to 1.6 voxels off moved at the junction it rises into).
constexpr double kAnswerWindow_bands = 3.0;
constexpr double kAnswerWindow_radii = 2.0;

CollectiveRounds roundsOfFaceTips()
{
  return CollectiveRounds({ "the face tips' traces across the pieces",
                            "the true tips' traces cross between pieces that often only in a "
                            "network that is not a vessel tree",
                            "extract on one rank" },
    CollectiveRounds::Payload::IndicesAndValues);
}

/// One message: where (whole linear index), to whom, which kind, in one int64 (the value: the tip's
/// rank key).
std::int64_t encode(std::int64_t wholeLinear, int dest, int ranks, std::int64_t kind)
{
  return ((wholeLinear * ranks) + dest) * 2 + kind;
}

/// The rank's piece as the rounds see it: its grid, codes and clusters (the coder's, read only).
class Piece
{
public:
  Piece(const skeleton::SkeletonTracer& t, const PieceLayout& l, bool outerLayerCleared)
    : tracer(t)
    , layout(l)
    , owned(l.owned[static_cast<std::size_t>(l.rank)])
    , coded(outerLayerCleared ? l.evaluable(l.rank) : l.mine())
  {
  }

  std::array<std::int64_t, 3> wholeOf(std::uint32_t lin) const
  {
    std::int64_t c[3];
    tracer.grid.coords(lin, c);
    return layout.toWhole({ c[0], c[1], c[2] });
  }
  /// The local vessel voxel of whole index `w` with a finite code, or -1.
  std::int64_t localOf(const std::array<std::int64_t, 3>& w) const
  {
    if (!layout.mine().contains(w))
    {
      return -1;
    }
    const std::array<std::int64_t, 3> l = layout.toLocal(w);
    const std::uint64_t lin = tracer.grid.linOf(l[0], l[1], l[2]);
    if (!tracer.grid.mask.test(lin) ||
        tracer.codes.ss[tracer.grid.mask.rank(lin)] == skeleton::VoxelCodes::kInf)
    {
      return -1;
    }
    return static_cast<std::int64_t>(lin);
  }
  float ssOf(std::uint32_t lin) const { return tracer.codes.ss[tracer.grid.mask.rank(lin)]; }
  std::uint32_t clusterOf(std::uint32_t lin) const { return tracer.clusterOf(lin); }
  /// The descent without touches (the single run's trace before anything is traced).
  std::vector<std::uint32_t> chain(std::uint32_t start) const
  {
    return tracer.descend(start, -1.0F, std::numeric_limits<std::size_t>::max()).voxels;
  }

  /// The distance (mm) from local voxel `lin` to the nearest face of the coded box that is not the
  /// volume's (a face the piece cuts); infinite when the held box is the whole volume.
  double toCutFace_mm(std::uint32_t lin) const
  {
    const VoxelBox& box = coded;
    const std::array<std::int64_t, 3> w = wholeOf(lin);
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t a = 0; a < 3; ++a)
    {
      const double spacing = tracer.grid.sp[a];
      if (box.lo[a] > 0)
      {
        best = std::min(best, static_cast<double>(w[a] - box.lo[a]) * spacing);
      }
      if (box.hi[a] < layout.wholeDims[a] - 1)
      {
        best = std::min(best, static_cast<double>(box.hi[a] - w[a]) * spacing);
      }
    }
    return best;
  }

  /// Per cluster: touches a face of the coded box that is not the volume's (cut by the piece).
  std::vector<bool> cutClusters() const
  {
    const skeleton::VoxelGrid& g = tracer.grid;
    const VoxelBox& box = coded;
    std::vector<bool> cut(tracer.graph.clusters.size(), false);
    g.mask.forEach(
      [&](std::uint64_t lin)
      {
        if (tracer.codes.ss[g.mask.rank(lin)] == skeleton::VoxelCodes::kInf)
        {
          return;
        }
        const std::array<std::int64_t, 3> w = wholeOf(static_cast<std::uint32_t>(lin));
        for (std::size_t a = 0; a < 3; ++a)
        {
          if ((w[a] == box.lo[a] && box.lo[a] > 0) ||
              (w[a] == box.hi[a] && box.hi[a] < layout.wholeDims[a] - 1))
          {
            cut[clusterOf(static_cast<std::uint32_t>(lin))] = true;
            return;
          }
        }
      });
    return cut;
  }

  const skeleton::SkeletonTracer& tracer;
  const PieceLayout& layout;
  const VoxelBox& owned;
  /// The box the coder's mask fills: the held box, or (the raw seeded mode, whose region is exact
  /// only there: SeededDistributedCoding::Settings::clearOuterLayer) the evaluable box. Its faces
  /// that are not the volume's are where the piece cuts the vessels (the face tips' faces).
  const VoxelBox coded;
};

/// One rank's side of the rounds: the chains it follows, what it sends and what it was told.
class Follower
{
public:
  Follower(const Piece* p, const PieceLayout& l)
    : piece(p)
    , layout(l)
  {
  }

  /// Follows the chain from local voxel `start` of its tip's rank key `key` (DistributedTipOrder:
  /// the tip's band and its place in the single run's order) through the owned box.
  void follow(std::uint32_t start, std::int64_t key, CollectiveRounds::Report& out)
  {
    auto [it, fresh] = followed.emplace(start, key);
    if (!fresh && it->second >= key)
    {
      return; // this chain carries a rank key at least as large already
    }
    it->second = key;
    for (const std::uint32_t v : piece->chain(start))
    {
      const std::array<std::int64_t, 3> w = piece->wholeOf(v);
      const std::int64_t lin = layout.wholeLinear(w);
      if (!piece->owned.contains(w))
      {
        send(out, lin, layout.ownerOf(w), kContinue, key);
        return;
      }
      for (int r = 0; r < layout.ranks(); ++r)
      {
        if (r != layout.rank && layout.held[static_cast<std::size_t>(r)].contains(w))
        {
          auto [s, added] = crossedSent.emplace(encode(lin, r, layout.ranks(), kCrossed), key);
          if (added || s->second < key)
          {
            s->second = key;
            send(out, lin, r, kCrossed, key);
          }
        }
      }
    }
  }

  /// The messages addressed to this rank in the last exchange: chains to follow (returned) and
  /// crossed voxels (kept, by local voxel: the largest rank key, the tip the single run traces
  /// first).
  std::vector<std::pair<std::uint32_t, std::int64_t>> receive(
    const CollectiveRounds::Exchange& previous)
  {
    std::vector<std::pair<std::uint32_t, std::int64_t>> chains;
    const std::int64_t ranks = layout.ranks();
    for (std::size_t r = 0; r < previous.indices.size() && piece; ++r)
    {
      for (std::size_t q = 0; q < previous.indices[r].size(); ++q)
      {
        const std::int64_t code = previous.indices[r][q];
        const std::int64_t kind = code % 2;
        const std::int64_t dest = (code / 2) % ranks;
        if (dest != layout.rank)
        {
          continue;
        }
        const std::int64_t local = piece->localOf(layout.wholeIndex(code / 2 / ranks));
        if (local < 0)
        {
          continue; // not a coded vessel voxel here (a component this rank does not code)
        }
        const auto key = static_cast<std::int64_t>(previous.values[r][q]);
        const auto lin = static_cast<std::uint32_t>(local);
        if (kind == kContinue)
        {
          chains.emplace_back(lin, key);
        }
        else
        {
          std::int64_t& b = crossed.emplace(lin, key).first->second;
          b = std::max(b, key);
        }
      }
    }
    return chains;
  }

  const Piece* piece;
  const PieceLayout& layout;
  std::unordered_map<std::uint32_t, std::int64_t> followed;   // local start -> key
  std::unordered_map<std::int64_t, std::int64_t> crossedSent; // message -> key
  std::unordered_map<std::uint32_t, std::int64_t> crossed;    // local voxel -> key

private:
  void send(CollectiveRounds::Report& out,
    std::int64_t wholeLinear,
    int dest,
    std::int64_t kind,
    std::int64_t key) const
  {
    if (dest < 0)
    {
      return; // outside the volume: not a vessel voxel's neighbour
    }
    out.indices.push_back(encode(wholeLinear, dest, layout.ranks(), kind));
    out.values.push_back(static_cast<double>(key));
  }
};

/// The face tips' answers from the crossed voxels, and the true tips' own rank keys (see the
/// header).
std::vector<std::int64_t> answers(const Piece& piece,
  const std::unordered_map<std::uint32_t, std::int64_t>& crossed,
  const std::vector<bool>& cut,
  const DistributedTipOrder& order)
{
  const std::vector<skeleton::Cluster>& clusters = piece.tracer.graph.clusters;
  const skeleton::VoxelGrid& grid = piece.tracer.grid;
  std::unordered_map<std::uint32_t, std::int64_t> crossedCluster; // cluster -> largest key
  for (const auto& [lin, key] : crossed)
  {
    std::int64_t& b = crossedCluster.emplace(piece.clusterOf(lin), key).first->second;
    b = std::max(b, key);
  }
  std::vector<std::int64_t> result(clusters.size(), DistributedFaceTips::kNotAFaceTip);
  for (std::uint32_t c = 0; c < clusters.size(); ++c)
  {
    if (!clusters[c].higher.empty() || clusters[c].band == 0)
    {
      continue;
    }
    if (!cut[c])
    {
      // A true tip (also one whose trace another rank follows): its place in the single run's
      // order, so that it and a face tip answered with another tip of its band go in that order.
      result[c] = order.rankKeyOf(
        piece.layout.wholeLinear(piece.wholeOf(clusters[c].firstVoxel)), clusters[c].band);
      continue;
    }
    result[c] = DistributedFaceTips::kNoTipBeyond;
    const std::uint32_t start = skeleton::ClusterStage::tipStart(grid, clusters[c]);
    double top_mm = piece.ssOf(start) - kAnswerWindow_bands * grid.bandWidth;
    double radius_mm = grid.minSpacing;
    for (const std::uint32_t v : piece.chain(start))
    {
      const skeleton::Cluster& at = clusters[piece.clusterOf(v)];
      radius_mm = std::max(radius_mm, static_cast<double>(at.maxBs));
      if (cut[piece.clusterOf(v)] || piece.toCutFace_mm(v) <= radius_mm)
      {
        top_mm = piece.ssOf(v) - kAnswerWindow_bands * grid.bandWidth; // still at the face
      }
      if (at.band == 0 || piece.ssOf(v) < top_mm - kAnswerWindow_radii * radius_mm)
      {
        break; // the root band (both sides of a root meet there) or beyond the window
      }
      const auto hit = crossedCluster.find(piece.clusterOf(v));
      if (hit != crossedCluster.end())
      {
        result[c] = hit->second;
        break;
      }
    }
  }
  return result;
}
} // namespace

DistributedFaceTips::DistributedFaceTips(RankCollectives& collectives,
  PieceLayout layout,
  int maximumRounds)
  : Collectives(collectives)
  , Layout(std::move(layout))
  , MaximumRounds(maximumRounds)
{
}

std::vector<std::int64_t> DistributedFaceTips::answer(const skeleton::SkeletonTracer& tracer)
{
  return this->run(&tracer);
}

void DistributedFaceTips::join()
{
  this->run(nullptr);
}

std::vector<std::int64_t> DistributedFaceTips::run(const skeleton::SkeletonTracer* tracer)
{
  if (this->Joined)
  {
    throw std::logic_error("DistributedFaceTips: a rank joins the face tips' rounds once per run");
  }
  this->Joined = true;
  std::unique_ptr<Piece> piece;
  std::vector<bool> cut;
  // This rank's own true tips: clusters without higher neighbours, out of the root band, not cut
  // by a shared face, their start voxel owned (each followed by one rank), with their rank keys.
  std::vector<std::pair<std::uint32_t, std::int64_t>> tips;
  std::vector<std::uint32_t> tipClusters;
  std::vector<DistributedTipOrder::Tip> ownTips;
  if (tracer && !tracer->graph.clusters.empty())
  {
    piece = std::make_unique<Piece>(*tracer, this->Layout, this->OuterLayerCleared);
    cut = piece->cutClusters();
    const std::vector<skeleton::Cluster>& clusters = tracer->graph.clusters;
    for (std::uint32_t c = 0; c < clusters.size(); ++c)
    {
      if (!clusters[c].higher.empty() || clusters[c].band == 0 || cut[c])
      {
        continue;
      }
      const std::uint32_t start = skeleton::ClusterStage::tipStart(tracer->grid, clusters[c]);
      if (piece->owned.contains(piece->wholeOf(start)))
      {
        tipClusters.push_back(c);
        ownTips.push_back({ clusters[c].band,
          piece->ssOf(clusters[c].firstVoxel),
          this->Layout.wholeLinear(piece->wholeOf(clusters[c].firstVoxel)) });
      }
    }
  }
  // The single run's order of every true tip (collective: every rank, with or without tips).
  DistributedTipOrder order;
  try
  {
    order.gather(this->Collectives, ownTips);
  }
  catch (const std::runtime_error& e)
  {
    throw DistributedFaceTipsError(e.what()); // on every rank: they gathered the same list
  }
  for (std::size_t i = 0; i < tipClusters.size(); ++i)
  {
    const skeleton::Cluster& c = tracer->graph.clusters[tipClusters[i]];
    tips.emplace_back(skeleton::ClusterStage::tipStart(tracer->grid, c),
      order.rankKeyOf(ownTips[i].firstWhole, c.band));
  }
  Follower follower(piece.get(), this->Layout);
  this->Outcome = roundsOfFaceTips().run(
    this->Collectives,
    [&](const CollectiveRounds::Exchange& previous)
    {
      const std::vector<std::pair<std::uint32_t, std::int64_t>> chains =
        previous.rounds == 0 ? tips : follower.receive(previous);
      CollectiveRounds::Report report;
      for (const auto& [start, key] : chains)
      {
        follower.follow(start, key, report);
      }
      return report;
    },
    this->MaximumRounds);
  if (!this->Outcome.settled)
  {
    throw DistributedFaceTipsError(
      "VesselCenterline (distributed): " + this->Outcome.message + ".");
  }
  if (!piece)
  {
    return std::vector<std::int64_t>(tracer ? tracer->graph.clusters.size() : 0, kNotAFaceTip);
  }
  return answers(*piece, follower.crossed, cut, order);
}

} // namespace vtouch

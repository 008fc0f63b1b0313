// VesselCandidateRegion's run on a distributed volume (issue 19 item 2, issue 16 item 1), both
// ways of the raw path: seeded (one click on a raw angiogram: the range from the seed's
// neighbourhood, the network grown from the seed, tubes only) and without a seed (the range from
// the whole volume, every voxel in it, tubes only). Each rank holds its piece grown by the ghost
// margin; every rank calls extract() (a collective) and takes the same branch: the same range,
// the same verdicts, the same message. Its result is the region on the rank's held piece, for
// the voxel coder there.
//
// Each step of VesselCandidateRegion::extract, and how it is made the single run's
// (Docs/CLIENT-SERVER.md, "The raw seeded mode, distributed"):
//  1. the volume's scan (extremes, two-valued): each rank scans its piece, the scans are combined
//     (global);
//  2. the range: the rank owning the seed voxel estimates it on its piece, which holds the seed's
//     neighbourhood when the ghost margin is at least its half size (kRangeMarginVoxels, checked),
//     and sends it to every rank with the seed verdict (background, outside: every rank the same
//     message);
//  3. growth: DistributedRegionGrowth, in rounds (exact on every rank's evaluable box);
//  4. dim dead-end strands (DimStrandPruner): local to each rank's piece (strands are a few
//     voxels long; a strand cut by a piece's edge lies in its ghost margin);
//  5. "no vessel-like structure": the region's voxel count summed over the ranks' owned voxels;
//  6. depth (RegionDepth): local (a voxel's depth is exact when the piece edge is farther than
//     it); the largest depth, which sets the tubularity's largest scale, is the ranks' maximum;
//  7. tubularity: DistributedTubularity, at the common scales, its tiles and coarse grids on the
//     whole volume's lattice and the blocks of a tile's box beyond the piece from their holders:
//     the single run's at every site whose depth the piece decides as the single run (h19t);
//  8. neck cutting's kept voxels: local (a core's reach is its depth + 1); whether any core
//     exists: summed over the ranks (global);
//  9. the seed's kept voxel: on the seed's rank, sent to all (global verdict);
// 10. the seed's component of the kept voxels: DistributedRegionGrowth again (global).
// Without a seed (Settings::useSeed off; Docs/CLIENT-SERVER.md, "The raw mode without a seed,
// distributed"), steps 2, 3 and 9-10 are replaced:
//  2. the range from the whole volume: DistributedVolumeRange (fromVolume's sample, gathered;
//     exactly the single run's);
//  3. every voxel in the range (SeededRegionGrower::threshold per piece: a voxel's own value
//     decides it, exact on every held voxel); no dim strands to prune (the single run has none);
//  9. (after 5-8, with the unseeded message) the held voxels a rank does not own take their
//     owners' decision (HeldRegionFromOwners): the ranks' masks are parts of one whole mask, as
//     the automatic roots across the ranks need.
// Cancel is not offered here: a rank stopping alone would leave the others waiting.
#pragma once

#include "vtouchDimStrandPruner.h"
#include "vtouchDistributedRegionGrowth.h"
#include "vtouchDistributedTubularity.h"
#include "vtouchDistributedVolumeRange.h"
#include "vtouchHeldRegionFromOwners.h"
#include "vtouchIntensityRangeEstimator.h"
#include "vtouchRegionDepth.h"
#include "vtouchRestrictedTubularity.h"
#include "vtouchSeededRegionGrower.h"
#include "vtouchTubeNeckCutter.h"
#include "vtouchVesselCandidateRegion.h"

#include <algorithm>
#include <chrono>
#include <string>
#include <utility>
#include <vector>

namespace vtouch
{

class DistributedCandidateRegion
{
public:
  /// The ghost margin the range estimate needs (project rule): the seed's cube of
  /// IntensityRangeParameters::neighbourhoodHalfSize_voxels (24) around a seed the rank owns,
  /// and the peak search and lumen plateau (2 + 2 voxels) inside it.
  static int rangeMarginVoxels()
  {
    const IntensityRangeParameters p;
    return std::max(p.neighbourhoodHalfSize_voxels, 2 * p.peakSearchHalfSize_voxels);
  }

  struct Result
  {
    /// The region on this rank's held piece (its seed, local, on the seed's rank only); range
    /// and message the same on every rank; coreVoxels counts a core held by two ranks twice
    /// (only whether it is 0 decides).
    VesselCandidateRegion::Result region;
    bool seedHere = false;            ///< this rank holds the coder's seed
    int growthRounds = 0;             ///< the growth's rounds (the same on every rank)
    int componentRounds = 0;          ///< the seed component's rounds after the neck cut
    std::uint64_t reportedVoxels = 0; ///< voxels this rank sent, both growths
    /// Without a seed: this rank's held voxels whose decision its owner's changed (step 9).
    std::uint64_t heldVoxelsFromOwners = 0;
    /// The tubularity's block means this rank took from others (DistributedTubularity), and the
    /// blocks nobody held whole (0 unless the ghost margin is narrower than a coarse block).
    std::uint64_t tubularityBlocksReceived = 0;
    std::uint64_t tubularityBlocksNotExact = 0;
  };

  /// `piece` is this rank's held box of the volume (layout.mine()), `seed` the seed's voxel in
  /// the whole volume (may be outside it; ignored when `s.useSeed` is off: the unseeded run).
  template<typename T>
  static Result extract(const VolumeView<T>& piece,
    const PieceLayout& layout,
    const std::array<std::int64_t, 3>& seed,
    const VesselCandidateRegion::Settings& s,
    RankCollectives& collectives);

private:
  static std::vector<double> encodeText(const std::string& text)
  {
    return std::vector<double>(text.begin(), text.end());
  }
  static std::string decodeText(const std::vector<double>& v, std::size_t from)
  {
    std::string text;
    for (std::size_t i = from; i < v.size(); ++i)
    {
      text.push_back(static_cast<char>(v[i]));
    }
    return text;
  }
  static IntensityRangeEstimator::Scan combine(const std::vector<std::vector<double>>& scans);
  /// The unseeded run's last step: the held voxels from their owners (HeldRegionFromOwners),
  /// every kept voxel the region (no seed, no component).
  static void finishUnseeded(Result& out,
    SparseVesselMask& kept,
    const PieceLayout& layout,
    RankCollectives& collectives)
  {
    out.heldVoxelsFromOwners = HeldRegionFromOwners::adopt(kept, layout, collectives);
    out.region.mask = std::move(kept);
    out.region.seed = { -1, -1, -1 };
    out.region.ok = true;
  }
};

inline IntensityRangeEstimator::Scan DistributedCandidateRegion::combine(
  const std::vector<std::vector<double>>& scans)
{
  IntensityRangeEstimator::Scan s;
  bool any = false;
  std::vector<double> values; // the distinct values met while every piece is two-valued
  for (const std::vector<double>& v : scans)
  {
    if (v.size() != 6 || v[5] < 0.0) // an empty piece
    {
      continue;
    }
    s.minimum = any ? std::min(s.minimum, v[0]) : v[0];
    s.maximum = any ? std::max(s.maximum, v[1]) : v[1];
    any = true;
    s.twoValued = s.twoValued && v[2] > 0.5;
    for (double x : { v[3], v[4] })
    {
      if ((x == v[3] || v[5] > 0.5) && std::find(values.begin(), values.end(), x) == values.end())
      {
        values.push_back(x);
      }
    }
  }
  s.twoValued = s.twoValued && values.size() <= 2;
  return s;
}

template<typename T>
DistributedCandidateRegion::Result DistributedCandidateRegion::extract(const VolumeView<T>& piece,
  const PieceLayout& layout,
  const std::array<std::int64_t, 3>& seed,
  const VesselCandidateRegion::Settings& s,
  RankCollectives& collectives)
{
  using Clock = std::chrono::steady_clock;
  auto t0 = Clock::now();
  Result out;
  VesselCandidateRegion::Result& r = out.region;
  const auto lap = [&t0, &r](const char* name)
  {
    const auto now = Clock::now();
    r.stageSeconds.emplace_back(name, std::chrono::duration<double>(now - t0).count());
    t0 = now;
  };
  r.mask = SparseVesselMask(piece.dims);
  r.mask.finalize();
  // 1. The volume's scan, combined.
  std::vector<double> mine{ 0.0, 0.0, 0.0, 0.0, 0.0, -1.0 };
  if (piece.size() > 0)
  {
    const IntensityRangeEstimator::Scan local = IntensityRangeEstimator::scan(piece);
    mine = { local.minimum,
      local.maximum,
      local.twoValued ? 1.0 : 0.0,
      local.first,
      local.second,
      local.haveSecond ? 1.0 : 0.0 };
  }
  const IntensityRangeEstimator::Scan scan = combine(collectives.allGather(mine));
  // 2. The range: on the seed's rank, every rank getting it with the verdict; without a seed
  // from the whole volume's sample, on every rank.
  int owner = -1;
  bool seedRank = false;
  std::array<std::int64_t, 3> qWhole{ -1, -1, -1 };
  if (!s.useSeed)
  {
    r.range = DistributedVolumeRange::estimate(piece, layout, scan, collectives);
  }
  else
  {
    owner = layout.ownerOf(seed);
    if (owner < 0)
    {
      r.message = IntensityRangeEstimator::outsideMessage();
      return out;
    }
    seedRank = owner == layout.rank;
    std::vector<double> sent;
    if (seedRank)
    {
      const std::array<std::int64_t, 3> local = layout.toLocal(seed);
      IntensityRange range;
      // The seed's cube must be inside this piece (or stop at the volume's faces).
      const int c = IntensityRangeParameters{}.neighbourhoodHalfSize_voxels;
      // (The cube as the single run clamps it to the volume, inside the held box.)
      bool fits = true;
      const VoxelBox& held = layout.mine();
      for (std::size_t a = 0; a < 3; ++a)
      {
        fits = fits && std::max<std::int64_t>(0, seed[a] - c) >= held.lo[a] &&
               std::min<std::int64_t>(layout.wholeDims[a] - 1, seed[a] + c) <= held.hi[a];
      }
      if (!fits)
      {
        range.message = "VesselCenterline (distributed): the ghost margin is narrower than the "
                        "seed's neighbourhood (" +
                        std::to_string(c) + " voxels); extract on one rank.";
      }
      else
      {
        range = IntensityRangeEstimator::fromSeedScanned(piece, local, scan);
      }
      const auto& q = range.seedIndex;
      const std::array<std::int64_t, 3> start = range.ok ? layout.toWhole(q) : seed;
      // The seed verdict (VesselCandidateRegion: the grower's start must be in the range).
      std::string message = range.message;
      if (range.ok)
      {
        const double value = piece.at(q[0], q[1], q[2]);
        if (!(value >= range.lower && value <= range.upper))
        {
          message =
            IntensityRangeEstimator::backgroundMessage(piece.at(local[0], local[1], local[2]));
        }
      }
      sent = { range.ok && message.empty() ? 1.0 : 0.0,
        range.binary ? 1.0 : 0.0,
        range.lower,
        range.upper,
        range.weakLower,
        range.background,
        range.backgroundNoise,
        range.vessel,
        static_cast<double>(start[0]),
        static_cast<double>(start[1]),
        static_cast<double>(start[2]) };
      const std::vector<double> text = encodeText(message);
      sent.insert(sent.end(), text.begin(), text.end());
    }
    const std::vector<double> got = collectives.broadcast(sent, owner);
    r.range.ok = got[0] > 0.5;
    r.range.binary = got[1] > 0.5;
    r.range.lower = got[2];
    r.range.upper = got[3];
    r.range.weakLower = got[4];
    r.range.background = got[5];
    r.range.backgroundNoise = got[6];
    r.range.vessel = got[7];
    qWhole = { static_cast<std::int64_t>(got[8]),
      static_cast<std::int64_t>(got[9]),
      static_cast<std::int64_t>(got[10]) };
    r.range.message = decodeText(got, 11);
  }
  lap("range");
  if (!r.range.ok)
  {
    r.message = r.range.message;
    return out;
  }
  // 3-4. The network grown from the seed, across the pieces; dim dead ends pruned per piece.
  // Without a seed every voxel in the range (its own value decides it: exact on every held
  // voxel), as the single run's threshold.
  const DistributedRegionGrowth growth(layout);
  SparseVesselMask region(piece.dims);
  if (!s.useSeed)
  {
    region = SeededRegionGrower::threshold(piece, r.range);
  }
  else
  {
    std::vector<std::uint64_t> dim;
    const IntensityRange& range = r.range;
    const auto accept = [&piece, &range](std::uint64_t lin)
    {
      const auto c = piece.index(lin);
      return SeededRegionGrower::joins(piece, range, c[0], c[1], c[2]);
    };
    const auto onJoin = [&piece, &range, &dim](std::uint64_t lin)
    {
      if (!SeededRegionGrower::strong(piece, range, lin))
      {
        dim.push_back(lin);
      }
    };
    std::vector<std::uint64_t> seeds;
    if (seedRank)
    {
      const auto q = layout.toLocal(qWhole);
      seeds.push_back(piece.linear(q[0], q[1], q[2]));
    }
    const DistributedRegionGrowth::Outcome grown =
      growth.run(collectives, region, seeds, accept, onJoin);
    out.growthRounds = grown.rounds;
    out.reportedVoxels += grown.reportedVoxels;
    if (!grown.settled)
    {
      r.message = "VesselCenterline (distributed): " + grown.message + ".";
      return out;
    }
    DimStrandPruner::prune(piece, range, dim, region);
    region.finalize();
  }
  // 5. The region's size over the owned voxels.
  double owned = 0.0;
  const VoxelBox& mineOwned = layout.owned[static_cast<std::size_t>(layout.rank)];
  region.forEach([&](std::uint64_t lin)
    { owned += mineOwned.contains(layout.toWhole(piece.index(lin))) ? 1.0 : 0.0; });
  r.grownVoxels = static_cast<std::uint64_t>(collectives.sum(owned));
  lap("grow");
  if (r.grownVoxels == 0)
  {
    r.message = "No voxel lies in the vessel range: the volume has no vessel-like structure.";
    return out;
  }
  const bool tubes = s.cutNonTubular && !(s.automatic && r.range.binary);
  std::array<std::int64_t, 3> keptSeed = qWhole;
  SparseVesselMask kept;
  if (!tubes)
  {
    if (!s.useSeed)
    {
      finishUnseeded(out, region, layout, collectives);
      return out;
    }
    kept = std::move(region);
  }
  else
  {
    // 6-8. Depth, tubularity and the kept voxels per piece, at the ranks' common scales.
    const std::vector<std::uint16_t> depth = RegionDepth::layers(region);
    lap("depth");
    const int localDeepest = depth.empty() ? 1 : *std::max_element(depth.begin(), depth.end());
    const int deepest =
      std::min<int>(s.maximumDepth_voxels, static_cast<int>(collectives.maximum(localDeepest)));
    const RestrictedTubularity::Parameters tp =
      VesselCandidateRegion::tubularityParameters(s, r.range, deepest, piece.spacing_mm);
    const DistributedTubularity::Result measured =
      DistributedTubularity::compute(piece, layout, region, depth, tp, collectives);
    const RestrictedTubularity::Result& tube = measured.tube;
    out.tubularityBlocksReceived = measured.blocksReceived;
    out.tubularityBlocksNotExact = tube.blocksNotExact;
    lap("tubularity");
    TubeNeckCutter::Result cut = TubeNeckCutter::cut(
      region, depth, tube.tubularity, s.coreTubularity, s.thinCoreTubularity, nullptr);
    r.coreVoxels = static_cast<std::uint64_t>(collectives.sum(static_cast<double>(cut.coreVoxels)));
    if (r.coreVoxels == 0)
    {
      // VesselCandidateRegion::extract's messages, word for word.
      r.message = s.useSeed ? "The seed's region has no vessel-like (tube-shaped) part: pick a "
                              "point on a vessel in the MIP."
                            : "The volume has no vessel-like (tube-shaped) structure in the "
                              "vessel range.";
      return out;
    }
    if (!s.useSeed)
    {
      finishUnseeded(out, cut.mask, layout, collectives);
      lap("necks");
      return out;
    }
    // 9. The kept voxel nearest the seed, on the seed's rank.
    std::vector<double> verdict;
    if (seedRank)
    {
      std::array<std::int64_t, 3> found{ -1, -1, -1 };
      const bool isKept =
        TubeNeckCutter::nearestKept(cut.mask, region, depth, layout.toLocal(qWhole), found);
      const auto w = isKept ? layout.toWhole(found) : qWhole;
      verdict = { isKept ? 1.0 : 0.0,
        static_cast<double>(w[0]),
        static_cast<double>(w[1]),
        static_cast<double>(w[2]) };
    }
    const std::vector<double> v = collectives.broadcast(verdict, owner);
    if (v[0] < 0.5)
    {
      r.message = "The seed is on a structure that is not a vessel (bone, a blob or tissue at "
                  "vessel intensity): pick a point on a vessel in the MIP.";
      return out;
    }
    keptSeed = { static_cast<std::int64_t>(v[1]),
      static_cast<std::int64_t>(v[2]),
      static_cast<std::int64_t>(v[3]) };
    kept = std::move(cut.mask);
  }
  // 10. The seed's component of what is kept, across the pieces (without the tube cut the
  // growth above already is that component: one round confirms it).
  SparseVesselMask component(piece.dims);
  std::vector<std::uint64_t> start;
  if (seedRank)
  {
    const auto q = layout.toLocal(keptSeed);
    start.push_back(piece.linear(q[0], q[1], q[2]));
  }
  const DistributedRegionGrowth::Outcome joined = growth.run(
    collectives,
    component,
    start,
    [&kept](std::uint64_t lin) { return kept.test(lin); },
    DistributedRegionGrowth::OnJoin());
  out.componentRounds = joined.rounds;
  out.reportedVoxels += joined.reportedVoxels;
  if (!joined.settled)
  {
    r.message = "VesselCenterline (distributed): " + joined.message + ".";
    return out;
  }
  component.finalize();
  lap("necks");
  r.mask = std::move(component);
  if (seedRank)
  {
    r.seed = layout.toLocal(keptSeed);
    out.seedHere = true;
  }
  r.ok = true;
  return out;
}

} // namespace vtouch

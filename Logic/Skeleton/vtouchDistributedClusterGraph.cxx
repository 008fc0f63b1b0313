// vtouch::DistributedClusterGraph: one component's cluster graph across pieces (see the header).
#include "vtouchDistributedClusterGraph.h"
#include "vtouchFloatWords.h"

#include "vtouchSkeletonVoxelCodes.h"
#include "vtouchSkeletonVoxelGrid.h"

#include <algorithm>
#include <cstring>
#include <limits>
#include <numeric>
#include <utility>

namespace vtouch
{
namespace
{
using Index = std::array<std::int64_t, 3>;
constexpr float kInf = skeleton::VoxelCodes::kInf;
constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();
constexpr std::int64_t kNoVoxel = std::numeric_limits<std::int64_t>::max();

/// The root of `r` in the forest `parent` (path halving).
std::uint32_t findRoot(std::vector<std::uint32_t>& parent, std::uint32_t r)
{
  while (parent[r] != r)
  {
    parent[r] = parent[parent[r]];
    r = parent[r];
  }
  return r;
}

/// What a rank adds up of one local set, over its owned voxels (packed as kValues int64).
struct Record
{
  static constexpr std::size_t kValues = 11;
  std::int64_t name = 0; // the set's smallest held voxel, whole linear index
  std::int64_t band = 0;
  std::int64_t count = 0;
  float maxBs = 0.0F;
  float bestSs = 0.0F;
  std::int64_t best = kNoVoxel;
  std::int64_t sum[3] = { 0, 0, 0 };
  std::int64_t first = kNoVoxel; // its smallest owned voxel
  float firstSs = 0.0F;

  /// Adds a voxel (ClusterStage's rule for the largest BS: ties to the lower SS, then the
  /// smaller index).
  void add(const Index& w, std::int64_t lin, float bs, float ss)
  {
    if (count == 0 || bs > maxBs || (bs == maxBs && (ss < bestSs || (ss == bestSs && lin < best))))
    {
      maxBs = bs;
      bestSs = ss;
      best = lin;
    }
    if (lin < first)
    {
      first = lin;
      firstSs = ss;
    }
    ++count;
    for (int a = 0; a < 3; ++a)
    {
      sum[a] += w[a];
    }
  }
  void merge(const Record& o)
  {
    if (o.count == 0)
    {
      return;
    }
    if (count == 0 || o.maxBs > maxBs ||
        (o.maxBs == maxBs && (o.bestSs < bestSs || (o.bestSs == bestSs && o.best < best))))
    {
      maxBs = o.maxBs;
      bestSs = o.bestSs;
      best = o.best;
    }
    if (o.first < first)
    {
      first = o.first;
      firstSs = o.firstSs;
    }
    count += o.count;
    band = o.band;
    for (int a = 0; a < 3; ++a)
    {
      sum[a] += o.sum[a];
    }
  }
  void pack(std::vector<std::int64_t>& out) const
  {
    out.insert(out.end(),
      { name,
        band,
        count,
        floatToWord(maxBs),
        floatToWord(bestSs),
        best,
        sum[0],
        sum[1],
        sum[2],
        first,
        floatToWord(firstSs) });
  }
  static Record unpack(const std::int64_t* v)
  {
    Record r;
    r.name = v[0];
    r.band = v[1];
    r.count = v[2];
    r.maxBs = wordToFloat(v[3]);
    r.bestSs = wordToFloat(v[4]);
    r.best = v[5];
    r.sum[0] = v[6];
    r.sum[1] = v[7];
    r.sum[2] = v[8];
    r.first = v[9];
    r.firstSs = wordToFloat(v[10]);
    return r;
  }
};

/// Union-find over set names (whole linear indices): the smaller name is the root.
class NameForest
{
public:
  explicit NameForest(std::vector<std::int64_t> all)
    : names(std::move(all))
  {
    std::sort(names.begin(), names.end());
    names.erase(std::unique(names.begin(), names.end()), names.end());
    parent.resize(names.size());
    std::iota(parent.begin(), parent.end(), 0U);
  }
  std::uint32_t find(std::int64_t name)
  {
    const auto i = static_cast<std::uint32_t>(
      std::lower_bound(names.begin(), names.end(), name) - names.begin());
    return findRoot(parent, i);
  }
  void unite(std::int64_t a, std::int64_t b)
  {
    const std::uint32_t x = find(a), y = find(b);
    parent[std::max(x, y)] = std::min(x, y);
  }
  std::size_t size() const { return names.size(); }

private:
  std::vector<std::int64_t> names;
  std::vector<std::uint32_t> parent;
};

/// One rank's part: its local sets and what it tells the others.
class LocalSets
{
public:
  LocalSets(const PieceLayout& l,
    const SparseVesselMask& m,
    const std::array<double, 3>& sp,
    float inverseBandWidth,
    const std::vector<float>& s,
    const std::vector<float>& b)
    : layout(l)
    , mask(m)
    , grid(m, sp, 0.0)
    , inverse(inverseBandWidth)
    , ss(s)
    , bs(b)
  {
  }
  void build();
  /// (set name, ghost voxel) for every held, not owned voxel of the component.
  std::vector<std::int64_t> ghostNames() const { return ghosts; }
  /// (their name, my name) for the others' ghost voxels this rank owns.
  std::vector<std::int64_t> answers(const std::vector<std::vector<std::int64_t>>& all) const;
  /// The records of the sets with owned voxels, then their touching pairs (names).
  std::vector<std::int64_t> report() const;

private:
  std::uint32_t band(std::uint32_t r) const { return static_cast<std::uint32_t>(ss[r] * inverse); }
  Index wholeOf(std::uint64_t localLin) const
  {
    std::int64_t c[3];
    grid.coords(localLin, c);
    return layout.toWhole({ c[0], c[1], c[2] });
  }
  bool owns(const Index& w) const
  {
    return layout.owned[static_cast<std::size_t>(layout.rank)].contains(w);
  }

  const PieceLayout& layout;
  const SparseVesselMask& mask;
  skeleton::VoxelGrid grid;
  float inverse;
  const std::vector<float>& ss;
  const std::vector<float>& bs;
  std::vector<std::uint32_t> setOf; // per piece vessel voxel: its local set, or kNone
  std::vector<Record> sets;
  std::vector<std::int64_t> ghosts;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> touching; // local sets, different bands
};

void LocalSets::build()
{
  std::vector<std::uint32_t> parent(mask.vesselCount(), kNone);
  std::uint32_t r = 0;
  // Same-band 26-neighbours joined, each pair once (from the later one in scan order), the
  // smaller rank the root: ClusterStage's union.
  mask.forEach(
    [&](std::uint64_t lin)
    {
      const std::uint32_t me = r++;
      if (ss[me] == kInf)
      {
        return;
      }
      parent[me] = me;
      std::uint32_t root = me;
      grid.forNeighbours(
        lin,
        [&](std::uint64_t, int, std::uint32_t ru)
        {
          if (ss[ru] != kInf && band(ru) == band(me))
          {
            const std::uint32_t y = findRoot(parent, ru);
            if (y != root)
            {
              parent[std::max(root, y)] = std::min(root, y);
              root = std::min(root, y);
            }
          }
        },
        skeleton::VoxelGrid::kHalf);
    });
  setOf.assign(mask.vesselCount(), kNone);
  r = 0;
  mask.forEach(
    [&](std::uint64_t lin)
    {
      const std::uint32_t me = r++;
      if (ss[me] == kInf)
      {
        return;
      }
      const std::uint32_t root = findRoot(parent, me);
      if (root == me)
      {
        setOf[me] = static_cast<std::uint32_t>(sets.size());
        sets.emplace_back();
        sets.back().name = layout.wholeLinear(wholeOf(lin));
        sets.back().band = band(me);
      }
      else
      {
        setOf[me] = setOf[root];
      }
      const std::uint32_t s = setOf[me];
      const Index w = wholeOf(lin);
      const bool mine = owns(w);
      if (mine)
      {
        sets[s].add(w, layout.wholeLinear(w), bs[me], ss[me]);
      }
      else
      {
        ghosts.push_back(sets[s].name);
        ghosts.push_back(layout.wholeLinear(w));
      }
      grid.forNeighbours(
        lin,
        [&](std::uint64_t u, int, std::uint32_t ru)
        {
          if (ss[ru] != kInf && band(ru) != band(me) && (mine || owns(wholeOf(u))))
          {
            const std::uint32_t a = s, b = setOf[ru];
            touching.emplace_back(std::min(a, b), std::max(a, b));
          }
        },
        skeleton::VoxelGrid::kHalf);
    });
  std::sort(touching.begin(), touching.end());
  touching.erase(std::unique(touching.begin(), touching.end()), touching.end());
}

std::vector<std::int64_t> LocalSets::answers(
  const std::vector<std::vector<std::int64_t>>& all) const
{
  std::vector<std::int64_t> out;
  const Index d = layout.pieceDims();
  for (const std::vector<std::int64_t>& v : all)
  {
    for (std::size_t p = 0; p + 1 < v.size(); p += 2)
    {
      const Index w = layout.wholeIndex(v[p + 1]);
      if (!owns(w))
      {
        continue;
      }
      const Index l = layout.toLocal(w);
      const auto lin = static_cast<std::uint64_t>(l[0] + d[0] * (l[1] + d[1] * l[2]));
      const std::uint32_t s = mask.test(lin) ? setOf[mask.rank(lin)] : kNone;
      if (s != kNone && sets[s].name != v[p])
      {
        out.push_back(v[p]);
        out.push_back(sets[s].name);
      }
    }
  }
  return out;
}

std::vector<std::int64_t> LocalSets::report() const
{
  std::vector<std::int64_t> out{ 0 };
  for (const Record& s : sets)
  {
    if (s.count > 0)
    {
      s.pack(out);
      ++out[0];
    }
  }
  for (const auto& t : touching)
  {
    out.push_back(sets[t.first].name);
    out.push_back(sets[t.second].name);
  }
  return out;
}

std::uint64_t valuesIn(const std::vector<std::vector<std::int64_t>>& all)
{
  std::uint64_t n = 0;
  for (const std::vector<std::int64_t>& v : all)
  {
    n += v.size();
  }
  return n;
}
} // namespace

DistributedClusterGraph::Graph DistributedClusterGraph::build(const PieceLayout& layout,
  const SparseVesselMask& pieceMask,
  const std::array<double, 3>& spacing_mm,
  float inverseBandWidth,
  const std::vector<float>& ss_mm,
  const std::vector<float>& bs_mm,
  RankCollectives& collectives)
{
  Graph g;
  LocalSets local(layout, pieceMask, spacing_mm, inverseBandWidth, ss_mm, bs_mm);
  local.build();
  const std::vector<std::vector<std::int64_t>> ghosts = collectives.allGather(local.ghostNames());
  const std::vector<std::vector<std::int64_t>> answers =
    collectives.allGather(local.answers(ghosts));
  const std::vector<std::vector<std::int64_t>> reports = collectives.allGather(local.report());
  g.exchanges = 3;
  g.gatheredValues = valuesIn(ghosts) + valuesIn(answers) + valuesIn(reports);
  // Every name, then the clusters: the names joined by the owners' answers.
  std::vector<std::int64_t> names;
  for (const std::vector<std::int64_t>& v : answers)
  {
    names.insert(names.end(), v.begin(), v.end());
  }
  for (const std::vector<std::int64_t>& v : reports)
  {
    const auto records = static_cast<std::size_t>(v[0]);
    for (std::size_t q = 0; q < records; ++q)
    {
      names.push_back(v[1 + q * Record::kValues]);
    }
    names.insert(
      names.end(), v.begin() + static_cast<std::ptrdiff_t>(1 + records * Record::kValues), v.end());
  }
  NameForest forest(names);
  for (const std::vector<std::int64_t>& v : answers)
  {
    for (std::size_t p = 0; p + 1 < v.size(); p += 2)
    {
      forest.unite(v[p], v[p + 1]);
    }
  }
  std::vector<Record> byRoot(forest.size());
  for (const std::vector<std::int64_t>& v : reports)
  {
    const auto records = static_cast<std::size_t>(v[0]);
    for (std::size_t q = 0; q < records; ++q)
    {
      const Record r = Record::unpack(v.data() + 1 + q * Record::kValues);
      byRoot[forest.find(r.name)].merge(r);
    }
  }
  // The clusters in key order.
  std::vector<std::uint32_t> roots;
  for (std::uint32_t i = 0; i < byRoot.size(); ++i)
  {
    if (byRoot[i].count > 0)
    {
      roots.push_back(i);
    }
  }
  std::sort(roots.begin(),
    roots.end(),
    [&](std::uint32_t a, std::uint32_t b)
    {
      return std::make_pair(byRoot[a].firstSs, byRoot[a].first) <
             std::make_pair(byRoot[b].firstSs, byRoot[b].first);
    });
  std::vector<std::uint32_t> clusterOf(byRoot.size(), kNone);
  g.clusters.resize(roots.size());
  for (std::uint32_t c = 0; c < roots.size(); ++c)
  {
    const Record& r = byRoot[roots[c]];
    clusterOf[roots[c]] = c;
    skeleton::Cluster& out = g.clusters[c];
    out.band = static_cast<std::uint32_t>(r.band);
    out.count = static_cast<std::uint32_t>(r.count);
    out.maxBs = r.maxBs;
    for (int a = 0; a < 3; ++a)
    {
      out.indexSum[a] = r.sum[a];
    }
    g.bestVoxel_Whole.push_back(r.best);
    g.firstVoxel_Whole.push_back(r.first);
  }
  for (const std::vector<std::int64_t>& v : reports)
  {
    const auto records = static_cast<std::size_t>(v[0]);
    for (std::size_t p = 1 + records * Record::kValues; p + 1 < v.size(); p += 2)
    {
      const std::uint32_t a = clusterOf[forest.find(v[p])], b = clusterOf[forest.find(v[p + 1])];
      if (a == kNone || b == kNone || g.clusters[a].band == g.clusters[b].band)
      {
        continue;
      }
      const std::uint32_t hi = g.clusters[a].band > g.clusters[b].band ? a : b;
      const std::uint32_t lo = hi == a ? b : a;
      g.clusters[hi].lower.push_back(lo);
      g.clusters[lo].higher.push_back(hi);
    }
  }
  for (skeleton::Cluster& c : g.clusters)
  {
    for (std::vector<std::uint32_t>* list : { &c.lower, &c.higher })
    {
      std::sort(list->begin(), list->end());
      list->erase(std::unique(list->begin(), list->end()), list->end());
    }
  }
  return g;
}

} // namespace vtouch

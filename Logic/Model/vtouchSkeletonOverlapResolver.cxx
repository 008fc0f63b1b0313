#include "vtouchSkeletonOverlapResolver.h"

#include "vtouchFragmentSegmentGrid.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>

namespace vtouch
{

SkeletonOverlapResolver::SkeletonOverlapResolver(const PieceOwnership& ownership,
  const IndexFrame& frame)
  : ownership_(ownership)
  , frame_(frame)
{
}

bool SkeletonOverlapResolver::wins(const Vec3& p, int r, const Vec3& q, int s) const
{
  const int o = ownership_.owner(frame_.toIndex((p + q) * 0.5));
  if (o == r || o == s)
  {
    return o == r;
  }
  return r < s;
}

namespace
{
/// Project rule: the half width, in points, of the window whose majority decides which copy of
/// a point is kept (see resolve()).
constexpr std::size_t kDecisionHalfWindow = 3;

/// Another piece's nearest copy of a point.
struct Copy
{
  long fragment = -1; ///< -1: no copy
  int piece = -1;
  double at = 0.0; ///< where on the copy's fragment, a fractional point index
  Vec3 position;
  double distance = std::numeric_limits<double>::infinity();
  /// |cos| of the angle between the two fragments' directions there (1 when either has none).
  double alignment = 1.0;
  /// The copy is its fragment's attached end: a duplicate of the parent point it hangs on.
  bool attachedEnd = false;
};

/// Copies this much nearer or farther than another are equally near (a point and its copy are
/// often equal up to the rounding of a projection, mm).
constexpr double kTie_mm = 1e-6;

/// The unit direction of a fragment at point i (central difference), or zero for one point.
Vec3 directionAt(const SkeletonFragment& f, std::size_t i)
{
  const std::size_t n = f.points.size();
  if (n < 2)
  {
    return {};
  }
  const std::size_t a = i == 0 ? 0 : i - 1;
  const std::size_t b = i + 1 >= n ? n - 1 : i + 1;
  const Vec3 d = f.points[b].position_World_mm - f.points[a].position_World_mm;
  const double length = d.norm();
  return length > 0.0 ? d * (1.0 / length) : Vec3{};
}

/// Whether point i of `f` is an attached end of it (a branch's first point, on its parent's).
bool isAttachedEnd(const SkeletonFragment& f, std::size_t i)
{
  return (i == 0 && f.head.kind == FragmentEnd::Kind::Attached) ||
         (i + 1 == f.points.size() && f.tail.kind == FragmentEnd::Kind::Attached);
}

/// The nearest point of each other piece's fragments to point i of fragment g, on their
/// segments (the coder's points may lie several voxels apart with DownsampleFactor: the lateral
/// offset is what tells copies apart), within `reach_mm` and running alike; nearest first.
/// A point within `coincident_mm` is a copy whatever the directions (see
/// SkeletonOverlapResolver::coincidentPoint_mm), unless either is an attached end.
std::vector<Copy> nearestCopies(const std::vector<SkeletonFragment>& fragments,
  const FragmentSegmentGrid& grid,
  std::size_t g,
  std::size_t i,
  double reach_mm,
  double minimumCosine,
  double coincident_mm)
{
  const SkeletonFragment& f = fragments[g];
  const Vec3& p = f.points[i].position_World_mm;
  const Vec3 dp = directionAt(f, i);
  const bool pointAttached = isAttachedEnd(f, i);
  std::vector<Copy> best;
  grid.visitNear(p,
    [&](const FragmentPointGrid::Item& item)
    {
      const SkeletonFragment& other = fragments[item.fragment];
      if (other.piece == f.piece)
      {
        return;
      }
      const std::size_t m = other.points.size();
      for (std::size_t a = item.point == 0 ? 0 : item.point - 1; a <= item.point; ++a)
      {
        const std::size_t b = std::min(a + 1, m - 1);
        const Vec3& qa = other.points[a].position_World_mm;
        const Vec3 ab = other.points[b].position_World_mm - qa;
        const double length2 = ab.dot(ab);
        const double t = length2 > 0.0 ? std::clamp((p - qa).dot(ab) / length2, 0.0, 1.0) : 0.0;
        const Vec3 q = qa + ab * t;
        const double d = (q - p).norm();
        if (d > reach_mm)
        {
          continue;
        }
        const Vec3 dq = length2 > 0.0 ? ab * (1.0 / std::sqrt(length2)) : Vec3{};
        const bool directed = dp.norm() > 0.0 && dq.norm() > 0.0;
        const double alignment = directed ? std::abs(dp.dot(dq)) : 1.0;
        Copy c;
        c.fragment = static_cast<long>(item.fragment);
        c.piece = other.piece;
        c.at = static_cast<double>(a) + t * static_cast<double>(b - a);
        c.position = q;
        c.distance = d;
        c.alignment = alignment;
        c.attachedEnd = isAttachedEnd(other, static_cast<std::size_t>(std::lround(c.at)));
        const bool samePoint = d <= coincident_mm && !pointAttached && !c.attachedEnd;
        if (alignment < minimumCosine && !samePoint)
        {
          continue; // another vessel passing near (a branch at its junction)
        }
        const auto same = std::find_if(
          best.begin(), best.end(), [&](const Copy& x) { return x.piece == other.piece; });
        if (same == best.end())
        {
          best.push_back(c);
        }
        else if (d < same->distance - kTie_mm ||
                 (std::abs(d - same->distance) <= kTie_mm &&
                   std::make_pair(!c.attachedEnd, c.alignment) >
                     std::make_pair(!same->attachedEnd, same->alignment)))
        {
          // Ties of distance: a junction's point is both a point of the parent path and the
          // first point of the branch attached there (a copy of it). The parent's point is the
          // copy, then the one along the same vessel (project rule; on the 512 x 512 x 256
          // tree a junction on a face went to the branch's copy, and the parent path, cut a
          // voxel short, left an unmatched cut end).
          *same = c;
        }
      }
    });
  std::sort(best.begin(),
    best.end(),
    [](const Copy& a, const Copy& b)
    { return std::tie(a.distance, a.piece) < std::tie(b.distance, b.piece); });
  return best;
}

/// A run [first, last] of fragment `source` with its ends.
OverlapRun makeRun(const std::vector<SkeletonFragment>& fragments,
  std::size_t source,
  std::size_t first,
  std::size_t last,
  const std::vector<long>& toward)
{
  const SkeletonFragment& f = fragments[source];
  OverlapRun run;
  run.source = source;
  run.fragment.piece = f.piece;
  run.fragment.points.assign(f.points.begin() + static_cast<std::ptrdiff_t>(first),
    f.points.begin() + static_cast<std::ptrdiff_t>(last + 1));
  const auto cutAt = [&](std::size_t kept, std::size_t dropped, long& towardOut, double& gap)
  {
    gap = (f.points[dropped].position_World_mm - f.points[kept].position_World_mm).norm();
    FragmentEnd end;
    end.kind = FragmentEnd::Kind::Cut;
    end.position_World_mm = f.points[kept].position_World_mm;
    towardOut = toward[dropped];
    end.neighbourPiece = towardOut >= 0 ? fragments[static_cast<std::size_t>(towardOut)].piece : -1;
    return end;
  };
  run.fragment.head = first == 0 ? f.head : cutAt(first, first - 1, run.headToward, run.headGap_mm);
  run.fragment.tail =
    last + 1 == f.points.size() ? f.tail : cutAt(last, last + 1, run.tailToward, run.tailGap_mm);
  return run;
}

/// The majority of `raw` over the window of each point among the points where `counts` holds;
/// a tie keeps the point's own.
std::vector<signed char> majority(const std::vector<signed char>& raw,
  const std::vector<char>& counts)
{
  std::vector<signed char> out = raw;
  const std::size_t n = raw.size();
  for (std::size_t i = 0; i < n; ++i)
  {
    if (!counts[i])
    {
      continue;
    }
    int kept = 0, total = 0;
    for (std::size_t j = i; counts[j] && i - j <= kDecisionHalfWindow; --j)
    {
      kept += raw[j];
      ++total;
      if (j == 0)
      {
        break;
      }
    }
    for (std::size_t j = i + 1; j < n && counts[j] && j - i <= kDecisionHalfWindow; ++j)
    {
      kept += raw[j];
      ++total;
    }
    out[i] = 2 * kept > total ? 1 : (2 * kept < total ? 0 : raw[i]);
  }
  return out;
}

/// Distance from `p` to the nearest segment (or lone point) of the kept points of fragment `f`.
double distanceToKept(const SkeletonFragment& f,
  const std::vector<signed char>& keep,
  const Vec3& p)
{
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t a = 0; a < f.points.size(); ++a)
  {
    if (!keep[a])
    {
      continue;
    }
    const Vec3& qa = f.points[a].position_World_mm;
    const bool segment = a + 1 < f.points.size() && keep[a + 1];
    const Vec3 ab = segment ? f.points[a + 1].position_World_mm - qa : Vec3{};
    const double length2 = ab.dot(ab);
    const double t = length2 > 0.0 ? std::clamp((p - qa).dot(ab) / length2, 0.0, 1.0) : 0.0;
    best = std::min(best, (qa + ab * t - p).norm());
  }
  return best;
}

/// The swap of settleOnePointRuns: the lone kept point g[i] gives way to its nearest copy c
/// (fragment h) when h's points around the copy were dropped in g's favour. Those points of h
/// (the contiguous stretch dropped toward g around the copy) that g's other kept points do not
/// cover are kept again; the swap is made only when they, with h's kept neighbours, form a run of
/// at least two points. Returns whether it was made (g[i] is then dropped toward h).
bool giveBack(const std::vector<SkeletonFragment>& fragments,
  const Copy& c,
  std::size_t g,
  std::size_t i,
  double reach_mm,
  std::vector<std::vector<signed char>>& keep,
  std::vector<std::vector<long>>& toward)
{
  const auto h = static_cast<std::size_t>(c.fragment);
  const std::size_t m = keep[h].size();
  const std::size_t j = std::min(static_cast<std::size_t>(std::lround(c.at)), m - 1);
  const auto lostToG = [&](std::size_t k)
  { return !keep[h][k] && toward[h][k] == static_cast<long>(g); };
  if (!lostToG(j))
  {
    return false;
  }
  keep[g][i] = 0; // tentatively: which of h's points does g still cover without it?
  std::size_t first = j, last = j;
  while (first > 0 && lostToG(first - 1))
  {
    --first;
  }
  while (last + 1 < m && lostToG(last + 1))
  {
    ++last;
  }
  std::vector<std::size_t> back;
  for (std::size_t k = first; k <= last; ++k)
  {
    if (distanceToKept(fragments[g], keep[g], fragments[h].points[k].position_World_mm) > reach_mm)
    {
      back.push_back(k);
    }
  }
  const bool keptNeighbour = !back.empty() && ((back.front() > 0 && keep[h][back.front() - 1]) ||
                                                (back.back() + 1 < m && keep[h][back.back() + 1]));
  const bool contiguous = !back.empty() && back.back() - back.front() + 1 == back.size();
  if (!contiguous || (back.size() < 2 && !keptNeighbour))
  {
    keep[g][i] = 1;
    return false;
  }
  for (const std::size_t k : back)
  {
    keep[h][k] = 1;
    toward[h][k] = -1;
  }
  return true;
}

/// The copies a lone kept point i (of a fragment of n points whose drops went to `toward`) may
/// swap with (giveBack), in order: its nearest copy, then its copies within `coincident_mm` (the
/// same centre coded by both pieces) in the fragments its dropped neighbours went to. Project
/// rule (h17y): at a junction on an edge of pieces every piece coded the same centre, so the
/// nearest copy is a tie at distance 0 decided by the lowest piece, often a band fragment with
/// nothing kept around it; the fragment the neighbours went to dropped this very point in the
/// lone point's favour, and unless it takes it back the point is dropped below as a copy of that
/// fragment's kept neighbours: neither keeps it (the Y in the CTA's frame on 1 2 2 pieces lost
/// its junction point, 0.708 mm). Only a coincident copy: taking it back changes no position,
/// while a copy a fraction of a voxel off is the existing rules' business (the random vessels
/// of SkeletonStitchProperty, whose copies are shifted: one of them lost its join otherwise).
std::vector<const Copy*> swapCandidates(const std::vector<Copy>& copies,
  const std::vector<long>& toward,
  std::size_t i,
  std::size_t n,
  double coincident_mm)
{
  std::vector<const Copy*> out;
  if (copies.empty())
  {
    return out;
  }
  out.push_back(&copies.front());
  for (const std::size_t k : { i - 1, i + 1 })
  {
    if (k >= n || toward[k] < 0)
    {
      continue; // (i - 1 wraps past n at i = 0)
    }
    for (const Copy& c : copies)
    {
      if (c.fragment == toward[k] && c.distance <= coincident_mm &&
          std::find(out.begin(), out.end(), &c) == out.end())
      {
        out.push_back(&c);
      }
    }
  }
  return out;
}

/// Project rule (issue 19, item 2): a kept run of one point is no path (a polyline needs two
/// points; the session refuses it). Found on the 256^3 scaling tree with 4 ranks: a branch
/// leaving its parent at a shallow angle, each rank placing the junction ~4 voxels apart along
/// the parent; the lower rank's branch lost every point to the other's copy but its attached head
/// (on the parent), whose one-sided direction failed the copy test. Such a point is settled here:
/// - swapped back: when its nearest copy h[j], or else its coincident copy in the fragment its
///   dropped neighbours went to (swapCandidates, h17y), was dropped in its favour, the copy it
///   replaced takes its place again (giveBack): one run, not a zigzag of one-point runs;
/// - a copy: when it lies within the copy reach (no direction test: its direction is one-sided or
///   crosses the switch) of the kept points of the fragment its dropped neighbours went to, it is
///   dropped as a duplicate of that geometry; not when its two neighbours went to two different
///   fragments (it bridges them: a path across a corner, SkeletonStitcher's corner test).
/// Otherwise it is left (it may still bridge two cut ends); the stitcher drops a chain that ends
/// with fewer than two points (StitchReport::strayPointsDropped).
void settleOnePointRuns(const std::vector<SkeletonFragment>& fragments,
  const std::vector<std::vector<std::vector<Copy>>>& copies,
  double reach_mm,
  double coincident_mm,
  std::vector<std::vector<signed char>>& keep,
  std::vector<std::vector<long>>& toward)
{
  for (std::size_t g = 0; g < fragments.size(); ++g)
  {
    const std::size_t n = keep[g].size();
    for (std::size_t i = 0; i < n; ++i)
    {
      const bool leftDropped = i > 0 && !keep[g][i - 1];
      const bool rightDropped = i + 1 < n && !keep[g][i + 1];
      const bool alone = keep[g][i] && (i == 0 || leftDropped) && (i + 1 == n || rightDropped);
      if (!alone || !(leftDropped || rightDropped))
      {
        continue;
      }
      long settledToward = -1;
      for (const Copy* c : swapCandidates(copies[g][i], toward[g], i, n, coincident_mm))
      {
        if (giveBack(fragments, *c, g, i, reach_mm, keep, toward))
        {
          settledToward = c->fragment;
          break;
        }
      }
      // A point between stretches that went to two different fragments bridges them (a path
      // across a corner: the two kept runs may lie farther apart than a join reaches): it stays.
      const bool bridge = leftDropped && rightDropped && toward[g][i - 1] != toward[g][i + 1];
      for (const std::size_t k : { i - 1, i + 1 })
      {
        if (bridge || settledToward >= 0 || k >= n || keep[g][k] || toward[g][k] < 0)
        {
          continue; // (i - 1 wraps past n at i = 0)
        }
        const auto h = static_cast<std::size_t>(toward[g][k]);
        if (distanceToKept(fragments[h], keep[h], fragments[g].points[i].position_World_mm) <=
            reach_mm)
        {
          settledToward = toward[g][k];
        }
      }
      if (settledToward >= 0)
      {
        keep[g][i] = 0;
        toward[g][i] = settledToward;
      }
    }
  }
}
} // namespace

std::vector<OverlapRun> SkeletonOverlapResolver::resolve(
  const std::vector<SkeletonFragment>& fragments,
  int& duplicatesRemoved,
  const ProgressSpan& progress) const
{
  duplicatesRemoved = 0;
  double longestSegment = 0.0;
  for (const SkeletonFragment& f : fragments)
  {
    for (std::size_t i = 0; i + 1 < f.points.size(); ++i)
    {
      longestSegment = std::max(
        longestSegment, (f.points[i + 1].position_World_mm - f.points[i].position_World_mm).norm());
    }
  }
  // The candidates in the order of a grid of cells of the reach plus half the longest segment
  // (the order decides ties), found through cells of the reach alone (h18s: one long junction
  // link made those cells huge; vtouch::FragmentSegmentGrid).
  const FragmentSegmentGrid grid(fragments, copyReach_mm + 0.5 * longestSegment, copyReach_mm);
  const std::size_t F = fragments.size();
  std::uint64_t points = 0;
  for (const SkeletonFragment& f : fragments)
  {
    points += f.points.size();
  }
  // The copy search is most of the resolver's time: its check points (h18q).
  ProgressCounter searched(progress.part(0.0, 0.9), points, kPointPeriod);
  std::vector<std::vector<std::vector<Copy>>> copies(F);
  for (std::size_t g = 0; g < F; ++g)
  {
    for (std::size_t i = 0; i < fragments[g].points.size(); ++i)
    {
      copies[g].push_back(
        nearestCopies(fragments, grid, g, i, copyReach_mm, minimumCopyCosine, coincidentPoint_mm));
      searched.tick();
    }
  }
  progress.report(0.9);
  // keep[g][i]: 1 kept, 0 dropped for a copy (toward[g][i] its fragment). Where one other piece
  // has a copy (a face), the lower piece's side decides (the midpoint rule, smoothed along its
  // fragment) and the other side takes the complement at its copy's place on the deciding
  // fragment, so that the two decisions meet without a gap. Where several pieces have copies
  // (an edge or a corner) the copies' centroid decides (winsAll).
  std::vector<std::vector<signed char>> keep(F);
  std::vector<std::vector<long>> toward(F);
  // With several pieces' copies (an edge or a corner) the pairwise rule can drop them all (each
  // loses to one other): the copies' centroid decides instead (the same point from every copy,
  // up to where each one's nearest copies lie): its owner keeps its copy; when its owner has
  // none, the lowest piece does.
  const auto winsAll = [&](std::size_t g, std::size_t i, long& winner)
  {
    winner = -1;
    const std::vector<Copy>& c = copies[g][i];
    const int own = fragments[g].piece;
    if (c.size() == 1)
    {
      const bool kept =
        wins(fragments[g].points[i].position_World_mm, own, c[0].position, c[0].piece);
      winner = kept ? -1 : c[0].fragment;
      return kept;
    }
    Vec3 centroid = fragments[g].points[i].position_World_mm;
    const Copy* lowest = nullptr;
    for (const Copy& x : c)
    {
      centroid = centroid + x.position;
      lowest = !lowest || x.piece < lowest->piece ? &x : lowest;
    }
    centroid = centroid * (1.0 / static_cast<double>(c.size() + 1));
    const int o = ownership_.owner(frame_.toIndex(centroid));
    if (o == own)
    {
      return true;
    }
    for (const Copy& x : c)
    {
      if (x.piece == o)
      {
        winner = x.fragment;
        return false;
      }
    }
    if (own < lowest->piece)
    {
      return true;
    }
    winner = lowest->fragment;
    return false;
  };
  for (std::size_t g = 0; g < F; ++g)
  {
    const SkeletonFragment& f = fragments[g];
    const std::size_t n = f.points.size();
    std::vector<signed char> raw(n, 1);
    std::vector<char> deciding(n, 0);
    toward[g].assign(n, -1);
    for (std::size_t i = 0; i < n; ++i)
    {
      const std::vector<Copy>& c = copies[g][i];
      deciding[i] = c.size() == 1 && c[0].piece > f.piece ? 1 : 0;
      long winner = -1;
      raw[i] = c.empty() || winsAll(g, i, winner) ? 1 : 0;
    }
    keep[g] = majority(raw, deciding);
  }
  for (std::size_t g = 0; g < F; ++g)
  {
    const SkeletonFragment& f = fragments[g];
    for (std::size_t i = 0; i < f.points.size(); ++i)
    {
      const std::vector<Copy>& c = copies[g][i];
      if (c.size() == 1 && c[0].piece < f.piece)
      {
        const auto h = static_cast<std::size_t>(c[0].fragment);
        const auto j = std::min(static_cast<std::size_t>(std::lround(c[0].at)), keep[h].size() - 1);
        const std::vector<Copy>& back = copies[h][j];
        if (back.size() == 1 && back[0].fragment == static_cast<long>(g))
        {
          keep[g][i] = keep[h][j] ? 0 : 1;
        }
      }
      if (!keep[g][i])
      {
        long winner = -1;
        winsAll(g, i, winner);
        toward[g][i] = winner >= 0 ? winner : c.front().fragment;
      }
    }
  }
  settleOnePointRuns(fragments, copies, copyReach_mm, coincidentPoint_mm, keep, toward);
  progress.report(1.0);
  std::vector<OverlapRun> runs;
  for (std::size_t g = 0; g < F; ++g)
  {
    const std::size_t n = keep[g].size();
    for (std::size_t i = 0; i < n; ++i)
    {
      duplicatesRemoved += keep[g][i] ? 0 : 1;
    }
    std::size_t i = 0;
    while (i < n)
    {
      if (!keep[g][i])
      {
        ++i;
        continue;
      }
      std::size_t j = i;
      while (j + 1 < n && keep[g][j + 1])
      {
        ++j;
      }
      runs.push_back(makeRun(fragments, g, i, j, toward[g]));
      i = j + 1;
    }
  }
  return runs;
}

} // namespace vtouch

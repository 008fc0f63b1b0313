#include "vtouchSkeletonStitcher.h"

#include "vtouchOverlapBandStubs.h"
#include "vtouchSegmentGrid.h"
#include "vtouchSkeletonOverlapResolver.h"
#include "vtouchSkeletonPointIndex.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <sstream>
#include <tuple>

namespace vtouch
{

namespace
{
/// Paths attached between two check points. Project rule (h18q): attaching a path's ends costs
/// up to about 2 ms on the long-run scenes (the nearest point of the whole stitched skeleton).
constexpr std::uint64_t kPathPeriod = 8;

/// Project rule (h18s): the attachments' point index is asked for the accepted distance plus
/// this (mm), so that no rounding drops a point the scan would accept (a point too many is
/// measured as the scan measured it and changes nothing).
constexpr double kIndexMargin_mm = 1e-6;

/// End e of the fragment list: fragment e / 2, head when e is even, tail when odd.
const FragmentEnd& endOf(const std::vector<SkeletonFragment>& f, std::size_t e)
{
  return e % 2 == 0 ? f[e / 2].head : f[e / 2].tail;
}

const SkeletonPoint& endPoint(const std::vector<SkeletonFragment>& f, std::size_t e)
{
  const SkeletonFragment& fragment = f[e / 2];
  return e % 2 == 0 ? fragment.points.front() : fragment.points.back();
}

std::string describe(const char* what, const Vec3& p, int piece)
{
  std::ostringstream text;
  text.precision(4);
  text << what << " of piece " << piece << " at (" << p.x << ", " << p.y << ", " << p.z << ") mm";
  return text.str();
}

/// The run end e's fragment-level "toward" (the source fragment whose copy won the next point).
long towardOf(const std::vector<OverlapRun>& runs, std::size_t e)
{
  return e % 2 == 0 ? runs[e / 2].headToward : runs[e / 2].tailToward;
}

/// The run end e's gap to its dropped neighbour (0 for a fragment's own end).
double gapOf(const std::vector<OverlapRun>& runs, std::size_t e)
{
  return e % 2 == 0 ? runs[e / 2].headGap_mm : runs[e / 2].tailGap_mm;
}

/// Pairs the cut ends: partner[e] is the end joined to e, or -1.
std::vector<long> matchCutEnds(const std::vector<OverlapRun>& runs,
  const std::vector<SkeletonFragment>& f,
  double tolerance_mm,
  double copyReach_mm,
  StitchReport& report)
{
  const std::size_t ends = 2 * f.size();
  std::vector<long> partner(ends, -1);
  std::vector<std::size_t> cuts;
  for (std::size_t e = 0; e < ends; ++e)
  {
    if (endOf(f, e).kind == FragmentEnd::Kind::Cut)
    {
      cuts.push_back(e);
    }
  }
  // (overlap, pass, consistency, distance, a, b): the overlap's own partner first (a run cut
  // where another fragment's copy won joins that fragment's run), across pieces next, named
  // neighbours next, nearest first.
  using Candidate = std::tuple<int, int, int, double, std::size_t, std::size_t>;
  std::vector<Candidate> candidates;
  for (std::size_t i = 0; i < cuts.size(); ++i)
  {
    for (std::size_t k = i + 1; k < cuts.size(); ++k)
    {
      const std::size_t a = cuts[i], b = cuts[k];
      if (a / 2 == b / 2)
      {
        continue; // a fragment's own two ends: never a loop of one short excursion
      }
      const FragmentEnd& ea = endOf(f, a);
      const FragmentEnd& eb = endOf(f, b);
      const double d = (ea.position_World_mm - eb.position_World_mm).norm();
      double reach =
        std::max(tolerance_mm, 0.5 * std::min(endPoint(f, a).radius_mm, endPoint(f, b).radius_mm));
      const long sa = static_cast<long>(runs[a / 2].source);
      const long sb = static_cast<long>(runs[b / 2].source);
      const int named = (towardOf(runs, a) == sb ? 1 : 0) + (towardOf(runs, b) == sa ? 1 : 0);
      // At an edge or corner two runs may both be cut where one third fragment's copy took
      // over, a copy that itself lost there to theirs (it kept nothing between them): they are
      // each other's neighbours across it (the property test's corner of 8 pieces).
      const long third = towardOf(runs, a);
      const bool acrossThird =
        third >= 0 && third == towardOf(runs, b) && third != sa && third != sb;
      if (named == 2 || acrossThird)
      {
        // Two runs cut where each other's copy took over: the dropped points between them lie
        // within the copy reach of each other, so the ends are at most that and the two gaps to
        // their dropped neighbours apart (points a few voxels apart with DownsampleFactor).
        reach = std::max(reach, copyReach_mm + gapOf(runs, a) + gapOf(runs, b));
      }
      if (d > reach)
      {
        continue;
      }
      const int overlap = 2 - named;
      const int pa = f[a / 2].piece, pb = f[b / 2].piece;
      const int pass = pa != pb ? 0 : 1;
      const int consistent = (ea.neighbourPiece == pb && eb.neighbourPiece == pa) ? 0 : 1;
      candidates.emplace_back(overlap, pass, consistent, d, a, b);
    }
  }
  std::sort(candidates.begin(), candidates.end());
  for (const Candidate& c : candidates)
  {
    const std::size_t a = std::get<4>(c), b = std::get<5>(c);
    if (partner[a] < 0 && partner[b] < 0)
    {
      partner[a] = static_cast<long>(b);
      partner[b] = static_cast<long>(a);
      ++report.cutEndsJoined;
    }
  }
  for (std::size_t e : cuts)
  {
    if (partner[e] < 0)
    {
      ++report.cutEndsUnmatched;
      report.notes.push_back(
        describe("unmatched cut end", endOf(f, e).position_World_mm, f[e / 2].piece));
    }
  }
  return partner;
}

/// Appends fragment `g`'s points to `path`, reversed (tangents negated) when `reversed`. Where
/// two runs meet and both kept one point (within `coincident_mm`), it is appended once: the
/// stitch makes no zero-length segment (the coder's own points pass as they are).
void appendPoints(SkeletonPath& path,
  const SkeletonFragment& g,
  bool reversed,
  double coincident_mm)
{
  std::vector<SkeletonPoint> points(g.points.begin(), g.points.end());
  if (reversed)
  {
    std::reverse(points.begin(), points.end());
    for (SkeletonPoint& p : points)
    {
      p.tangent_World = p.tangent_World * -1.0;
    }
  }
  auto first = points.begin();
  if (!path.points.empty() &&
      (first->position_World_mm - path.points.back().position_World_mm).norm() <= coincident_mm)
  {
    ++first;
  }
  path.points.insert(path.points.end(), first, points.end());
}

/// For a loop, drops the last points within `coincident_mm` of point 0 (the loop's closing link
/// is a junction onto point 0, not a segment), keeping at least two.
void trimClosedLoop(SkeletonPath& path, double coincident_mm)
{
  while (path.points.size() > 2 &&
         (path.points.back().position_World_mm - path.points.front().position_World_mm).norm() <=
           coincident_mm)
  {
    path.points.pop_back();
  }
}

/// A stitched path's free or attached ends, before the junctions are resolved.
struct ChainEnds
{
  FragmentEnd head, tail;
  bool closed = false;
};

/// Follows matched cut ends from end `start` (an end of fragment start / 2 that the chain begins
/// at); marks the fragments used.
ChainEnds walkChain(const std::vector<SkeletonFragment>& f,
  const std::vector<long>& partner,
  std::size_t start,
  std::vector<char>& used,
  double coincident_mm,
  SkeletonPath& path)
{
  ChainEnds ends;
  ends.head = endOf(f, start);
  std::size_t entry = start;
  while (true)
  {
    const std::size_t fragment = entry / 2;
    used[fragment] = 1;
    const bool reversed = entry % 2 == 1; // entered at its tail
    appendPoints(path, f[fragment], reversed, coincident_mm);
    const std::size_t exit = reversed ? 2 * fragment : 2 * fragment + 1;
    const long next = partner[exit];
    if (next < 0)
    {
      ends.tail = endOf(f, exit);
      return ends;
    }
    if (static_cast<std::size_t>(next) == start)
    {
      ends.closed = true; // back where the chain began: a loop
      return ends;
    }
    entry = static_cast<std::size_t>(next);
  }
}

/// The same position bit for bit, or both absent (NaN: the parent point is a path's end).
bool samePosition(const Vec3& a, const Vec3& b)
{
  return a.isFinite() ? (b.isFinite() && a.x == b.x && a.y == b.y && a.z == b.z) : !b.isFinite();
}

/// True when point `i` of `path` has the neighbours of `end`'s parent point, either order.
bool sameNeighbours(const SkeletonPath& path, std::size_t i, const FragmentEnd& end)
{
  const Vec3 none{
    FragmentEnd::kNoNeighbour, FragmentEnd::kNoNeighbour, FragmentEnd::kNoNeighbour
  };
  const Vec3 before = i > 0 ? path.points[i - 1].position_World_mm : none;
  const Vec3 after = i + 1 < path.points.size() ? path.points[i + 1].position_World_mm : none;
  const Vec3& b = end.parentBefore_World_mm;
  const Vec3& a = end.parentAfter_World_mm;
  return (samePosition(before, b) && samePosition(after, a)) ||
         (samePosition(before, a) && samePosition(after, b));
}

/// The nearest point of `s` to `end`'s parent position but path `self`'s points within 2 of
/// index `selfPoint`.
/// Among points at the same distance (the coder writes a path's last point twice where a child
/// hangs on it), a path's end wins (a project rule): the single run hangs the child on the end,
/// and a child hung one point before it would leave that end a free vessel end. Then the point
/// whose radius is nearest `radius_mm`, the child end's (a project rule): the child's end is a
/// copy of its parent point, radius included, while consecutive voxels of one cluster share its
/// centre (the distributed run stitches the coder's centres, whole paths smoothed afterwards).
/// Then, among points tied in all three (consecutive voxels of one cluster share its centre and
/// its radius: the same doubles, since every rank computes them in the whole volume's frame),
/// the one whose neighbours along its path are the parent point's neighbours in the coder's
/// skeleton (`end`'s, either order: a fragment may be stitched reversed), a project rule: the
/// coder hung the child on one voxel of the cluster, and the smoothing's corners
/// (smoothSkeletonPaths) sit on that point, so the single run's choice matters (the shared CTA
/// thresholded: the child one point off moved 15 points by up to 0.078 mm, h17f).
/// Never another path's attached end (`ends`): it is a copy of its own parent point, where two
/// branches leave one point the other branch's head lies on the parent point too.
/// Only `candidates` ((path index, point), in path then point order: the scan's order, which
/// decides full ties) are measured: SkeletonPointIndex gives every point within the distance the
/// caller accepts (h18s; a farther point never wins where a nearer one exists).
bool nearestPoint(const QSkeleton& s,
  const std::vector<std::pair<std::size_t, std::size_t>>& candidates,
  const std::vector<ChainEnds>& ends,
  const FragmentEnd& end,
  double radius_mm,
  int self,
  long selfPoint,
  int& path,
  int& point,
  double& d)
{
  const Vec3& p = end.position_World_mm;
  d = std::numeric_limits<double>::infinity();
  bool atEnd = false;
  double radiusOff = std::numeric_limits<double>::infinity();
  bool neighboursMatch = false;
  for (const auto& [pathIndex, i] : candidates)
  {
    const SkeletonPath& candidate = s.paths[pathIndex];
    if (candidate.id == self && std::labs(static_cast<long>(i) - selfPoint) <= 2)
    {
      continue;
    }
    const bool head = i == 0, tail = i + 1 == candidate.points.size();
    const ChainEnds& e = ends[static_cast<std::size_t>(candidate.id)];
    if (candidate.id != self && ((head && e.head.kind == FragmentEnd::Kind::Attached) ||
                                  (tail && e.tail.kind == FragmentEnd::Kind::Attached)))
    {
      continue;
    }
    const double di = (candidate.points[i].position_World_mm - p).norm();
    const bool isEnd = head || tail;
    const double off = std::abs(candidate.points[i].radius_mm - radius_mm);
    const bool matches = sameNeighbours(candidate, i, end);
    if (di < d || (di == d && isEnd && !atEnd) || (di == d && isEnd == atEnd && off < radiusOff) ||
        (di == d && isEnd == atEnd && off == radiusOff && matches && !neighboursMatch))
    {
      d = di;
      path = candidate.id;
      point = static_cast<int>(i);
      atEnd = isEnd;
      radiusOff = off;
      neighboursMatch = matches;
    }
  }
  return std::isfinite(d);
}
/// Counts the points labelled Bifurcation that no junction of `s` is near (a lost branch).
void reportLostBranches(const QSkeleton& s, double tolerance_mm, StitchReport& report)
{
  std::vector<Vec3> junctionPoints;
  for (const Junction& j : s.junctions)
  {
    junctionPoints.push_back(s.paths[static_cast<std::size_t>(j.parentPath)]
                               .points[static_cast<std::size_t>(j.parentPoint)]
                               .position_World_mm);
  }
  for (const SkeletonPath& path : s.paths)
  {
    for (const SkeletonPoint& q : path.points)
    {
      if (q.label != PointLabel::Bifurcation)
      {
        continue;
      }
      const double reach = std::max(tolerance_mm, q.radius_mm);
      const bool near = std::any_of(junctionPoints.begin(),
        junctionPoints.end(),
        [&](const Vec3& x) { return (x - q.position_World_mm).norm() <= reach; });
      if (!near)
      {
        ++report.bifurcationsWithoutBranch;
        report.notes.push_back(describe("bifurcation without its branch", q.position_World_mm, -1));
      }
    }
  }
}

/// Distance from `p` to the segment [a, b].
double segmentDistance(const Vec3& p, const Vec3& a, const Vec3& b)
{
  const Vec3 ab = b - a;
  const double length2 = ab.dot(ab);
  const double t = length2 > 0.0 ? std::clamp((p - a).dot(ab) / length2, 0.0, 1.0) : 0.0;
  return (a + ab * t - p).norm();
}

/// Counts the points of `sent` farther than `reach_mm` from `s` (its paths and junction links).
/// A check point of `progress` every kPointPeriod points.
void reportDroppedPoints(const QSkeleton& s,
  const std::vector<SkeletonFragment>& sent,
  double reach_mm,
  StitchReport& report,
  const ProgressSpan& progress)
{
  std::vector<std::pair<Vec3, Vec3>> segments;
  for (const SkeletonPath& path : s.paths)
  {
    for (std::size_t i = 0; i < path.points.size(); ++i)
    {
      const Vec3& a = path.points[i].position_World_mm;
      segments.emplace_back(
        a, i + 1 < path.points.size() ? path.points[i + 1].position_World_mm : a);
    }
  }
  for (const Junction& j : s.junctions)
  {
    const SkeletonPath& child = s.paths[static_cast<std::size_t>(j.childPath)];
    const SkeletonPoint& end =
      j.childEnd == Junction::End::Head ? child.points.front() : child.points.back();
    segments.emplace_back(end.position_World_mm,
      s.paths[static_cast<std::size_t>(j.parentPath)]
        .points[static_cast<std::size_t>(j.parentPoint)]
        .position_World_mm);
  }
  // Cells from the reach alone (vtouch::SegmentGrid, h18s): sized by the longest segment, a
  // junction link across the volume made every cell hold most segments (the check was 13.6 s of
  // the 128^3 raw phantom's 20.8 s stitch on 2 ranks). Which segments are visited, and in what
  // order, decides nothing: a point is dropped when none is within the reach.
  SegmentGrid grid(reach_mm);
  for (std::size_t k = 0; k < segments.size(); ++k)
  {
    grid.add(segments[k].first, segments[k].second, k);
  }
  std::uint64_t points = 0;
  for (const SkeletonFragment& f : sent)
  {
    points += f.points.size();
  }
  ProgressCounter checked(progress, points, SkeletonOverlapResolver::kPointPeriod);
  for (const SkeletonFragment& f : sent)
  {
    for (const SkeletonPoint& q : f.points)
    {
      checked.tick();
      double best = std::numeric_limits<double>::infinity();
      grid.visitNear(q.position_World_mm,
        [&](std::size_t k)
        {
          const auto& [a, b] = segments[k];
          best = std::min(best, segmentDistance(q.position_World_mm, a, b));
        });
      if (best > reach_mm)
      {
        if (report.pointsDropped == 0)
        {
          report.notes.push_back(
            describe("a stretch no piece kept, first point", q.position_World_mm, f.piece));
        }
        ++report.pointsDropped;
      }
    }
  }
}
} // namespace

QSkeleton SkeletonStitcher::stitch(const std::vector<SkeletonFragment>& fragments,
  StitchReport& report) const
{
  report = StitchReport{};
  // Progress shares (h18q): the 128^3 raw phantom's seeded long run on 2 ranks spent 26 % of its
  // 20.8 s stitch resolving the overlap, 9 % attaching ends and 65 % in the coverage check;
  // the joins between take milliseconds (a check point after each). Since h18s's grids the
  // check and the attachments take a fraction of that: the shares now overweight them (left
  // alone, Docs/CLIENT-SERVER.md).
  const ProgressSpan all(&this->progress);
  all.report(0.0);
  std::vector<SkeletonFragment> sent;
  for (const SkeletonFragment& fragment : fragments)
  {
    if (!fragment.points.empty())
    {
      sent.push_back(fragment);
    }
  }
  std::vector<OverlapRun> runs;
  if (ownership.pieceCount() > 0)
  {
    SkeletonOverlapResolver resolver(ownership, frame);
    resolver.copyReach_mm = copyReach_mm;
    resolver.coincidentPoint_mm = coincidentPoint_mm;
    runs = resolver.resolve(sent, report.duplicatesRemoved, all.part(0.0, 0.3));
  }
  else
  {
    for (std::size_t g = 0; g < sent.size(); ++g)
    {
      OverlapRun run;
      run.fragment = sent[g];
      run.source = g;
      runs.push_back(std::move(run));
    }
  }
  std::vector<SkeletonFragment> f;
  for (const OverlapRun& run : runs)
  {
    f.push_back(run.fragment);
  }
  all.report(0.3);
  std::vector<long> partner = matchCutEnds(runs, f, joinTolerance_mm, copyReach_mm, report);
  all.report(0.3);
  // Band runs that stitch to nothing go (vtouch::OverlapBandStubs); the ends are matched again
  // without them (the same pairs: a stub has no joined end).
  const std::vector<char> stub = OverlapBandStubs(ownership, frame).find(f, partner);
  const int stubs = static_cast<int>(std::count(stub.begin(), stub.end(), 1));
  if (stubs > 0)
  {
    std::vector<OverlapRun> keptRuns;
    for (std::size_t i = 0; i < runs.size(); ++i)
    {
      if (!stub[i])
      {
        keptRuns.push_back(std::move(runs[i]));
      }
    }
    runs = std::move(keptRuns);
    f.clear();
    for (const OverlapRun& run : runs)
    {
      f.push_back(run.fragment);
    }
    const int duplicates = report.duplicatesRemoved;
    report = StitchReport{};
    report.duplicatesRemoved = duplicates;
    report.bandStubsDropped = stubs;
    partner = matchCutEnds(runs, f, joinTolerance_mm, copyReach_mm, report);
  }
  QSkeleton s;
  std::vector<ChainEnds> chainEnds;
  std::vector<char> used(f.size(), 0);
  const auto addChain = [&](std::size_t start)
  {
    SkeletonPath path;
    path.id = static_cast<int>(s.paths.size());
    const ChainEnds ends = walkChain(f, partner, start, used, coincidentPoint_mm, path);
    if (ends.closed)
    {
      trimClosedLoop(path, coincidentPoint_mm);
    }
    if (path.points.size() < 2)
    {
      // Project rule: a chain of fewer than two points is no path (the session refuses a
      // one-point polyline): a stray the resolver could not settle (settleOnePointRuns), dropped;
      // when no kept point covers it, the coverage check below also counts it as dropped.
      report.strayPointsDropped += static_cast<int>(path.points.size());
      report.notes.push_back(describe("a stray point (a chain of one point) dropped",
        path.points.front().position_World_mm,
        f[start / 2].piece));
      return;
    }
    chainEnds.push_back(ends);
    s.paths.push_back(std::move(path));
  };
  // Open chains first, from every end that is not joined; then what is left are loops. From the
  // free heads first (project rule, h19r): a chain whose fragments all run head to tail (the
  // coder's order; with the global SS field the single run's) then runs as they do, as the
  // single run's path, instead of from whichever of its free ends comes first in the fragments'
  // order (the 256^3 raw phantom on 4 ranks: two of 27 paths reversed, and the raw path's
  // re-tracing, which runs forward from a stretch's clean point before, retraced them
  // otherwise: 0.24 voxel). Then the chains with two free tails (fragments run both ways).
  for (const std::size_t parity : { std::size_t{ 0 }, std::size_t{ 1 } })
  {
    for (std::size_t e = parity; e < 2 * f.size(); e += 2)
    {
      if (!used[e / 2] && partner[e] < 0)
      {
        addChain(e);
      }
    }
  }
  for (std::size_t g = 0; g < f.size(); ++g)
  {
    if (!used[g])
    {
      addChain(2 * g);
    }
  }
  all.report(0.3);
  // Junctions: attached ends by their parent point's position; loops onto their own point 0.
  SkeletonPointIndex points(s, joinTolerance_mm);
  ProgressCounter attached(all.part(0.3, 0.4), s.paths.size(), kPathPeriod);
  for (std::size_t i = 0; i < s.paths.size(); ++i)
  {
    attached.tick();
    SkeletonPath& path = s.paths[i];
    const ChainEnds& ends = chainEnds[i];
    if (ends.closed)
    {
      Junction j;
      j.childPath = path.id;
      j.childEnd = Junction::End::Tail;
      j.parentPath = path.id;
      j.parentPoint = 0;
      path.tail.junction = static_cast<int>(s.junctions.size());
      s.junctions.push_back(j);
      ++report.loopsClosed;
      continue;
    }
    for (const Junction::End which : { Junction::End::Head, Junction::End::Tail })
    {
      const FragmentEnd& end = which == Junction::End::Head ? ends.head : ends.tail;
      const long index =
        which == Junction::End::Head ? 0 : static_cast<long>(path.points.size()) - 1;
      SkeletonPoint& q = path.points[static_cast<std::size_t>(index)];
      if (end.kind == FragmentEnd::Kind::Cut)
      {
        q.label = PointLabel::EndPoint; // unmatched: reported above
        continue;
      }
      if (end.kind != FragmentEnd::Kind::Attached)
      {
        continue;
      }
      int parentPath = -1, parentPoint = -1;
      double d = 0.0;
      const double accepted_mm = std::max(joinTolerance_mm, 0.5 * q.radius_mm);
      const bool found = nearestPoint(s,
        points.near(end.position_World_mm, accepted_mm + kIndexMargin_mm),
        chainEnds,
        end,
        q.radius_mm,
        path.id,
        index,
        parentPath,
        parentPoint,
        d);
      if (!found || d > accepted_mm)
      {
        ++report.attachmentsUnresolved;
        report.notes.push_back(describe("unresolved attached end", q.position_World_mm, -1));
        q.label = PointLabel::EndPoint;
        continue;
      }
      // The coder writes a child's end point on its parent point; where the parent's copy was
      // dropped for another piece's, the end moves onto the kept copy (<= the copy reach).
      if ((q.position_World_mm - end.position_World_mm).norm() <= 1e-9 * (1.0 + d))
      {
        q.position_World_mm = s.paths[static_cast<std::size_t>(parentPath)]
                                .points[static_cast<std::size_t>(parentPoint)]
                                .position_World_mm;
        points.moved(i, static_cast<std::size_t>(index));
      }
      Junction j;
      j.childPath = path.id;
      j.childEnd = which;
      j.parentPath = parentPath;
      j.parentPoint = parentPoint;
      (which == Junction::End::Head ? path.head : path.tail).junction =
        static_cast<int>(s.junctions.size());
      s.junctions.push_back(j);
      ++report.attachmentsResolved;
    }
  }
  reportLostBranches(s, joinTolerance_mm, report);
  all.report(0.4);
  reportDroppedPoints(s, sent, coverageReach_mm, report, all.part(0.4, 1.0));
  all.report(1.0);
  return s;
}

} // namespace vtouch

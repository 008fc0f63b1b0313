#include "vtouchTracer.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace vtouch
{

namespace
{
constexpr int kMaxNeighbours = 16;
constexpr double kZeroLength_px = 1e-6;
constexpr int kLookAhead = 256;
constexpr double kLeadTurnCos = 0.9961946980917455; // cos 5 degrees (locationToward)

Vec2 unit(const Vec2& v)
{
  const double n = v.norm();
  return n > 0.0 ? v * (1.0 / n) : Vec2{};
}
} // namespace

void Tracer::release()
{
  this->State = InteractionState::Exploring;
  this->Location = {};
  this->Direction = 0;
  this->Junction = {};
  this->ArrivedAt = -1;
  this->ArrivedFrom = -1;
}

void Tracer::placeAt(const ViewModel& vm, int g)
{
  this->State = InteractionState::Tracing;
  this->Location = { g, -1, 0.0 };
  this->Direction = 0;
  this->TopologyId = vm.topology().id();
  this->Junction = {};
  this->ArrivedAt = -1;
  this->ArrivedFrom = -1;
}

bool Tracer::tryContact(const ViewModel& vm, const Vec2& cursor_px)
{
  if (!cursor_px.isFinite())
  {
    return false;
  }
  const int g = vm.contactAt(
    static_cast<int>(std::floor(cursor_px.x)), static_cast<int>(std::floor(cursor_px.y)));
  if (g < 0)
  {
    return false;
  }
  // The map holds the screen-nearest splatted pixel; refine to the nearest point along the path.
  const SceneTopology& topo = vm.topology();
  const int path = topo.pathOf(g);
  const int lo = std::max(topo.pathBegin(path), g - this->refineWindow);
  const int hi = std::min(topo.pathEnd(path) - 1, g + this->refineWindow);
  int best = g;
  double bestD = (vm.screen_px(g) - cursor_px).norm();
  for (int k = lo; k <= hi; ++k)
  {
    const double d = (vm.screen_px(k) - cursor_px).norm();
    if (d < bestD)
    {
      bestD = d;
      best = k;
    }
  }
  this->placeAt(vm, best);
  return true;
}

Vec2 Tracer::directionTo(const ViewModel& vm, int a, int m) const
{
  const Vec2 pa = vm.screen_px(a);
  Vec2 d = vm.screen_px(m) - pa;
  if (d.norm() > kZeroLength_px)
  {
    return unit(d);
  }
  // The edge is (nearly) parallel to the view direction: look further along the chain until the
  // screen position changes, so the agent can pass through a vessel seen end-on.
  const SceneTopology& topo = vm.topology();
  int prev = a;
  int cur = m;
  int nb[kMaxNeighbours];
  for (int k = 0; k < kLookAhead; ++k)
  {
    const int count = topo.neighbours(cur, nb, kMaxNeighbours);
    int next = -1;
    const int straight = cur + (cur - prev);
    for (int i = 0; i < count; ++i)
    {
      if (nb[i] == straight && topo.pathOf(nb[i]) == topo.pathOf(cur))
      {
        next = nb[i];
      }
    }
    for (int i = 0; i < count && next < 0; ++i)
    {
      if (nb[i] != prev)
      {
        next = nb[i];
      }
    }
    if (next < 0)
    {
      return {};
    }
    d = vm.screen_px(next) - pa;
    if (d.norm() > kZeroLength_px)
    {
      return unit(d);
    }
    prev = cur;
    cur = next;
  }
  return {};
}

double Tracer::advance(const ViewModel& vm, int a, int b, double fromT, double toT)
{
  // Torsion angle and direction bookkeeping for a move on edge a->b from fromT to toT.
  const SceneTopology& topo = vm.topology();
  const double len3 = (topo.position_World_mm(b) - topo.position_World_mm(a)).norm();
  const double ds = (toT - fromT) * len3;
  const double tau = 0.5 * (topo.torsion_per_mm(a) + topo.torsion_per_mm(b));
  const int sign = (b > a) ? 1 : -1;
  this->TorsionAngle += tau * ds * sign;
  this->ArcLength += ds * sign;
  if (std::fabs(toT - fromT) > 0.0)
  {
    this->Direction = (toT > fromT) ? sign : -sign;
  }
  // Junction bookkeeping for reconsiderJunction(): leaving a point of more than two neighbours
  // records the choice made there; reaching a point records where the agent came from.
  const int left = fromT <= 0.0 && toT > 0.0 ? a : (fromT >= 1.0 && toT < 1.0 ? b : -1);
  if (left >= 0)
  {
    const int toward = left == a ? b : a;
    const int entry = this->ArrivedAt == left ? this->ArrivedFrom : -1;
    int nb[kMaxNeighbours];
    if (toward != entry && topo.neighbours(left, nb, kMaxNeighbours) > 2)
    {
      this->Junction = {};
      this->Junction.point = left;
      this->Junction.entry = entry;
      this->Junction.taken = toward;
    }
  }
  if (toT >= 1.0 && fromT < 1.0)
  {
    this->ArrivedAt = b;
    this->ArrivedFrom = a;
  }
  else if (toT <= 0.0 && fromT > 0.0)
  {
    this->ArrivedAt = a;
    this->ArrivedFrom = b;
  }
  return std::fabs(toT - fromT) * (vm.screen_px(b) - vm.screen_px(a)).norm();
}

Tracer::ChainFit Tracer::fitChain(const ViewModel& vm,
  int point,
  int first,
  double window_px,
  int* out,
  int cap) const
{
  const SceneTopology& topo = vm.topology();
  ChainFit fit;
  out[0] = point;
  out[1] = first;
  fit.count = 2;
  int nb[kMaxNeighbours];
  const AgentLocation& loc = this->Location;
  for (int i = 0; i + 1 < fit.count; ++i)
  {
    const int p = out[i];
    const int q = out[i + 1];
    const double len = (vm.screen_px(q) - vm.screen_px(p)).norm();
    // The agent on this segment (at a point counts as the end of the segment reaching it).
    if (fit.agentSegment < 0)
    {
      if (loc.t > 0.0 && loc.to >= 0 &&
          ((loc.from == p && loc.to == q) || (loc.from == q && loc.to == p)))
      {
        fit.agentSegment = i;
        fit.agentFraction = loc.from == p ? loc.t : 1.0 - loc.t;
      }
      else if (!(loc.t > 0.0) && loc.from == q)
      {
        fit.agentSegment = i;
        fit.agentFraction = 1.0;
      }
      if (fit.agentSegment == i)
      {
        fit.agentArc_px = fit.arc_px + fit.agentFraction * len;
      }
    }
    fit.arc_px += len;
    if (fit.arc_px > window_px || fit.count >= cap)
    {
      break;
    }
    // On through q: straight along its path, or its one other neighbour; stop at a junction.
    const int count = topo.neighbours(q, nb, kMaxNeighbours);
    const int straight = q + (q - p);
    int next = -1;
    int others = 0;
    for (int k = 0; k < count; ++k)
    {
      if (nb[k] == p)
      {
        continue;
      }
      ++others;
      if (nb[k] == straight && topo.pathOf(nb[k]) == topo.pathOf(q))
      {
        next = nb[k];
      }
    }
    if (next < 0 && others == 1)
    {
      for (int k = 0; k < count; ++k)
      {
        next = nb[k] != p ? nb[k] : next;
      }
    }
    if (next < 0 || next == point)
    {
      break;
    }
    out[fit.count++] = next;
  }
  return fit;
}

void Tracer::chainAt(const ViewModel& vm,
  const int* chain,
  int count,
  double arc_px,
  int* segment,
  double* fraction)
{
  double arc = 0.0;
  for (int i = 0; i + 1 < count; ++i)
  {
    const double len = (vm.screen_px(chain[i + 1]) - vm.screen_px(chain[i])).norm();
    if (arc + len >= arc_px && len > kZeroLength_px)
    {
      *segment = i;
      *fraction = std::clamp((arc_px - arc) / len, 0.0, 1.0);
      return;
    }
    arc += len;
  }
  *segment = std::max(0, count - 2);
  *fraction = 1.0;
}

double Tracer::reconsiderJunction(const ViewModel& vm, const Vec2& cursor_px)
{
  if (this->State != InteractionState::Tracing || this->Junction.point < 0 ||
      !(this->junctionWindow_px > 0.0) || !cursor_px.isFinite())
  {
    return 0.0;
  }
  if (!this->Junction.hasCursor)
  {
    // The tick the agent passed the junction: the hand's movement is measured from here.
    this->Junction.hasCursor = true;
    this->Junction.cursor_px = cursor_px;
    return 0.0;
  }
  const JunctionChoice j = this->Junction;
  constexpr int kChain = 256;
  int taken[kChain];
  int best[kChain];
  int scratch[kChain];
  const ChainFit onTaken =
    this->fitChain(vm, j.point, j.taken, this->junctionWindow_px, taken, kChain);
  if (onTaken.agentSegment < 0 || onTaken.agentArc_px > this->junctionWindow_px)
  {
    this->Junction = {}; // the agent left the branch it took, or is past the window
    return 0.0;
  }
  const Vec2 moved = cursor_px - j.cursor_px;
  const double reach = moved.norm();
  if (!(reach > this->junctionMargin_px))
  {
    return 0.0; // not enough movement to tell the candidates apart
  }
  // Yi & Hayward §3.2.1 on the movement since the junction: its projection on each candidate's
  // direction (the chord from the junction to where the movement reaches along it), compared by
  // the perpendicular residual (the same order as the projections: one vector is projected).
  const Vec2 junction = vm.screen_px(j.point);
  auto residual = [&vm, &moved, &junction, reach](const int* chain, int count)
  {
    int segment = 0;
    double fraction = 0.0;
    chainAt(vm, chain, count, reach, &segment, &fraction);
    const Vec2 at =
      vm.screen_px(chain[segment]) * (1.0 - fraction) + vm.screen_px(chain[segment + 1]) * fraction;
    const Vec2 chord = at - junction;
    const double n = chord.norm();
    if (!(n > kZeroLength_px))
    {
      return std::numeric_limits<double>::infinity();
    }
    const double along = moved.dot(chord) / n;
    return along > 0.0 ? std::sqrt(std::max(0.0, reach * reach - along * along)) : reach - along;
  };
  const double takenResidual = residual(taken, onTaken.count);
  int nb[kMaxNeighbours];
  const int count = vm.topology().neighbours(j.point, nb, kMaxNeighbours);
  double bestResidual = takenResidual - this->junctionMargin_px;
  int bestFirst = -1;
  int bestCount = 0;
  for (int i = 0; i < count; ++i)
  {
    if (nb[i] == j.entry || nb[i] == j.taken)
    {
      continue;
    }
    const ChainFit fit =
      this->fitChain(vm, j.point, nb[i], this->junctionWindow_px, scratch, kChain);
    const double r = residual(scratch, fit.count);
    if (r < bestResidual)
    {
      bestResidual = r;
      bestFirst = nb[i];
      bestCount = fit.count;
      std::copy(scratch, scratch + fit.count, best);
    }
  }
  if (bestFirst < 0)
  {
    return 0.0;
  }
  // Back along the branch taken to the junction, then on along the winner as far from the
  // junction as the agent was (the torsion, arc and direction bookkeeping of advance()).
  double travelled = this->advance(
    vm, taken[onTaken.agentSegment], taken[onTaken.agentSegment + 1], onTaken.agentFraction, 0.0);
  for (int i = onTaken.agentSegment - 1; i >= 0; --i)
  {
    travelled += this->advance(vm, taken[i], taken[i + 1], 1.0, 0.0);
  }
  int segment = 0;
  double fraction = 0.0;
  chainAt(vm, best, bestCount, onTaken.agentArc_px, &segment, &fraction);
  for (int i = 0; i < segment; ++i)
  {
    travelled += this->advance(vm, best[i], best[i + 1], 0.0, 1.0);
  }
  const int a = best[segment];
  const int b = best[segment + 1];
  if (fraction > 0.0)
  {
    travelled += this->advance(vm, a, b, 0.0, fraction);
  }
  this->Location = fraction >= 1.0 ? AgentLocation{ b, a, 0.0 }
                   : fraction > 0.0
                     ? AgentLocation{ a, b, fraction }
                     : AgentLocation{ a, segment > 0 ? best[segment - 1] : j.entry, 0.0 };
  this->Junction = j; // the advance() calls above passed the junction again: keep its record
  this->Junction.taken = bestFirst;
  return travelled;
}

bool Tracer::foldAhead(const ViewModel& vm,
  const Vec2& cursor_px,
  const Vec2& here_px,
  double reverseProj_px,
  int* pointOut,
  int* behindOut) const
{
  const AgentLocation& loc = this->Location;
  if (this->Direction == 0 || !(this->foldLookAhead_px > 0.0) || loc.to < 0)
  {
    return false;
  }
  // Start at the end ahead in the direction of travel (advance() signs Direction by index order).
  int cur = loc.from;
  int prev = loc.to;
  if (loc.t > 0.0)
  {
    const bool headingToTo = this->Direction == ((loc.to > loc.from) ? 1 : -1);
    cur = headingToTo ? loc.to : loc.from;
    prev = headingToTo ? loc.from : loc.to;
  }
  else
  {
    // At a point loc.to is the neighbour behind: step to the single one ahead.
    int nb[kMaxNeighbours];
    const int count = vm.topology().neighbours(cur, nb, kMaxNeighbours);
    int next = -1;
    for (int i = 0; i < count; ++i)
    {
      if (nb[i] != prev)
      {
        if (next >= 0)
        {
          return false; // a junction: the branch choice is the projection rule's business
        }
        next = nb[i];
      }
    }
    if (next < 0)
    {
      return false;
    }
    prev = cur;
    cur = next;
  }
  // What reversing would achieve: the cursor's distance to the line back along the path.
  const double rNorm = (cursor_px - here_px).norm();
  const double residual = std::sqrt(std::max(0.0, rNorm * rNorm - reverseProj_px * reverseProj_px));
  const double good = residual + this->deadBand_px + this->directionHysteresis * rNorm;
  double arc = (vm.screen_px(cur) - here_px).norm();
  int nb[kMaxNeighbours];
  for (int k = 0; k < kLookAhead && arc <= this->foldLookAhead_px; ++k)
  {
    // A point ahead, within the look-ahead, that the cursor is about as close to as reversing
    // would bring it: the path folds back in screen space and continuing is as good.
    const double d = (cursor_px - vm.screen_px(cur)).norm();
    if (d <= good && d < rNorm) // and strictly closer than now: never on a straight reversal
    {
      *pointOut = cur;
      *behindOut = prev;
      return true;
    }
    const int count = vm.topology().neighbours(cur, nb, kMaxNeighbours);
    int next = -1;
    for (int i = 0; i < count; ++i)
    {
      if (nb[i] != prev)
      {
        if (next >= 0)
        {
          return false;
        }
        next = nb[i];
      }
    }
    if (next < 0)
    {
      return false;
    }
    arc += (vm.screen_px(next) - vm.screen_px(cur)).norm();
    prev = cur;
    cur = next;
  }
  return false;
}

double Tracer::crossFold(const ViewModel& vm, int point, int behind)
{
  // Walk from the agent to `point` along the chain (the fold search saw no junction), keeping the
  // torsion and direction bookkeeping of advance().
  AgentLocation& loc = this->Location;
  double travelled = 0.0;
  int cur = loc.from;
  int prev = loc.to;
  if (loc.t > 0.0)
  {
    const bool headingToTo = this->Direction == ((loc.to > loc.from) ? 1 : -1);
    travelled += headingToTo ? this->advance(vm, loc.from, loc.to, loc.t, 1.0)
                             : this->advance(vm, loc.from, loc.to, loc.t, 0.0);
    cur = headingToTo ? loc.to : loc.from;
    prev = headingToTo ? loc.from : loc.to;
  }
  int nb[kMaxNeighbours];
  for (int k = 0; k < kLookAhead && cur != point; ++k)
  {
    const int count = vm.topology().neighbours(cur, nb, kMaxNeighbours);
    int next = -1;
    for (int i = 0; i < count && next < 0; ++i)
    {
      if (nb[i] != prev)
      {
        next = nb[i];
      }
    }
    if (next < 0)
    {
      break;
    }
    travelled += this->advance(vm, cur, next, 0.0, 1.0);
    prev = cur;
    cur = next;
  }
  loc = { cur, cur == point ? behind : prev, 0.0 };
  return travelled;
}

double Tracer::follow(const ViewModel& vm, const Vec2& cursor_px)
{
  if (this->State != InteractionState::Tracing || !this->Location.valid() || !cursor_px.isFinite())
  {
    return 0.0;
  }
  const SceneTopology& topo = vm.topology();
  double travelled = 0.0;
  int nb[kMaxNeighbours];
  AgentLocation& loc = this->Location;
  // The agent keeps `keep` behind the cursor's projection: a hysteresis (no stick-slip steps once
  // moving), and with trail_px the drag threshold of Ikits' eq. 8.
  const double keep = std::max(this->deadBand_px, this->trail_px);
  bool folded = false; // at most one fold crossing per tick
  for (int step = 0; step < this->maxStepsPerTick; ++step)
  {
    const Vec2 here = loc.t > 0.0 && loc.to >= 0
                        ? vm.screen_px(loc.from) * (1.0 - loc.t) + vm.screen_px(loc.to) * loc.t
                        : vm.screen_px(loc.from);
    const Vec2 r = cursor_px - here;
    if (loc.t > 0.0)
    {
      // Inside an edge: the candidates are its two ends.
      const Vec2 pa = vm.screen_px(loc.from);
      const Vec2 pb = vm.screen_px(loc.to);
      const double len = (pb - pa).norm();
      const Vec2 u = unit(pb - pa);
      const double proj = r.dot(u);
      const double want = std::fabs(proj) - keep;
      if (std::fabs(proj) <= this->deadBand_px || want <= 0.0 || len <= kZeroLength_px)
      {
        // The agent trails the cursor by the dead band: when that leaves it just short of a
        // junction the hand is turning at (the cursor is off the edge, beyond the junction's
        // end of it), finish the edge so the branches become candidates at the next step.
        const int end = proj > 0.0 ? loc.to : loc.from;
        const double left = (proj > 0.0 ? 1.0 - loc.t : loc.t) * len;
        if (len > kZeroLength_px && proj != 0.0 && left <= keep + kZeroLength_px &&
            topo.neighbours(end, nb, kMaxNeighbours) > 2 && (r - u * proj).norm() > keep)
        {
          const double tEnd = proj > 0.0 ? 1.0 : 0.0;
          travelled += this->advance(vm, loc.from, loc.to, loc.t, tEnd);
          loc = proj > 0.0 ? AgentLocation{ loc.to, loc.from, 0.0 }
                           : AgentLocation{ loc.from, loc.to, 0.0 };
          continue;
        }
        break;
      }
      const double t0 = loc.t;
      const int towardTo = (loc.to > loc.from) ? 1 : -1;
      const bool reversing =
        this->Direction != 0 && ((proj > 0.0) != (this->Direction == towardTo));
      int foldPoint = -1;
      int foldBehind = -1;
      if (reversing && !folded &&
          this->foldAhead(vm, cursor_px, here, std::fabs(proj), &foldPoint, &foldBehind))
      {
        // Hysteresis at a screen-space fold (projection cusp): the path just ahead turns back
        // toward the cursor, so keep the direction of travel and cross the fold.
        travelled += this->crossFold(vm, foldPoint, foldBehind);
        folded = true;
        continue;
      }
      if (proj > 0.0)
      {
        const double tNew = t0 + want / len;
        if (tNew >= 1.0)
        {
          travelled += this->advance(vm, loc.from, loc.to, t0, 1.0);
          loc = { loc.to, loc.from, 0.0 };
          continue;
        }
        travelled += this->advance(vm, loc.from, loc.to, t0, tNew);
        loc.t = tNew;
      }
      else
      {
        const double tNew = t0 - want / len;
        if (tNew <= 0.0)
        {
          travelled += this->advance(vm, loc.from, loc.to, t0, 0.0);
          loc = { loc.from, loc.to, 0.0 };
          continue;
        }
        travelled += this->advance(vm, loc.from, loc.to, t0, tNew);
        loc.t = tNew;
      }
      break;
    }
    // At a point: candidates are all graph neighbours (lower/higher index, joining branches).
    const int count = topo.neighbours(loc.from, nb, kMaxNeighbours);
    int best = -1;
    double bestProj = this->deadBand_px;
    // The neighbour behind the direction of travel (loc.to holds it at a point, see below).
    const int behind = this->Direction != 0 ? loc.to : -1;
    int forward = -1;
    double forwardProj = this->deadBand_px;
    for (int i = 0; i < count; ++i)
    {
      const double proj = r.dot(this->directionTo(vm, loc.from, nb[i]));
      if (proj > bestProj)
      {
        bestProj = proj;
        best = nb[i];
      }
      if (nb[i] != behind && proj > forwardProj)
      {
        forwardProj = proj;
        forward = nb[i];
      }
    }
    // Hysteresis at projection cusps: when going back beats going on by only a sliver of
    // |r| (the two screen directions nearly coincide), keep the direction of travel; when the
    // path ahead folds back toward the cursor within the look-ahead, cross the fold.
    if (best >= 0 && best == behind)
    {
      int foldPoint = -1;
      int foldBehind = -1;
      if (forward >= 0 && bestProj - forwardProj <= this->directionHysteresis * r.norm())
      {
        best = forward;
        bestProj = forwardProj;
      }
      else if (!folded && this->foldAhead(vm, cursor_px, here, bestProj, &foldPoint, &foldBehind))
      {
        travelled += this->crossFold(vm, foldPoint, foldBehind);
        folded = true;
        continue;
      }
    }
    const double want = bestProj - keep;
    if (best < 0 || want <= 0.0)
    {
      break; // below the threshold, or at a path end with the cursor beyond it
    }
    const double len = (vm.screen_px(best) - vm.screen_px(loc.from)).norm();
    if (len <= kZeroLength_px || want >= len)
    {
      travelled += this->advance(vm, loc.from, best, 0.0, 1.0);
      loc = { best, loc.from, 0.0 };
      continue;
    }
    travelled += this->advance(vm, loc.from, best, 0.0, want / len);
    loc = { loc.from, best, want / len };
    break;
  }
  return travelled;
}

double Tracer::followMovement(const ViewModel& vm, const Vec2& movement_px)
{
  if (this->State != InteractionState::Tracing || !this->Location.valid() ||
      !movement_px.isFinite())
  {
    return 0.0;
  }
  const SceneTopology& topo = vm.topology();
  AgentLocation& loc = this->Location;
  int nb[kMaxNeighbours];
  // Candidate directions at the agent: inside an edge its two ends, at a point every neighbour.
  int best = -1;
  double bestProj = -1.0;
  if (loc.t > 0.0 && loc.to >= 0)
  {
    const Vec2 u = unit(vm.screen_px(loc.to) - vm.screen_px(loc.from));
    const double proj = movement_px.dot(u);
    best = proj >= 0.0 ? loc.to : loc.from;
    bestProj = std::fabs(proj);
  }
  else
  {
    const int count = topo.neighbours(loc.from, nb, kMaxNeighbours);
    for (int i = 0; i < count; ++i)
    {
      const double proj = movement_px.dot(this->directionTo(vm, loc.from, nb[i]));
      if (proj > bestProj)
      {
        bestProj = proj;
        best = nb[i];
      }
    }
  }
  if (best < 0 || !(bestProj >= this->movementThreshold_px) || bestProj <= 0.0)
  {
    return 0.0; // §3.2.1: "below a threshold, the agent remains stationary"
  }
  // Travel the subtended screen arc length, iterating over points.
  double remaining = bestProj;
  double travelled = 0.0;
  const Vec2 heading = unit(movement_px);
  for (int step = 0; step < this->maxStepsPerTick && remaining > 0.0; ++step)
  {
    int a = loc.from;
    double t0 = 0.0;
    int b = best;
    if (loc.t > 0.0 && loc.to >= 0)
    {
      // Inside an edge: toward `best` (one of its ends).
      a = loc.from;
      b = loc.to;
      t0 = loc.t;
      if (best == loc.from)
      {
        std::swap(a, b);
        t0 = 1.0 - loc.t;
      }
    }
    const double len = (vm.screen_px(b) - vm.screen_px(a)).norm();
    const double left = (1.0 - t0) * len;
    if (len <= kZeroLength_px || remaining >= left)
    {
      travelled += this->advance(vm, a, b, t0, 1.0);
      remaining -= std::max(0.0, left);
      const int came = a;
      loc = { b, a, 0.0 };
      // Go on along the neighbour best aligned with the movement, never straight back.
      const int count = topo.neighbours(b, nb, kMaxNeighbours);
      best = -1;
      double bestDot = -2.0;
      for (int i = 0; i < count; ++i)
      {
        if (nb[i] == came)
        {
          continue;
        }
        const double d = heading.dot(this->directionTo(vm, b, nb[i]));
        if (d > bestDot)
        {
          bestDot = d;
          best = nb[i];
        }
      }
      if (best < 0)
      {
        break; // a path end
      }
      continue;
    }
    const double t1 = t0 + remaining / len;
    travelled += this->advance(vm, a, b, t0, t1);
    loc =
      (a == loc.from || loc.t == 0.0) ? AgentLocation{ a, b, t1 } : AgentLocation{ b, a, 1.0 - t1 };
    remaining = 0.0;
  }
  return travelled;
}

AgentLocation Tracer::locationToward(const ViewModel& vm,
  const Vec2& cursor_px,
  double reach_px,
  double* arcOffset_mm) const
{
  const AgentLocation& loc = this->Location;
  double arc = 0.0;
  const SceneTopology& topo = vm.topology();
  // Signed 3D arc of a move on edge a -> b from fraction t0 to t1 (advance()'s convention).
  auto along = [&topo, &arc](int a, int b, double t0, double t1)
  {
    const double len3 = (topo.position_World_mm(b) - topo.position_World_mm(a)).norm();
    arc += (t1 - t0) * len3 * (b > a ? 1.0 : -1.0);
  };
  if (arcOffset_mm)
  {
    *arcOffset_mm = 0.0;
  }
  if (!loc.valid() || !cursor_px.isFinite() || !(reach_px > 0.0))
  {
    return loc;
  }
  int nb[kMaxNeighbours];
  // The edge a -> b the location moves along, from fraction t, and the cursor's projection on it.
  int a = loc.from;
  int b = -1;
  double t = 0.0;
  double proj = 0.0;
  if (loc.t > 0.0 && loc.to >= 0)
  {
    const Vec2 here = vm.screen_px(loc.from) * (1.0 - loc.t) + vm.screen_px(loc.to) * loc.t;
    proj = (cursor_px - here).dot(this->directionTo(vm, loc.from, loc.to));
    a = proj >= 0.0 ? loc.from : loc.to;
    b = proj >= 0.0 ? loc.to : loc.from;
    t = proj >= 0.0 ? loc.t : 1.0 - loc.t;
    proj = std::fabs(proj);
  }
  else
  {
    // At a point: toward the neighbour of largest projection (the tracer's candidates).
    const Vec2 r = cursor_px - vm.screen_px(loc.from);
    const int count = topo.neighbours(loc.from, nb, kMaxNeighbours);
    for (int i = 0; i < count; ++i)
    {
      const double p = r.dot(this->directionTo(vm, loc.from, nb[i]));
      if (p > proj)
      {
        proj = p;
        b = nb[i];
      }
    }
  }
  double remaining = std::min(proj, reach_px);
  if (b < 0 || !(remaining > 0.0))
  {
    return loc;
  }
  // The walk stops before a point whose eta (the stencil's projected tangent, smooth along the
  // vessel) has turned by more than 5 degrees from the agent's: at a projection cusp (Yi &
  // Hayward §4.2, Fig. 4) eta turns by up to 180 degrees within a fraction of a pixel, and a
  // reading that followed a dithering cursor into the turn would swing the force back and forth
  // while the agent (with its fold hysteresis) stays. On a smooth screen path the dead band's
  // reach never turns that much.
  const Vec2 eta0 = vm.eta(loc.from);
  for (int step = 0; step < kLookAhead; ++step)
  {
    const double len = (vm.screen_px(b) - vm.screen_px(a)).norm();
    if (std::fabs(vm.eta(b).dot(eta0)) < kLeadTurnCos)
    {
      if (arcOffset_mm)
      {
        *arcOffset_mm = arc;
      }
      return { a, b, t };
    }
    const double left = (1.0 - t) * len;
    if (len > kZeroLength_px && left > remaining)
    {
      along(a, b, t, t + remaining / len);
      if (arcOffset_mm)
      {
        *arcOffset_mm = arc;
      }
      return { a, b, t + remaining / len };
    }
    along(a, b, t, 1.0);
    remaining -= left;
    // On through b along its path (straight on), or its one other neighbour; stop at a junction
    // or a path end.
    const int count = topo.neighbours(b, nb, kMaxNeighbours);
    const int straight = b + (b - a);
    int next = -1;
    int others = 0;
    for (int i = 0; i < count; ++i)
    {
      if (nb[i] == a)
      {
        continue;
      }
      ++others;
      if (nb[i] == straight && topo.pathOf(nb[i]) == topo.pathOf(b))
      {
        next = nb[i];
      }
    }
    if (next < 0 && others == 1)
    {
      for (int i = 0; i < count; ++i)
      {
        next = nb[i] != a ? nb[i] : next;
      }
    }
    if (next < 0 || !(remaining > 0.0))
    {
      if (arcOffset_mm)
      {
        *arcOffset_mm = arc;
      }
      return { b, a, 0.0 };
    }
    a = b;
    b = next;
    t = 0.0;
  }
  if (arcOffset_mm)
  {
    *arcOffset_mm = arc;
  }
  return { a, b, t };
}

AgentSample Tracer::sample(const ViewModel& vm) const
{
  return sampleAt(vm, this->Location);
}

AgentSample Tracer::sampleAt(const ViewModel& vm, const AgentLocation& loc)
{
  AgentSample s;
  const SceneTopology& topo = vm.topology();
  const int a = loc.from;
  const bool onEdge = loc.t > 0.0 && loc.to >= 0;
  const int b = onEdge ? loc.to : a;
  const double t = onEdge ? loc.t : 0.0;
  const double wa = 1.0 - t;
  s.point = t < 0.5 ? a : b;
  s.screen_px = vm.screen_px(a) * wa + vm.screen_px(b) * t;
  s.position_World_mm = topo.position_World_mm(a) * wa + topo.position_World_mm(b) * t;
  s.tangent_World = topo.tangent_World(s.point);
  // Eta points toward increasing index within each path; across a junction edge the two ends may
  // disagree, so align b's with a's before blending.
  Vec2 eb = vm.eta(b);
  const Vec2 ea = vm.eta(a);
  double zb = vm.dz_mm(b);
  if (ea.dot(eb) < 0.0)
  {
    eb = eb * -1.0;
    zb = -zb;
  }
  const Vec2 e = ea * wa + eb * t;
  const double en = e.norm();
  s.eta = en > 1e-12 ? e * (1.0 / en) : (t < 0.5 ? ea : eb);
  s.dz_mm = vm.dz_mm(a) * wa + zb * t;
  s.dl_mm = vm.dl_mm(a) * wa + vm.dl_mm(b) * t;
  s.frameStrength = vm.frameStrength(a) * wa + vm.frameStrength(b) * t;
  s.mmPerPixel = vm.mmPerPixel(s.point);
  s.torsion_per_mm = topo.torsion_per_mm(s.point);
  return s;
}

} // namespace vtouch

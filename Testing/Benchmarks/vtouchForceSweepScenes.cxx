#include "vtouchForceSweepScenes.h"

#include "vtouchHapticPipeline.h"
#include "vtouchHapticsTestUtilities.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <iterator>
#include <utility>
#include <vector>

namespace vtouch
{
namespace bench
{
using namespace vtouch::testing;

namespace
{
struct TracerMeasure
{
  double meanError_px = 0.0;
  double maxError_px = 0.0;
  double maxForceStep_N = 0.0;
  double reached = 0.0;
  int lastPath = -1;
};

/// The cursor visits the screen position of every point of `route` (global indices), one per
/// tick, plus a seeded dither of `dither_px` (uniform, per axis, not accumulated).
TracerMeasure traceRoute(const ViewModel& vm,
  const std::vector<int>& route,
  int rule,
  double dither_px,
  unsigned seed,
  double junctionWindow_px = HapticParameters{}.tracerJunctionWindow_px)
{
  HapticPipeline pipeline;
  HapticParameters p = immediateContact();
  p.tracerRule = rule;
  p.tracerJunctionWindow_px = junctionWindow_px;
  DeviceCapabilities caps;
  caps.maxContinuousForce_N = 3.0; // the simulated stylus's range (lambda is sized from it)
  TickInput in;
  in.capabilities = &caps;
  in.view = &vm;
  in.device.pressure = 1.0;
  std::uint64_t state = seed * 2654435761ull + 1;
  auto uniform = [&state]()
  {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return static_cast<double>(state >> 11) / 9007199254740992.0 * 2.0 - 1.0;
  };
  const Vec2 start = vm.screen_px(route.front());
  pipeline.setCursor_px(start);
  Vec2 previousTarget = start;
  TracerMeasure m;
  Vec2 previousForce;
  int n = 0;
  int furthest = 0;
  for (std::size_t k = 0; k < route.size(); ++k)
  {
    const Vec2 target = vm.screen_px(route[k]) + Vec2{ uniform(), uniform() } * dither_px;
    const Vec2 d = target - previousTarget;
    previousTarget = target;
    in.device.position_Device_mm.x += d.x / 4.0; // 4 px per hand mm at zoom 1
    in.device.position_Device_mm.y += d.y / 4.0;
    const AgentState st = pipeline.step(in, p);
    if (st.state != InteractionState::Tracing)
    {
      continue;
    }
    const double error = (st.agentScreen_px - vm.screen_px(route[k])).norm();
    m.meanError_px += error;
    m.maxError_px = std::max(m.maxError_px, error);
    if (n > 0)
    {
      m.maxForceStep_N = std::max(m.maxForceStep_N, (st.targetForce_N - previousForce).norm());
    }
    previousForce = st.targetForce_N;
    ++n;
    const int g = vm.topology().pathBegin(st.path) + st.point;
    const auto it = std::find(route.begin(), route.end(), g);
    if (it != route.end())
    {
      furthest = std::max(furthest, static_cast<int>(it - route.begin()));
    }
    m.lastPath = st.path;
  }
  m.meanError_px = n ? m.meanError_px / n : std::nan("");
  m.reached = static_cast<double>(furthest) / static_cast<double>(route.size() - 1);
  return m;
}

/// A parent vessel along +x and a branch leaving its middle at `angle_deg` in the screen plane.
QSkeleton branchScene(double angle_deg)
{
  QSkeleton s = straightLine({ -20, 0, 0 }, { 20, 0, 0 }, 0.25);
  const double a = angle_deg * kPi / 180.0;
  QSkeleton branch = straightLine({ 0, 0, 0 }, { 20 * std::cos(a), 20 * std::sin(a), 0 }, 0.25);
  branch.paths[0].id = 1;
  s.paths.push_back(branch.paths[0]);
  join(s, 1, Junction::End::Head, 0, 80);
  return s;
}

/// Hayward & Yi eq. 4 on three patches (a trough).
double surfaceHeight(double x, double y)
{
  const double omega = 2.0 * kPi * 100.0 / 60.0; // ~100 oscillations over the 60 mm line
  const double slope = x < -10.0 ? -std::tan(0.4) : (x > 10.0 ? std::tan(0.7) : 0.0);
  const double base = x < -10.0 ? slope * (x + 10.0) : (x > 10.0 ? slope * (x - 10.0) : 0.0);
  return base + 1.0 * std::sin(omega * x) * y;
}

} // namespace

void printSurfaceStimulus()
{
  QSkeleton s;
  for (int j = -12; j <= 12; ++j)
  {
    const double y = 0.25 * j; // 1 px apart at 0.25 mm/px
    SkeletonPath path;
    for (int i = 0; i <= 2400; ++i)
    {
      const double x = -30.0 + 60.0 * i / 2400.0;
      SkeletonPoint q;
      q.position_World_mm = { x, y, surfaceHeight(x, y) }; // world +z is toward the viewer
      const Vec3 d{ 0.025, 0.0, surfaceHeight(x + 0.0125, y) - surfaceHeight(x - 0.0125, y) };
      q.tangent_World = d * (1.0 / d.norm());
      path.points.push_back(q);
    }
    path.id = static_cast<int>(s.paths.size());
    s.paths.push_back(path);
  }
  const auto view = buildView(s, topCamera({ 0, 0, 0 }, 0.25), 12.0);
  const int centre = view->topology().pathBegin(12); // y = 0
  std::vector<double> xs;
  std::vector<double> fx[2];
  std::vector<double> fy[2];
  const ForceLawId laws[2] = { ForceLawId::ChangeOfHeight, ForceLawId::LateralGradient };
  const char* keys[2] = { "change_of_height", "lateral_gradient" };
  for (int l = 0; l < 2; ++l)
  {
    HapticPipeline pipeline;
    HapticParameters p = immediateContact();
    p.forceLaw = laws[l];
    p.slopeForceBudget = 0.0; // the paper's k with a 5 N device: no lambda sizing here
    p.maxForceRate_N_per_s = 1e9;
    p.lateralProbe_px = 1.0;
    DeviceCapabilities caps;
    TickInput in;
    in.capabilities = &caps;
    in.view = view.get();
    in.device.pressure = 1.0;
    pipeline.setCursor_px(view->screen_px(centre + 100));
    double sum[3] = { 0, 0, 0 };
    int count[3] = { 0, 0, 0 };
    double fy2 = 0.0;
    int n = 0;
    for (int k = 0; k < 2500; ++k) // 20 mm/s = 0.08 px per tick, 50 mm
    {
      in.device.position_Device_mm.x += 0.02;
      const AgentState st = pipeline.step(in, p);
      if (st.state != InteractionState::Tracing || k < 50)
      {
        continue;
      }
      const double x = st.position_World_mm.x;
      const int patch = x < -10.5 ? 0 : (x > 10.5 ? 2 : (std::fabs(x) < 9.5 ? 1 : -1));
      if (patch >= 0)
      {
        sum[patch] += st.targetForce_N.x;
        ++count[patch];
      }
      fy2 += st.targetForce_N.y * st.targetForce_N.y;
      ++n;
      if (k % 5 == 0)
      {
        if (l == 0)
        {
          xs.push_back(x);
        }
        fx[l].push_back(st.targetForce_N.x);
        fy[l].push_back(st.targetForce_N.y);
      }
    }
    for (int i = 0; i < 3; ++i)
    {
      std::printf(",\n  \"surface.%s.patch%d.mean_fx_n\": %.6g",
        keys[l],
        i,
        count[i] ? sum[i] / count[i] : std::nan(""));
    }
    std::printf(
      ",\n  \"surface.%s.rms_fy_n\": %.6g", keys[l], n ? std::sqrt(fy2 / n) : std::nan(""));
  }
  auto list = [](const char* key, const std::vector<double>& v)
  {
    std::printf(",\n  \"surface.trace.%s\": [", key);
    for (std::size_t i = 0; i < v.size(); ++i)
    {
      std::printf("%s%.5g", i ? ", " : "", v[i]);
    }
    std::printf("]");
  };
  list("x_mm", xs);
  list("change_of_height_fx_n", fx[0]);
  list("change_of_height_fy_n", fy[0]);
  list("lateral_gradient_fx_n", fx[1]);
  list("lateral_gradient_fy_n", fy[1]);
}

void printTracerComparison()
{
  for (int rule : { 0, 1 })
  {
    const char* key = rule == 0 ? "offset" : "movement";
    // The spiral of the force sweep seen 3 degrees off edge-on: projection cusps, and the
    // helix seen from the side.
    const double tilt = 3.0 * kPi / 180.0;
    const QSkeleton spiral = singlePath(
      [tilt](double u)
      {
        const double t = 4 * kPi * u;
        const double r = 8 + 3 * t;
        return Vec3{
          r * std::cos(t), r * std::sin(t) * std::sin(tilt), r * std::sin(t) * std::cos(tilt)
        };
      },
      2400);
    const QSkeleton helix = singlePath(
      [](double u)
      {
        const double t = 6 * kPi * u;
        return Vec3{ 10 * std::cos(t), 10 * std::sin(t), 3 * t };
      },
      2400);
    const auto spiralView = buildView(spiral, topCamera({ 0, 0, 0 }, 0.1), 12.0);
    const auto helixView = buildView(
      helix, makeOrthographicCamera({ 0, 0, 9 * kPi }, { 0, 1, 0 }, { 0, 0, 1 }, 75.0, 800, 600));
    std::vector<int> all(2400);
    for (int g = 0; g < 2400; ++g)
    {
      all[g] = g;
    }
    const std::pair<const char*, const ViewModel*> scenes[] = { { "spiral", spiralView.get() },
      { "helix", helixView.get() } };
    for (const auto& [name, view] : scenes)
    {
      const TracerMeasure m = traceRoute(*view, all, rule, 0.3, 1);
      std::printf(",\n  \"tracer.%s.%s.mean_error_px\": %.6g", key, name, m.meanError_px);
      std::printf(",\n  \"tracer.%s.%s.max_error_px\": %.6g", key, name, m.maxError_px);
      std::printf(",\n  \"tracer.%s.%s.max_force_step_n\": %.6g", key, name, m.maxForceStep_N);
      std::printf(",\n  \"tracer.%s.%s.reached_fraction\": %.6g", key, name, m.reached);
    }
    // Branch choices against the branch's angle: the hand comes along the parent to the junction
    // and then follows the branch (it should be taken) or goes on along the parent (it should
    // not), five dither seeds each; with the junction re-decision (default) and without it (the
    // choice made at the junction is final).
    const double angles[] = { 10.0, 20.0, 30.0, 45.0, 60.0, 90.0 };
    const unsigned seeds[] = { 1u, 2u, 3u, 4u, 5u };
    int correct = 0;
    int runs = 0;
    std::printf(",\n  \"tracer.%s.branch.angles_deg\": [10, 20, 30, 45, 60, 90]", key);
    for (const bool reconsider : { true, false })
    {
      const char* variant = reconsider ? "branch" : "branch_at_junction";
      for (double angle : angles)
      {
        const auto view = buildView(branchScene(angle), topCamera({ 0, 0, 0 }, 0.25));
        std::vector<int> toBranch;
        std::vector<int> onParent;
        for (int g = 20; g <= 80; ++g) // along the parent to the junction
        {
          toBranch.push_back(g);
          onParent.push_back(g);
        }
        const int branchBegin = view->topology().pathBegin(1);
        const int branchEnd = view->topology().pathEnd(1);
        for (int g = branchBegin + 1; g < branchEnd; ++g) // then along the branch
        {
          toBranch.push_back(g);
        }
        for (int g = 81; g <= 140; ++g) // or on along the parent
        {
          onParent.push_back(g);
        }
        int taken = 0;
        int kept = 0;
        for (unsigned seed : seeds)
        {
          const double window = reconsider ? HapticParameters{}.tracerJunctionWindow_px : 0.0;
          taken += traceRoute(*view, toBranch, rule, 0.3, seed, window).lastPath == 1 ? 1 : 0;
          kept += traceRoute(*view, onParent, rule, 0.3, seed, window).lastPath == 0 ? 1 : 0;
        }
        const int n = static_cast<int>(std::size(seeds));
        std::printf(",\n  \"tracer.%s.%s.angle%d.taken\": %.6g",
          key,
          variant,
          static_cast<int>(angle),
          static_cast<double>(taken) / n);
        std::printf(",\n  \"tracer.%s.%s.angle%d.kept\": %.6g",
          key,
          variant,
          static_cast<int>(angle),
          static_cast<double>(kept) / n);
        if (reconsider)
        {
          correct += taken + kept;
          runs += 2 * n;
        }
      }
    }
    std::printf(
      ",\n  \"tracer.%s.branch.correct_fraction\": %.6g", key, static_cast<double>(correct) / runs);
  }
}

} // namespace bench
} // namespace vtouch

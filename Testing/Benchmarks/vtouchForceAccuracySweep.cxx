// vesseltouch-force-sweep: force error of each force law against the haptic loop rate, and the
// tick cost, on the helix phantom and a conical spiral, through the session's offline path (the
// same tick code as the real-time loop, a simulated handle, zero-order hold of each force).
//
//   vesseltouch-force-sweep [--seconds S] [--rates 250,500,1000,2000,4000,10000]
//                           [--reference-rate 20000] [--speed-mm-per-s 50]
//
// Prints one JSON object (flat keys, units in the names) on stdout:
//   force.<law>.<scene>.<rate>hz.rel_rms_error  RMS |F_rate(t) - F_ref(t)| / RMS |F_ref(t)|, where
//       F_rate is the force the handle feels (held between ticks) and F_ref the same run at the
//       reference rate: the error the loop rate adds (hold, interpolation lag, closed loop).
//   force.<law>.<scene>.tick_median_ns          median wall time of one session tick at 1 kHz
//   force.<law>.<scene>.tracing_fraction        fraction of the measured window spent tracing
//   force.ldgf.<scene>.max_rel_error            LDGF against the analytic k tan(beta), agent placed
//       on every point whose projected tangent keeps half its length (as the phantom test).
// A scripted hand (position drive, 1000 N/m grip) approaches the path in 0.3 s, then follows the
// projected centerline at the given speed; the first 0.5 s are not measured.
//
// It also prints the tracing-rule comparison and Hayward & Yi's surface stimulus
// (vtouchForceSweepScenes.h: keys tracer.* and surface.*).
#include "vtouchForceSweepScenes.h"
#include "vtouchHapticSession.h"
#include "vtouchHapticsTestUtilities.h"
#include "vtouchLdgfForceLaw.h"
#include "vtouchPhantomGenerator.h"
#include "vtouchSimulatedDevice.h"
#include "vtouchTracer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

using namespace vtouch;
using namespace vtouch::testing;

namespace
{
struct Scene
{
  std::string name;
  QSkeleton skeleton;
  Vec3 focal_World_mm;
};

Scene helixScene()
{
  PhantomSpec spec;
  spec.shape = PhantomShape::Helix;
  PhantomGenerator phantom(spec);
  Scene s;
  s.name = "helix";
  s.skeleton = phantom.centerline();
  const auto centre = [&spec](int a)
  { return spec.origin_mm[a] + 0.5 * (spec.dimensions[a] - 1) * spec.spacing_mm[a]; };
  s.focal_World_mm = Vec3{ centre(0), centre(1), centre(2) };
  return s;
}

/// A conical spiral: two turns whose radius grows from 8 to 32 mm while it rises 40 mm, so the
/// slope seen from above changes continuously along the path.
Scene spiralScene()
{
  Scene s;
  s.name = "spiral";
  s.skeleton = singlePath(
    [](double t)
    {
      const double a = 4 * kPi * t;
      const double r = 8.0 + 24.0 * t;
      return Vec3{ r * std::cos(a), r * std::sin(a), -20.0 + 40.0 * t };
    },
    2400);
  return s;
}

/// Screen-plane (x, y) polyline of path 0 with its cumulative arc length, mm.
struct PlanarPath
{
  std::vector<Vec2> xy;
  std::vector<double> s;
  Vec2 at(double arc) const
  {
    const auto it = std::lower_bound(s.begin(), s.end(), arc);
    if (it == s.begin())
    {
      return xy.front();
    }
    if (it == s.end())
    {
      return xy.back();
    }
    const std::size_t i = static_cast<std::size_t>(it - s.begin());
    const double u = (arc - s[i - 1]) / std::max(1e-12, s[i] - s[i - 1]);
    return xy[i - 1] + (xy[i] - xy[i - 1]) * u;
  }
};

PlanarPath planar(const Scene& scene)
{
  PlanarPath p;
  double acc = 0.0;
  for (const auto& q : scene.skeleton.paths[0].points)
  {
    const Vec2 v{ q.position_World_mm.x - scene.focal_World_mm.x,
      q.position_World_mm.y - scene.focal_World_mm.y };
    if (!p.xy.empty())
    {
      acc += (v - p.xy.back()).norm();
    }
    p.xy.push_back(v);
    p.s.push_back(acc);
  }
  return p;
}

/// Hand: from the handle's rest (0, 0) to the path at 15 % of its length in 0.3 s, then along it.
HandScript sweepHand(std::shared_ptr<const PlanarPath> path, double speed_mm_per_s)
{
  HandScript hand;
  hand.drive = HandScript::Drive::Position;
  hand.handStiffness_N_per_m = 1000.0;
  const double s0 = 0.15 * path->s.back();
  hand.trajectory = [path, speed_mm_per_s, s0](double t, HandSample& h)
  {
    h.pressure = 1.0;
    if (t < 0.3)
    {
      const Vec2 start = path->at(s0);
      h.position_Device_mm = start * (t / 0.3);
      h.velocity_Device_mm_per_s = start * (1.0 / 0.3);
      return;
    }
    const double arc = s0 + speed_mm_per_s * (t - 0.3);
    h.position_Device_mm = path->at(arc);
    const Vec2 d = path->at(arc + 0.05) - path->at(arc - 0.05);
    const double n = d.norm();
    h.velocity_Device_mm_per_s = n > 0 ? d * (speed_mm_per_s / n) : Vec2{};
  };
  return hand;
}

struct Run
{
  std::vector<double> time_s;
  std::vector<Vec2> force_N;
  std::vector<int> tracing;
  double tickMedian_ns = 0.0;
};

Run runAt(const Scene& scene,
  std::shared_ptr<const PlanarPath> path,
  ForceLawId law,
  double rate_Hz,
  double seconds,
  double speed)
{
  HapticSession session;
  session.setSkeleton(scene.skeleton);
  session.setCamera(topCamera(scene.focal_World_mm, 0.25));
  auto device = std::make_shared<SimulatedDevice>();
  device->setHandScript(sweepHand(path, speed));
  session.setDevice(device);
  ForceSafetyParameters safety;
  safety.maxTickInterval_s = 0.01; // 250 Hz ticks are 4 ms apart
  session.setSafetyParameters(safety);
  HapticParameters p;
  p.forceLaw = law;
  session.setParameters(p);
  const double dt = 1.0 / rate_Hz;
  const auto ticks = static_cast<std::size_t>(std::llround(seconds * rate_Hz));
  session.setLogCapacity(ticks + 1);
  session.setLogging(true);
  Run r;
  if (device->open() != DeviceStatus::Ok)
  {
    std::fprintf(stderr, "cannot open the simulated device\n");
    std::exit(1);
  }
  std::vector<double> cost;
  cost.reserve(ticks);
  double t = 0.0;
  for (std::size_t k = 0; k < ticks; ++k)
  {
    const auto t0 = std::chrono::steady_clock::now();
    session.tick(t, dt);
    const auto t1 = std::chrono::steady_clock::now();
    cost.push_back(std::chrono::duration<double, std::nano>(t1 - t0).count());
    device->advance(dt);
    t += dt;
  }
  for (const auto& e : session.log())
  {
    r.time_s.push_back(e.time_s);
    r.force_N.push_back(e.force_N);
    r.tracing.push_back(e.state == InteractionState::Tracing ? 1 : 0);
  }
  std::nth_element(cost.begin(), cost.begin() + cost.size() / 2, cost.end());
  r.tickMedian_ns = cost.empty() ? 0.0 : cost[cost.size() / 2];
  return r;
}

/// Zero-order-hold value of a logged force at time t.
Vec2 heldAt(const Run& r, double t)
{
  const auto it = std::upper_bound(r.time_s.begin(), r.time_s.end(), t);
  if (it == r.time_s.begin())
  {
    return Vec2{};
  }
  return r.force_N[static_cast<std::size_t>(it - r.time_s.begin()) - 1];
}

double relativeRmsError(const Run& run, const Run& ref, double from_s, double to_s)
{
  double err = 0.0;
  double norm = 0.0;
  for (double t = from_s; t < to_s; t += 2.5e-5)
  {
    const Vec2 a = heldAt(run, t);
    const Vec2 b = heldAt(ref, t);
    err += (a - b).dot(a - b);
    norm += b.dot(b);
  }
  return norm > 0 ? std::sqrt(err / norm) : std::nan("");
}

double tracingFraction(const Run& r, double from_s)
{
  int n = 0;
  int on = 0;
  for (std::size_t i = 0; i < r.time_s.size(); ++i)
  {
    if (r.time_s[i] >= from_s)
    {
      ++n;
      on += r.tracing[i];
    }
  }
  return n ? static_cast<double>(on) / n : 0.0;
}

/// Worst |F.eta / k - tan(beta)| / |tan(beta)| of the LDGF at every point away from cusps and ends
/// (|tan(beta)| > 0.05), as Testing/Logic/Haptics/vtouchPhantomAccuracyTest.cxx.
double ldgfMaxRelativeError(const Scene& scene)
{
  auto vm = buildView(scene.skeleton, topCamera(scene.focal_World_mm, 0.25));
  Tracer tracer;
  LdgfForceLaw law;
  double worst = 0.0;
  for (int g = 0; g < vm->pointCount(); ++g)
  {
    const SceneTopology& topo = vm->topology();
    const int i = topo.pointOf(g);
    const int n = topo.pathEnd(topo.pathOf(g)) - topo.pathBegin(topo.pathOf(g));
    const Vec3 tw = topo.tangent_World(g);
    const double txy = std::hypot(tw.x, tw.y);
    if (txy < 0.5 || i < 8 || i > n - 9)
    {
      continue;
    }
    const double tanBeta = -tw.z / txy;
    const Vec2 etaA{ tw.x / txy, tw.y / txy };
    tracer.placeAt(*vm, g);
    ForceInput in;
    in.view = vm.get();
    in.state = InteractionState::Tracing;
    in.agent = tracer.sample(*vm);
    in.zoneGain_N = 1.0;
    ForceRequest req;
    const Vec2 f = law.compute(in, req);
    if (std::fabs(tanBeta) > 0.05)
    {
      worst = std::max(worst, std::fabs(f.dot(etaA) - tanBeta) / std::fabs(tanBeta));
    }
  }
  return worst;
}

const char* lawKey(ForceLawId law)
{
  switch (law)
  {
    case ForceLawId::Ldgf:
      return "ldgf";
    case ForceLawId::ChangeOfHeight:
      return "change_of_height";
    case ForceLawId::LateralGradient:
      return "lateral_gradient";
    case ForceLawId::ConstraintProxy:
      return "constraint_proxy";
    default:
      return "none";
  }
}
} // namespace

int main(int argc, char** argv)
{
  double seconds = 2.5;
  double referenceRate = 20000.0;
  double speed = 50.0;
  std::vector<double> rates{ 250, 500, 1000, 2000, 4000, 10000 };
  for (int i = 1; i < argc; ++i)
  {
    if (!std::strcmp(argv[i], "--seconds") && i + 1 < argc)
    {
      seconds = std::atof(argv[++i]);
    }
    else if (!std::strcmp(argv[i], "--reference-rate") && i + 1 < argc)
    {
      referenceRate = std::atof(argv[++i]);
    }
    else if (!std::strcmp(argv[i], "--speed-mm-per-s") && i + 1 < argc)
    {
      speed = std::atof(argv[++i]);
    }
    else if (!std::strcmp(argv[i], "--rates") && i + 1 < argc)
    {
      rates.clear();
      std::stringstream list(argv[++i]);
      std::string item;
      while (std::getline(list, item, ','))
      {
        rates.push_back(std::atof(item.c_str()));
      }
    }
    else
    {
      std::fprintf(stderr,
        "usage: %s [--seconds S] [--rates 250,...,10000] [--reference-rate 20000] "
        "[--speed-mm-per-s 50]\n",
        argv[0]);
      return 2;
    }
  }
  if (!(seconds > 0.6))
  {
    std::fprintf(stderr, "--seconds must exceed 0.6 (the first 0.5 s are not measured)\n");
    return 2;
  }
  const double from = 0.5;
  const double to = seconds - 0.01;
  std::printf("{\n  \"force.seconds_simulated\": %g,\n  \"force.reference_rate_hz\": %g,\n"
              "  \"force.hand_speed_mm_per_s\": %g",
    seconds,
    referenceRate,
    speed);
  for (const Scene& scene : { helixScene(), spiralScene() })
  {
    auto path = std::make_shared<const PlanarPath>(planar(scene));
    std::printf(",\n  \"force.ldgf.%s.max_rel_error\": %.6g",
      scene.name.c_str(),
      ldgfMaxRelativeError(scene));
    for (ForceLawId law : { ForceLawId::Ldgf,
           ForceLawId::ChangeOfHeight,
           ForceLawId::LateralGradient,
           ForceLawId::ConstraintProxy })
    {
      const Run ref = runAt(scene, path, law, referenceRate, seconds, speed);
      const std::string prefix = std::string("force.") + lawKey(law) + "." + scene.name;
      std::printf(",\n  \"%s.tracing_fraction\": %.4f", prefix.c_str(), tracingFraction(ref, from));
      for (double rate : rates)
      {
        const Run run = runAt(scene, path, law, rate, seconds, speed);
        std::printf(",\n  \"%s.%.0fhz.rel_rms_error\": %.6g",
          prefix.c_str(),
          rate,
          relativeRmsError(run, ref, from, to));
        if (std::fabs(rate - 1000.0) < 0.5)
        {
          std::printf(",\n  \"%s.tick_median_ns\": %.1f", prefix.c_str(), run.tickMedian_ns);
        }
      }
      std::fflush(stdout);
    }
  }
  bench::printTracerComparison();
  bench::printSurfaceStimulus();
  std::printf("\n}\n");
  return 0;
}

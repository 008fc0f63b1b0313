// vesseltouch-stability-map: stable/unstable maps of three settings against the loop rate, on the
// simulated handle through the session's offline path (the approach of
// Testing/Logic/Haptics/vtouchCouplerStabilityTest.cxx).
//
//   vesseltouch-stability-map [--points N] [--rates 250,500,1000,2000,4000,10000] [--seconds S]
//
// Maps (JSON on stdout, one object; grids as lists, row = rate, column = parameter value):
//   coupler: constraint-proxy stiffness k_c (N/m). A resting hand 2 mm beside a straight vessel;
//            force interpolation and slew off, so the coupler alone is measured. Stable = still
//            tracing and the last 20 % of the run within half the initial offset (the test's rule).
//   ldgf_lambda: LDGF lambda (mm) at a projection cusp (the winding line seen edge-on, where
//            dl -> 0), force interpolation off. A hand held at the cusp by a soft grip.
//   interpolation: the force-interpolation bound maxForceRate (N/s) at the same cusp, LDGF with
//            its default lambda.
// For the two cusp maps the hand sweeps the handle across the cusp (+-2 mm, 3 Hz) and "unstable" =
// energy growth: over the second half of the run the device does more than 1 mJ of net work on the
// handle beyond what the same setting does at a near-continuous 20 kHz (lambda map: the same
// lambda; interpolation map: the default bound). The slope field itself is not conservative at a
// cusp (the tracer's branch choice differs going and coming back), so only the energy the sampled
// loop adds is counted; 1 mJ is the kinetic energy of the 50 g handle at 0.2 m/s. Each map also
// reports the device's net work (J) per cell and the defaults.
#include "vtouchHapticSession.h"
#include "vtouchHapticsTestUtilities.h"
#include "vtouchPhantomGenerator.h"
#include "vtouchSimulatedDevice.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

using namespace vtouch;
using namespace vtouch::testing;

namespace
{
/// Cusp maps: net device work over the second half beyond the reference-rate run's is energy
/// growth above this, J.
constexpr double kGrowth_J = 1e-3;
/// Cusp maps: the near-continuous reference rate, Hz.
constexpr double kReferenceRate_Hz = 20000.0;

struct Cell
{
  bool stable = true;
  double work_J = 0.0;    ///< net device work on the handle over the second half of the run
  double motion_mm = 0.0; ///< coupler: largest offset; cusp: peak-to-peak motion, last 20 %
};

HandScript restingHand()
{
  HandScript hand;
  hand.drive = HandScript::Drive::Force;
  hand.trajectory = [](double, HandSample& s) { s.pressure = 1.0; };
  return hand;
}

/// Runs `session` offline in two halves and returns the device work over the second half.
double secondHalfWork(HapticSession& session, SimulatedDevice& device, double seconds, double rate)
{
  session.runOffline(0.5 * seconds, rate);
  const double w0 = device.energy().deviceWork_J;
  session.runOffline(0.5 * seconds, rate);
  return device.energy().deviceWork_J - w0;
}

Cell couplerCell(double stiffness, double rate, double seconds)
{
  HapticSession session;
  session.setSkeleton(straightLine({ -60, 2, 0 }, { 60, 2, 0 }, 0.25));
  session.setCamera(topCamera({ 0, 0, 0 }, 0.25));
  SimulatedDeviceParameters dp;
  dp.maxContinuousForce_N = 1000.0;
  dp.maxStiffness_N_per_m = 1e7;
  auto device = std::make_shared<SimulatedDevice>(dp);
  device->setHandScript(restingHand());
  session.setDevice(device);
  ForceSafetyParameters safety;
  safety.engageThreshold_N = 1e9;
  safety.maxForce_N = 1000.0;
  safety.maxSlewRate_N_per_s = 1e12;
  safety.maxTickInterval_s = 1.0;
  session.setSafetyParameters(safety);
  HapticParameters p = immediateContact(); // the resting hand starts on the vessel
  p.forceLaw = ForceLawId::ConstraintProxy;
  p.proxyStiffness_N_per_m = stiffness;
  p.maxForceRate_N_per_s = 1e12;
  session.setParameters(p);
  Cell c;
  c.work_J = secondHalfWork(session, *device, seconds, rate);
  const auto& log = session.log();
  double peak = 0.0;
  for (std::size_t i = log.size() * 8 / 10; i < log.size(); ++i)
  {
    peak = std::max(peak, std::fabs(log[i].cursor_px.y - 308.0) / 4.0);
  }
  c.motion_mm = peak;
  c.stable =
    session.agentState().state == InteractionState::Tracing && peak < 1.0 && std::isfinite(peak);
  return c;
}

/// The winding line seen from +z and the screen position (device mm from the centre) of its
/// steepest point: a projection cusp.
struct CuspScene
{
  QSkeleton skeleton;
  Vec3 focal_World_mm;
  Vec2 cusp_Device_mm;
};

CuspScene cuspScene()
{
  PhantomSpec spec;
  spec.shape = PhantomShape::WindingLine;
  PhantomGenerator phantom(spec);
  CuspScene s;
  s.skeleton = phantom.centerline();
  const auto centre = [&spec](int a)
  { return spec.origin_mm[a] + 0.5 * (spec.dimensions[a] - 1) * spec.spacing_mm[a]; };
  s.focal_World_mm = Vec3{ centre(0), centre(1), centre(2) };
  // The steepest point nearest the middle of the path.
  const auto& pts = s.skeleton.paths[0].points;
  double best = 1e300;
  for (std::size_t i = pts.size() / 4; i < 3 * pts.size() / 4; ++i)
  {
    const Vec3& t = pts[i].tangent_World;
    const double score =
      std::hypot(t.x, t.y) + 1e-4 * std::fabs(static_cast<double>(i) - 0.5 * pts.size());
    if (score < best)
    {
      best = score;
      s.cusp_Device_mm = { pts[i].position_World_mm.x - s.focal_World_mm.x,
        pts[i].position_World_mm.y - s.focal_World_mm.y };
    }
  }
  return s;
}

/// A grip (1000 N/m) that moves the handle from the centre to the cusp in 0.3 s, then sweeps it
/// across the cusp along x (the winding line's projected direction), +-2 mm at 3 Hz, so the law's
/// steep force change at the cusp is crossed again and again.
HandScript crossCusp(const Vec2& cusp)
{
  HandScript hand;
  hand.drive = HandScript::Drive::Position;
  hand.handStiffness_N_per_m = 1000.0;
  hand.trajectory = [cusp](double t, HandSample& h)
  {
    h.pressure = 1.0;
    if (t < 0.3)
    {
      h.position_Device_mm = cusp * (t / 0.3);
      h.velocity_Device_mm_per_s = cusp * (1.0 / 0.3);
      return;
    }
    const double w = 2.0 * kPi * 3.0;
    h.position_Device_mm = cusp + Vec2{ 2.0 * std::sin(w * (t - 0.3)), 0.0 };
    h.velocity_Device_mm_per_s = Vec2{ 2.0 * w * std::cos(w * (t - 0.3)), 0.0 };
  };
  return hand;
}

Cell cuspCell(const CuspScene& scene,
  double rate,
  double seconds,
  const std::function<void(HapticParameters&)>& set)
{
  HapticSession session;
  session.setSkeleton(scene.skeleton);
  session.setCamera(topCamera(scene.focal_World_mm, 0.25));
  auto device = std::make_shared<SimulatedDevice>();
  device->setHandScript(crossCusp(scene.cusp_Device_mm));
  session.setDevice(device);
  ForceSafetyParameters safety;
  safety.maxSlewRate_N_per_s = 1e12;
  safety.maxTickInterval_s = 1.0;
  session.setSafetyParameters(safety);
  HapticParameters p = immediateContact(); // the hand starts on the vessel
  p.forceLaw = ForceLawId::Ldgf;
  set(p);
  session.setParameters(p);
  Cell c;
  c.work_J = secondHalfWork(session, *device, seconds, rate);
  const auto& log = session.log();
  double lo = 1e300;
  double hi = -1e300;
  for (std::size_t i = log.size() * 8 / 10; i < log.size(); ++i)
  {
    const Vec2 h = log[i].hand_Device_mm;
    const double along = h.x; // the hand sweeps along x
    lo = std::min(lo, along);
    hi = std::max(hi, along);
  }
  c.motion_mm = hi - lo;
  c.stable = std::isfinite(c.work_J) && std::isfinite(c.motion_mm);
  return c;
}

/// A cusp cell judged against the same run at the reference rate: the energy the sampled loop adds.
Cell cuspCellAgainstReference(const CuspScene& scene,
  double rate,
  double seconds,
  const std::function<void(HapticParameters&)>& set,
  std::map<double, double>& referenceWork,
  double value)
{
  auto it = referenceWork.find(value);
  if (it == referenceWork.end())
  {
    it =
      referenceWork.emplace(value, cuspCell(scene, kReferenceRate_Hz, seconds, set).work_J).first;
  }
  Cell c = cuspCell(scene, rate, seconds, set);
  c.work_J -= it->second;
  c.stable = c.stable && c.work_J <= kGrowth_J;
  return c;
}

std::vector<double> logspace(double a, double b, int n)
{
  std::vector<double> v;
  for (int i = 0; i < n; ++i)
  {
    v.push_back(a * std::pow(b / a, n > 1 ? static_cast<double>(i) / (n - 1) : 0.0));
  }
  return v;
}

void printList(const char* key, const std::vector<double>& v)
{
  std::printf(",\n  \"%s\": [", key);
  for (std::size_t i = 0; i < v.size(); ++i)
  {
    std::printf("%s%.6g", i ? ", " : "", v[i]);
  }
  std::printf("]");
}

void printMap(const std::string& name,
  const std::vector<double>& values,
  const std::vector<double>& rates,
  double defaultValue,
  const std::function<Cell(double, double)>& cell)
{
  std::vector<double> stable;
  std::vector<double> work;
  std::vector<double> motion;
  for (double rate : rates)
  {
    for (double v : values)
    {
      const Cell c = cell(v, rate);
      stable.push_back(c.stable ? 1.0 : 0.0);
      work.push_back(c.work_J);
      motion.push_back(c.motion_mm);
    }
  }
  printList(("stability." + name + ".values").c_str(), values);
  printList(("stability." + name + ".rates_hz").c_str(), rates);
  printList(("stability." + name + ".stable").c_str(), stable);
  printList(("stability." + name + ".work_J").c_str(), work);
  printList(("stability." + name + ".motion_mm").c_str(), motion);
  std::printf(",\n  \"stability.%s.default\": %.6g", name.c_str(), defaultValue);
  std::fflush(stdout);
}
} // namespace

int main(int argc, char** argv)
{
  int points = 12;
  double seconds = 1.5;
  std::vector<double> rates{ 250, 500, 1000, 2000, 4000, 10000 };
  for (int i = 1; i < argc; ++i)
  {
    if (!std::strcmp(argv[i], "--points") && i + 1 < argc)
    {
      points = std::max(2, std::atoi(argv[++i]));
    }
    else if (!std::strcmp(argv[i], "--seconds") && i + 1 < argc)
    {
      seconds = std::atof(argv[++i]);
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
      std::fprintf(
        stderr, "usage: %s [--points N] [--rates 250,...,10000] [--seconds S]\n", argv[0]);
      return 2;
    }
  }
  const HapticParameters defaults;
  const CuspScene cusp = cuspScene();
  std::map<double, double> lambdaReference;
  std::map<double, double> interpolationReference;
  std::printf("{\n  \"stability.seconds_simulated\": %g", seconds);
  printMap("coupler_kc_n_per_m",
    logspace(20.0, 2e5, points),
    rates,
    defaults.proxyStiffness_N_per_m,
    [seconds](double k, double rate) { return couplerCell(k, rate, seconds); });
  printMap("ldgf_lambda_mm",
    logspace(1e-4, 1.0, points),
    rates,
    // The default in use: sized for the default 3 N stylus (Yi & Hayward 4.1, LdgfForceLaw).
    std::max(defaults.ldgfLambda_mm, defaults.zoneGain_N * 1.0 / (defaults.slopeForceBudget * 3.0)),
    [&cusp, seconds, &lambdaReference](double lambda, double rate)
    {
      return cuspCellAgainstReference(
        cusp,
        rate,
        seconds,
        [lambda](HapticParameters& p)
        {
          p.ldgfLambda_mm = lambda;
          p.slopeForceBudget = 0.0; // the lambda under test, not the device-sized one
          p.maxForceRate_N_per_s = 1e12;
        },
        lambdaReference,
        lambda);
    });
  printMap("interpolation_n_per_s",
    logspace(3.0, 1e5, points),
    rates,
    defaults.maxForceRate_N_per_s,
    [&cusp, seconds, &interpolationReference](double maxRate, double rate)
    {
      // The reference keeps the default bound: what a slower bound costs against the default
      // rendering at a near-continuous rate.
      const double reference =
        interpolationReference.count(-1.0)
          ? interpolationReference[-1.0]
          : (interpolationReference[-1.0] =
                cuspCell(cusp, kReferenceRate_Hz, seconds, [](HapticParameters&) {}).work_J);
      Cell c = cuspCell(
        cusp, rate, seconds, [maxRate](HapticParameters& p) { p.maxForceRate_N_per_s = maxRate; });
      c.work_J -= reference;
      c.stable = c.stable && c.work_J <= kGrowth_J;
      return c;
    });
  std::printf("\n}\n");
  return 0;
}

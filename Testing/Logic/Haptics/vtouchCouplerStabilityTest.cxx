// Passivity and stability of Ikits' virtual coupler on the simulated device (mass, damping,
// zero-order hold at the loop rate), run through the session's offline mode: the same tick code as
// the real-time loop.
#include "vtouchHapticSession.h"
#include "vtouchHapticsTestUtilities.h"
#include "vtouchSimulatedDevice.h"

#include <gtest/gtest.h>

namespace vtouch
{
namespace
{
using namespace vtouch::testing;

/// A hand resting on the stylus (pressure 1: saturation zone, no re-indexing) that does not push.
HandScript restingHand()
{
  HandScript hand;
  hand.drive = HandScript::Drive::Force;
  hand.trajectory = [](double, HandSample& s) { s.pressure = 1.0; };
  return hand;
}

struct CouplerRun
{
  double injected_J = 0.0; ///< device work minus the drop of the virtual spring's energy
  double initialOffset_mm = 0.0;
  double finalPeak_mm = 0.0; ///< largest |normal offset| over the last 20 % of the run
  bool tracing = false;
};

/// A vessel along x, 2 mm beside the handle's start (8 px at 4 px/mm): contact at the first tick,
/// then the coupler pulls the handle onto the vessel. `isolate` removes the pipeline's force
/// interpolation and the safety slew so the coupler alone is measured.
CouplerRun runCoupler(double stiffness,
  double rate_Hz,
  double duration_s,
  bool isolate,
  HandScript hand = restingHand(),
  double damping = -1.0)
{
  HapticSession session;
  session.setSkeleton(straightLine({ -60, 2, 0 }, { 60, 2, 0 }, 0.25));
  session.setCamera(topCamera({ 0, 0, 0 }, 0.25));
  SimulatedDeviceParameters dp;
  dp.maxContinuousForce_N = 1000.0;
  dp.maxStiffness_N_per_m = 1e7; // let the sweep go past the reported capability
  auto device = std::make_shared<SimulatedDevice>(dp);
  device->setHandScript(std::move(hand));
  session.setDevice(device);
  ForceSafetyParameters safety;
  safety.engageThreshold_N = 1e9; // engaged from the first tick (contact is immediate here)
  safety.maxForce_N = 1000.0;
  if (isolate)
  {
    safety.maxSlewRate_N_per_s = 1e12;
    safety.maxTickInterval_s = 1.0;
  }
  session.setSafetyParameters(safety);
  HapticParameters p = immediateContact(); // the resting hand starts on the vessel
  p.forceLaw = ForceLawId::ConstraintProxy;
  p.proxyStiffness_N_per_m = stiffness;
  if (damping >= 0.0)
  {
    p.proxyDamping_N_s_per_m = damping;
  }
  if (isolate)
  {
    p.maxForceRate_N_per_s = 1e12;
  }
  session.setParameters(p);
  session.setLogging(true);

  CouplerRun r;
  r.initialOffset_mm = 2.0;
  EXPECT_TRUE(session.runOffline(duration_s, rate_Hz)) << session.lastError();
  const auto& log = session.log();
  const AgentState last = session.agentState();
  r.tracing = last.state == InteractionState::Tracing;
  const double offsetEnd_mm = (last.cursor_px.y - last.agentScreen_px.y) / 4.0;
  const double k = std::min(stiffness, dp.maxStiffness_N_per_m);
  const double v0 = 0.5 * k * 0.002 * 0.002;
  const double vEnd = 0.5 * k * offsetEnd_mm * 1e-3 * offsetEnd_mm * 1e-3;
  r.injected_J = device->energy().deviceWork_J - (v0 - vEnd);
  for (std::size_t i = log.size() * 8 / 10; i < log.size(); ++i)
  {
    // The vessel is at world y = 2 mm = screen 308 px; the cursor's distance to it is the offset.
    r.finalPeak_mm = std::max(r.finalPeak_mm, std::fabs(log[i].cursor_px.y - 308.0) / 4.0);
  }
  return r;
}

bool stable(double k, double rate)
{
  const CouplerRun r = runCoupler(k, rate, 1.0, true);
  return r.tracing && r.finalPeak_mm < 0.5 * r.initialOffset_mm;
}

/// Largest stable stiffness by bisection in log space between 10 N/m and 1e6 N/m.
double largestStableStiffness(double rate)
{
  double lo = 10.0;
  double hi = 1e6;
  EXPECT_TRUE(stable(lo, rate));
  EXPECT_FALSE(stable(hi, rate));
  for (int i = 0; i < 14; ++i)
  {
    const double mid = std::sqrt(lo * hi);
    (stable(mid, rate) ? lo : hi) = mid;
  }
  return lo;
}

TEST(VirtualCoupler, DefaultStiffnessIsPassiveOverLongContact)
{
  // A hand pushing across and along the vessel for 5 s (force drive, 3 Hz): the coupler with the
  // default k_c and b_c, through the full default pipeline, must not inject energy.
  HandScript hand;
  hand.drive = HandScript::Drive::Force;
  hand.trajectory = [](double t, HandSample& s)
  {
    s.force_Device_N = { 0.2 * std::sin(2 * kPi * 1.3 * t), 0.3 * std::sin(2 * kPi * 3.0 * t) };
    s.pressure = 1.0;
  };
  const HapticParameters defaults;
  for (double rate : { 1000.0, 4000.0 })
  {
    const CouplerRun r = runCoupler(defaults.proxyStiffness_N_per_m, rate, 5.0, false, hand);
    EXPECT_TRUE(r.tracing) << rate;
    EXPECT_LE(r.injected_J, 0.0) << rate;
  }
  // The same run with the damping removed and a much stiffer spring does inject energy: the
  // measure can fail.
  const CouplerRun bad = runCoupler(3000.0, 250.0, 5.0, true, hand, 0.0);
  EXPECT_GT(bad.injected_J, 0.0);
}

TEST(VirtualCoupler, DefaultStiffnessSitsBelowLargestStableAt250Hz1kHz4kHz)
{
  const HapticParameters defaults;
  double previous = 0.0;
  for (double rate : { 250.0, 1000.0, 4000.0 })
  {
    const double kMax = largestStableStiffness(rate);
    std::printf("[ coupler  ] largest stable k_c at %6.0f Hz: %8.0f N/m (default %g N/m)\n",
      rate,
      kMax,
      defaults.proxyStiffness_N_per_m);
    EXPECT_LT(defaults.proxyStiffness_N_per_m, kMax) << rate;
    EXPECT_GT(kMax, previous) << "a faster loop must allow a stiffer coupler";
    previous = kMax;
  }
}

} // namespace
} // namespace vtouch

// vesseltouch-loop-timing: runs the real-time haptic loop (a HapticSession with a simulated device
// on the real-time clock) and prints achieved rate and period-error percentiles.
//
//   vesseltouch-loop-timing [--seconds S] [--rates 1000,10000] [--render] [--no-fifo]
//                           [--spin-us 250]
//
// --render adds a busy "render" thread that rebuilds the view model continuously (the GUI work of
// camera changes) and burns CPU in between, on the same 2 cores.
#include "vtouchHapticSession.h"
#include "vtouchHapticsTestUtilities.h"
#include "vtouchSimulatedDevice.h"

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

using namespace vtouch;
using namespace vtouch::testing;

namespace
{
QSkeleton demoSkeleton()
{
  // A helix of 4000 points seen from the side and a crossing line: a small realistic scene.
  QSkeleton s = singlePath(
    [](double t)
    {
      const double a = 6 * kPi * t;
      return Vec3{ 25 * std::cos(a), 25 * std::sin(a), -36 + 72 * t };
    },
    4000);
  return s;
}

void run(double rate, double seconds, bool render, bool fifo, double spin)
{
  HapticSession session;
  session.setSkeleton(demoSkeleton());
  session.setCamera(topCamera({ 0, 0, 0 }, 0.25));
  SimulatedDeviceParameters dp;
  dp.clock = SimulatedDeviceParameters::Clock::RealTime;
  auto device = std::make_shared<SimulatedDevice>(dp);
  HandScript hand = HandScript::circle({ 0, 0 }, 25.0, 0.5, 2000.0);
  auto circle = hand.trajectory;
  hand.trajectory = [circle](double t, HandSample& s)
  {
    circle(t, s);
    s.pressure = 1.0;
  };
  device->setHandScript(hand);
  session.setDevice(device);

  std::atomic<bool> stopRender{ false };
  std::atomic<long> frames{ 0 };
  std::thread renderer;
  if (render)
  {
    renderer = std::thread(
      [&]
      {
        volatile double sink = 0.0;
        int k = 0;
        while (!stopRender.load())
        {
          session.setCamera(topCamera({ 0.01 * (k++ % 100), 0, 0 }, 0.25));
          for (int i = 0; i < 200000; ++i)
          {
            sink = sink + std::sqrt(static_cast<double>(i));
          }
          frames.fetch_add(1);
        }
      });
  }
  LoopOptions o;
  o.rate_Hz = rate;
  o.realtimePriority = fifo ? 80 : 0;
  o.spinMargin_us = spin;
  if (!session.start(o))
  {
    std::fprintf(stderr, "cannot start: %s\n", session.lastError().c_str());
    std::exit(1);
  }
  std::this_thread::sleep_for(std::chrono::duration<double>(seconds));
  session.stop();
  stopRender.store(true);
  if (renderer.joinable())
  {
    renderer.join();
  }
  const LoopStatisticsSummary s = session.statistics();
  std::printf("rate %6.0f Hz%s: achieved %9.1f Hz over %llu ticks | period error p50 %6.1f us "
              "p99 %7.1f us p99.9 %7.1f us max %8.1f us | overruns %llu (skipped %llu) | tick "
              "cost p50 %.2f us p99 %.2f us max %.1f us | render frames %ld | fault %s\n",
    rate,
    render ? " +render" : "",
    s.achievedRate_Hz,
    static_cast<unsigned long long>(s.ticks),
    s.periodErrorP50_us,
    s.periodErrorP99_us,
    s.periodErrorP999_us,
    s.periodErrorMax_us,
    static_cast<unsigned long long>(s.overruns),
    static_cast<unsigned long long>(s.skippedDeadlines),
    s.tickCostP50_us,
    s.tickCostP99_us,
    s.tickCostMax_us,
    frames.load(),
    toString(session.fault()));
  std::printf("  %s\n", session.schedulerNotice().c_str());
}
} // namespace

int main(int argc, char** argv)
{
  double seconds = 3.0;
  std::vector<double> rates{ 1000.0, 10000.0 };
  bool render = false;
  bool fifo = true;
  double spin = 250.0;
  for (int i = 1; i < argc; ++i)
  {
    if (!std::strcmp(argv[i], "--seconds") && i + 1 < argc)
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
    else if (!std::strcmp(argv[i], "--render"))
    {
      render = true;
    }
    else if (!std::strcmp(argv[i], "--no-fifo"))
    {
      fifo = false;
    }
    else if (!std::strcmp(argv[i], "--spin-us") && i + 1 < argc)
    {
      spin = std::atof(argv[++i]);
    }
    else
    {
      std::fprintf(stderr,
        "usage: %s [--seconds S] [--rates 1000,10000] [--render] [--no-fifo] [--spin-us 250]\n",
        argv[0]);
      return 2;
    }
  }
  for (double rate : rates)
  {
    run(rate, seconds, render, fifo, spin);
  }
  return 0;
}

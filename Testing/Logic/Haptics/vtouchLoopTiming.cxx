// vesseltouch-loop-timing: runs the real-time haptic loop (a HapticSession with a simulated device
// on the real-time clock) and prints achieved rate and period-error percentiles.
//
//   vesseltouch-loop-timing [--seconds S] [--rates 1000,10000] [--render] [--no-fifo]
//                           [--spin-us 250] [--json out.json]
//
// --json also writes, per rate, the statistics and a histogram of the period error (lateness of
// each wake-up against its absolute deadline, recovered from the session log's tick times) as one
// JSON object with flat keys: haptic.loop_<rate>hz[_render].<name>.
//
// --render adds a busy "render" thread that rebuilds the view model continuously (the GUI work of
// camera changes) and burns CPU in between, on the same 2 cores.
#include "vtouchHapticSession.h"
#include "vtouchHapticsTestUtilities.h"
#include "vtouchSimulatedDevice.h"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
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

/// Lateness (us) of each logged tick against its deadline on the grid k * period: the loop wakes
/// at or after its deadline, and after a tick that ends past the next deadline it skips the missed
/// ones (the tick's end is taken as its wake time: ticks cost microseconds).
std::vector<double> periodErrors_us(const std::vector<SessionLogEntry>& log, double rate)
{
  std::vector<double> late;
  const double period = 1.0 / rate;
  double deadline = 0.0;
  for (std::size_t k = 0; k < log.size(); ++k)
  {
    if (k > 0)
    {
      deadline += period;
      if (log[k - 1].time_s >= deadline)
      {
        deadline += (std::floor((log[k - 1].time_s - deadline) / period) + 1.0) * period;
      }
    }
    late.push_back(std::max(0.0, (log[k].time_s - deadline) * 1e6));
  }
  return late;
}

/// CPU time the hypervisor gave to other guests ("steal", /proc/stat), ms summed over all CPUs;
/// -1 when unknown. A wake-up delayed by steal is late whatever the loop does, so the timing
/// report shows it beside the period error.
double hostSteal_ms()
{
  std::ifstream stat("/proc/stat");
  std::string cpu;
  unsigned long long v[8] = {};
  if (!(stat >> cpu) || cpu != "cpu")
  {
    return -1.0;
  }
  for (unsigned long long& x : v)
  {
    if (!(stat >> x))
    {
      return -1.0;
    }
  }
  const long ticksPerSecond = sysconf(_SC_CLK_TCK);
  return ticksPerSecond > 0 ? 1000.0 * static_cast<double>(v[7]) / ticksPerSecond : -1.0;
}

/// Appends `"prefix.key": value` lines for one run to `json`.
void appendJson(std::string& json,
  const std::string& prefix,
  const LoopStatisticsSummary& s,
  const std::vector<double>& late,
  long frames,
  double steal_ms)
{
  char line[256];
  const auto add = [&](const char* key, double value)
  {
    std::snprintf(line,
      sizeof line,
      "%s  \"%s.%s\": %.6g",
      json.empty() ? "" : ",\n",
      prefix.c_str(),
      key,
      value);
    json += line;
  };
  add("achieved_hz", s.achievedRate_Hz);
  add("ticks", static_cast<double>(s.ticks));
  add("p50_period_error_us", s.periodErrorP50_us);
  add("p99_period_error_us", s.periodErrorP99_us);
  add("p999_period_error_us", s.periodErrorP999_us);
  add("max_period_error_us", s.periodErrorMax_us);
  add("overruns", static_cast<double>(s.overruns));
  add("tick_median_ns", 1000.0 * s.tickCostP50_us);
  add("tick_p99_ns", 1000.0 * s.tickCostP99_us);
  add("render_frames", static_cast<double>(frames));
  add("host_steal_ms", steal_ms);
  add("stalls", static_cast<double>(s.stalls));
  add("stall_time_ms", 1000.0 * s.stallTime_s);
  add("achieved_hz_outside_stalls", s.achievedRateOutsideStalls_Hz);
  // Histogram: 0.5 us bins up to 50 us, then one bin per decade step of 10 % up to 10 ms.
  std::vector<double> edges;
  for (double e = 0.0; e < 50.0; e += 0.5)
  {
    edges.push_back(e);
  }
  for (double e = 50.0; e <= 1e4; e *= 1.1)
  {
    edges.push_back(e);
  }
  std::vector<double> counts(edges.size(), 0.0);
  for (double v : late)
  {
    const auto it = std::upper_bound(edges.begin(), edges.end(), v);
    counts[static_cast<std::size_t>(it - edges.begin()) - 1] += 1.0;
  }
  for (const auto* list : { &edges, &counts })
  {
    json += ",\n  \"" + prefix + (list == &edges ? ".hist_edges_us" : ".hist_counts") + "\": [";
    for (std::size_t i = 0; i < list->size(); ++i)
    {
      std::snprintf(line, sizeof line, "%s%.4g", i ? ", " : "", (*list)[i]);
      json += line;
    }
    json += "]";
  }
}

void run(double rate, double seconds, bool render, bool fifo, double spin, std::string* json)
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
  if (json)
  {
    session.setLogCapacity(static_cast<std::size_t>(rate * (seconds + 1.0)));
    session.setLogging(true);
  }

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
  const double stealBefore_ms = hostSteal_ms();
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
  const double stealAfter_ms = hostSteal_ms();
  const double steal_ms =
    stealBefore_ms < 0.0 || stealAfter_ms < 0.0 ? -1.0 : stealAfter_ms - stealBefore_ms;
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
  std::printf("  host: steal %.0f ms (other guests ran on our CPUs), %llu stalls beyond the "
              "watchdog losing %.1f ms, %.1f Hz outside them\n",
    steal_ms,
    static_cast<unsigned long long>(s.stalls),
    1000.0 * s.stallTime_s,
    s.achievedRateOutsideStalls_Hz);
  std::printf("  %s\n", session.schedulerNotice().c_str());
  if (json)
  {
    char prefix[64];
    std::snprintf(prefix, sizeof prefix, "haptic.loop_%.0fhz%s", rate, render ? "_render" : "");
    appendJson(*json, prefix, s, periodErrors_us(session.log(), rate), frames.load(), steal_ms);
  }
}
} // namespace

int main(int argc, char** argv)
{
  double seconds = 3.0;
  std::vector<double> rates{ 1000.0, 10000.0 };
  bool render = false;
  bool fifo = true;
  double spin = 250.0;
  std::string jsonPath;
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
    else if (!std::strcmp(argv[i], "--json") && i + 1 < argc)
    {
      jsonPath = argv[++i];
    }
    else
    {
      std::fprintf(stderr,
        "usage: %s [--seconds S] [--rates 1000,10000] [--render] [--no-fifo] [--spin-us 250] "
        "[--json out.json]\n",
        argv[0]);
      return 2;
    }
  }
  std::string json;
  for (double rate : rates)
  {
    run(rate, seconds, render, fifo, spin, jsonPath.empty() ? nullptr : &json);
  }
  if (!jsonPath.empty())
  {
    std::ofstream out(jsonPath);
    out << "{\n" << json << "\n}\n";
    if (!out)
    {
      std::fprintf(stderr, "cannot write %s\n", jsonPath.c_str());
      return 1;
    }
  }
  return 0;
}

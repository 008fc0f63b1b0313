// Benchmarks of issue 5 point 9: view-model rebuild and tick cost on a 1 M-point skeleton.
//   vtouchHapticsBenchmark --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include "vtouchHapticPipeline.h"
#include "vtouchHapticSession.h"
#include "vtouchHapticsTestUtilities.h"
#include "vtouchSimulatedDevice.h"
#include "vtouchViewModelBuilder.h"

#include <benchmark/benchmark.h>

#include <random>

namespace vtouch
{
namespace
{
using namespace vtouch::testing;

/// 1000 smooth random vessels of 1000 points (0.25 mm apart) in a 150 mm box: 1 M points, with
/// junctions every 100 vessels so the graph is connected in places.
const QSkeleton& millionPointSkeleton()
{
  static const QSkeleton skeleton = []
  {
    QSkeleton s;
    std::mt19937 rng(2024);
    std::uniform_real_distribution<double> u(-60.0, 60.0);
    std::uniform_real_distribution<double> phase(0.0, 2 * kPi);
    for (int p = 0; p < 1000; ++p)
    {
      const Vec3 a{ u(rng), u(rng), u(rng) };
      const Vec3 dir{ u(rng), u(rng), u(rng) };
      const double ph = phase(rng);
      const Vec3 d = dir * (1.0 / dir.norm());
      SkeletonPath path = samplePath(
        [a, d, ph](double t)
        {
          const double s = 250.0 * t; // 250 mm long, 1000 points
          return a + d * (0.6 * s) +
                 Vec3{
                   8 * std::sin(0.05 * s + ph), 8 * std::cos(0.04 * s + ph), 6 * std::sin(0.03 * s)
                 };
        },
        1000);
      path.id = p;
      s.paths.push_back(std::move(path));
    }
    for (int p = 1; p < 1000; p += 100)
    {
      join(s, p, Junction::End::Head, p - 1, 500);
    }
    return s;
  }();
  return skeleton;
}

void BM_ViewModelRebuild_1M_800x600(benchmark::State& state)
{
  auto topo = SceneTopology::build(millionPointSkeleton(), 1.0);
  ViewModelBuilder builder;
  builder.setThreads(static_cast<int>(state.range(0)));
  std::shared_ptr<ViewModel> previous = builder.build(topo, topCamera({ 0, 0, 0 }, 0.25));
  int k = 0;
  for (auto _ : state)
  {
    // A new camera every time (orbiting), rebuilt into the previous snapshot's buffers as the
    // session does through ViewModelExchange::takeRecyclable().
    const double a = 0.01 * (k++);
    HostCamera cam = makeOrthographicCamera(
      { 0, 0, 0 }, { std::sin(a), 0.2, -std::cos(a) }, { 0, 1, 0 }, 75.0, 800, 600);
    previous = builder.build(topo, cam, std::move(previous));
    benchmark::DoNotOptimize(previous->contactAt(400, 300));
  }
  state.counters["points"] = static_cast<double>(topo->pointCount());
}
// Argument: threads of the distance transform (1 or 2).
BENCHMARK(BM_ViewModelRebuild_1M_800x600)
  ->Arg(1)
  ->Arg(2)
  ->Unit(benchmark::kMillisecond)
  ->UseRealTime();

void BM_ViewModelRebuild_1M_800x600_Cold(benchmark::State& state)
{
  auto topo = SceneTopology::build(millionPointSkeleton(), 1.0);
  ViewModelBuilder builder;
  for (auto _ : state)
  {
    auto vm = builder.build(topo, topCamera({ 0, 0, 0 }, 0.25)); // fresh allocation every time
    benchmark::DoNotOptimize(vm->contactAt(400, 300));
  }
}
BENCHMARK(BM_ViewModelRebuild_1M_800x600_Cold)->Unit(benchmark::kMillisecond)->UseRealTime();

/// One pipeline tick while tracing a vessel of the 1 M-point scene with a moving hand.
void BM_PipelineTick_1M(benchmark::State& state)
{
  auto topo = SceneTopology::build(millionPointSkeleton(), 1.0);
  ViewModelBuilder builder;
  auto vm = builder.build(topo, topCamera({ 0, 0, 0 }, 0.25));
  HapticPipeline pipeline;
  HapticParameters params = immediateContact(); // starts on the vessel
  params.forceLaw = static_cast<ForceLawId>(state.range(0));
  DeviceCapabilities caps;
  caps.maxStiffness_N_per_m = 1000.0;
  // Start on the middle of a vessel that is on screen.
  int start = -1;
  for (int g = 500; g < vm->pointCount() && start < 0; g += 1000)
  {
    const Vec2 p = vm->screen_px(g);
    if (p.x > 200 && p.x < 600 && p.y > 150 && p.y < 450)
    {
      start = g;
    }
  }
  pipeline.setCursor_px(vm->screen_px(start));
  TickInput in;
  in.capabilities = &caps;
  in.view = vm.get();
  in.device.pressure = 1.0;
  int k = 0;
  int direction = 1;
  for (auto _ : state)
  {
    // The hand follows the vessel's screen direction at ~50 mm/s, back and forth.
    const AgentState s = pipeline.step(in, params);
    const int g = s.point >= 0 ? topo->globalIndex(s.path, s.point) : start;
    const Vec2 eta = vm->eta(g);
    in.device.position_Device_mm.x += direction * 0.05 * eta.x;
    in.device.position_Device_mm.y += direction * 0.05 * eta.y;
    if (++k % 2000 == 0)
    {
      direction = -direction;
    }
    in.time_s += 0.001;
    benchmark::DoNotOptimize(s.force_N);
  }
}
BENCHMARK(BM_PipelineTick_1M)
  ->Arg(static_cast<int>(ForceLawId::Ldgf))
  ->Arg(static_cast<int>(ForceLawId::ChangeOfHeight))
  ->Arg(static_cast<int>(ForceLawId::LateralGradient))
  ->Arg(static_cast<int>(ForceLawId::ConstraintProxy))
  ->Unit(benchmark::kNanosecond);

/// The whole session tick (device read/write through the interface, snapshot acquire, parameter
/// seqlock, pipeline, safety filter, state publication) on the 1 M-point scene.
void BM_SessionTick_1M(benchmark::State& state)
{
  HapticSession session;
  session.setSkeleton(millionPointSkeleton());
  session.setCamera(topCamera({ 0, 0, 0 }, 0.25));
  auto device = std::make_shared<SimulatedDevice>();
  HandScript hand;
  hand.trajectory = [](double, HandSample& s) { s.pressure = 1.0; };
  device->setHandScript(hand);
  device->open();
  session.setDevice(device);
  double t = 0.0;
  for (auto _ : state)
  {
    session.tick(t, 0.001);
    t += 0.001;
  }
  benchmark::DoNotOptimize(session.agentState());
}
BENCHMARK(BM_SessionTick_1M)->Unit(benchmark::kNanosecond);

} // namespace
} // namespace vtouch

BENCHMARK_MAIN();

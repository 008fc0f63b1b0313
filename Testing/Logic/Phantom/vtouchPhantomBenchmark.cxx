// Phantom generation time against volume size (issue 2: 384^3 in a few seconds).
#include "vtouchPhantomGenerator.h"

#include <benchmark/benchmark.h>

#include <vector>

namespace
{
void BM_PhantomFill(benchmark::State& state, vtouch::PhantomShape shape)
{
  vtouch::PhantomSpec spec;
  spec.shape = shape;
  const int n = static_cast<int>(state.range(0));
  spec.dimensions = { n, n, n };
  spec.noiseStdDev = 10.0;
  std::vector<float> voxels(static_cast<std::size_t>(n) * n * n);
  for (auto _ : state)
  {
    vtouch::PhantomGenerator generator(spec);
    benchmark::DoNotOptimize(generator.fill(voxels.data()));
  }
  state.counters["voxels"] = static_cast<double>(voxels.size());
}
} // namespace

BENCHMARK_CAPTURE(BM_PhantomFill, Helix, vtouch::PhantomShape::Helix)
  ->Arg(64)
  ->Arg(128)
  ->Arg(256)
  ->Arg(384)
  ->Unit(benchmark::kMillisecond)
  ->Iterations(1);
BENCHMARK_CAPTURE(BM_PhantomFill, Tree, vtouch::PhantomShape::Tree)
  ->Arg(128)
  ->Arg(384)
  ->Unit(benchmark::kMillisecond)
  ->Iterations(1);
BENCHMARK_MAIN();

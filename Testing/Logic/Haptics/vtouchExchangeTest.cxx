#include "vtouchHapticsTestUtilities.h"
#include "vtouchSeqLock.h"
#include "vtouchViewModelExchange.h"

#include <gtest/gtest.h>

#include <atomic>
#include <thread>

namespace vtouch
{
namespace
{
using namespace vtouch::testing;

struct Payload
{
  std::uint64_t a = 0;
  double b = 0.0;
  std::uint64_t c = 0;
  int d[7] = {};
};

TEST(SeqLock, ReaderNeverSeesATornWrite)
{
  SeqLock<Payload> lock;
  std::atomic<bool> done{ false };
  std::thread writer(
    [&]
    {
      for (std::uint64_t i = 1; i <= 200000; ++i)
      {
        Payload p;
        p.a = i;
        p.b = static_cast<double>(i);
        p.c = i * 3;
        for (int& x : p.d)
        {
          x = static_cast<int>(i);
        }
        lock.store(p);
      }
      done.store(true);
    });
  std::uint64_t last = 0;
  int reads = 0;
  while (!done.load() || reads < 10)
  {
    const Payload p = lock.load();
    ASSERT_EQ(static_cast<double>(p.a), p.b);
    ASSERT_EQ(p.a * 3, p.c);
    for (int x : p.d)
    {
      ASSERT_EQ(x, static_cast<int>(p.a));
    }
    ASSERT_GE(p.a, last); // never goes back in time
    last = p.a;
    ++reads;
  }
  writer.join();
  EXPECT_EQ(lock.load().a, 200000u);
}

TEST(ViewModelExchange, ReaderSeesWholeSnapshotsWhileProducerRecycles)
{
  const QSkeleton s = straightLine({ -20, 0, 0 }, { 20, 0, 0 }, 0.5);
  auto topo = SceneTopology::build(s, 1.0);
  ViewModelExchange exchange;
  std::atomic<bool> done{ false };
  std::atomic<int> recycledCount{ 0 };
  std::thread producer(
    [&]
    {
      ViewModelBuilder builder;
      builder.setCaptureRadius_px(4.0);
      for (int i = 0; i < 300; ++i)
      {
        // Each snapshot shifts the line by i pixels: every point of one snapshot agrees on i.
        auto recycled = exchange.takeRecyclable();
        if (recycled)
        {
          recycledCount.fetch_add(1);
        }
        exchange.publish(builder.build(
          topo, topCamera({ -0.25 * (i % 100), 0, 0 }, 0.25, 320, 240), std::move(recycled)));
      }
      done.store(true);
    });
  int reads = 0;
  std::uint64_t lastGeneration = 0;
  while (!done.load() || reads < 10)
  {
    const ViewModel* vm = exchange.acquire();
    if (!vm)
    {
      continue;
    }
    ASSERT_GE(vm->generation(), lastGeneration);
    lastGeneration = vm->generation();
    const double shift = vm->screen_px(0).x - 80.0;
    const int n = vm->pointCount();
    for (int g = 0; g < n; g += 7)
    {
      ASSERT_NEAR(vm->screen_px(g).x - 80.0 - g * 2.0, shift, 1e-3);
    }
    ++reads;
  }
  exchange.release();
  producer.join();
  EXPECT_GT(reads, 0);
  EXPECT_GT(recycledCount.load(), 0); // buffers were reused, not reallocated every time
  ASSERT_NE(exchange.current(), nullptr);
}

} // namespace
} // namespace vtouch

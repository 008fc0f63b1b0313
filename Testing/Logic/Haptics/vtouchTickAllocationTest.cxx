// The haptic tick must not allocate: counts every operator new made on the ticking thread while a
// flag is up, over many ticks of every force law (after a warm-up that reserves the log).
#include "vtouchHapticSession.h"
#include "vtouchHapticsTestUtilities.h"
#include "vtouchSimulatedDevice.h"

#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <memory>
#include <new>

namespace
{
thread_local bool CountAllocations = false;
std::atomic<long> Allocations{ 0 };
} // namespace

// Replacement allocation functions (GCC cannot see that this new and delete pair up).
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
#endif

void* operator new(std::size_t size)
{
  if (CountAllocations)
  {
    Allocations.fetch_add(1);
  }
  if (void* p = std::malloc(size ? size : 1))
  {
    return p;
  }
  throw std::bad_alloc();
}

void operator delete(void* p) noexcept
{
  std::free(p);
}

void operator delete(void* p, std::size_t) noexcept
{
  std::free(p);
}

namespace vtouch
{
namespace
{
using namespace vtouch::testing;

TEST(HapticSession, TickNeverAllocates)
{
  // The counter itself works.
  CountAllocations = true;
  {
    auto probe = std::make_unique<int>(1);
    EXPECT_EQ(*probe, 1);
  }
  CountAllocations = false;
  ASSERT_EQ(Allocations.exchange(0), 1);

  HapticSession session;
  QSkeleton s = straightLine({ -40, 0, 0 }, { 40, 0, 20 }, 0.25);
  QSkeleton branch = straightLine({ 0, 0, 10 }, { 10, 20, 10 }, 0.25);
  branch.paths[0].id = 1;
  s.paths.push_back(branch.paths[0]);
  join(s, 1, Junction::End::Head, 0, 160);
  session.setSkeleton(s);
  session.setCamera(topCamera({ 0, 0, 10 }));
  auto device = std::make_shared<SimulatedDevice>();
  HandScript hand = HandScript::circle({ 0, 0 }, 10.0, 1.0, 2000.0);
  auto circle = hand.trajectory;
  hand.trajectory = [circle](double t, HandSample& h)
  {
    circle(t, h);
    h.pressure = 1.0;
  };
  device->setHandScript(hand);
  ASSERT_EQ(device->open(), DeviceStatus::Ok);
  session.setDevice(device);
  session.setLogging(true);
  session.setLogCapacity(20000);
  double t = 0.0;
  long total = 0;
  for (ForceLawId law : { ForceLawId::Ldgf,
         ForceLawId::ChangeOfHeight,
         ForceLawId::LateralGradient,
         ForceLawId::ConstraintProxy })
  {
    session.setForceLaw(law); // outside the tick (control thread)
    CountAllocations = true;
    for (int k = 0; k < 2000; ++k)
    {
      session.tick(t, 0.001);
      device->advance(0.001);
      t += 0.001;
    }
    CountAllocations = false;
    total += Allocations.exchange(0);
  }
  EXPECT_EQ(total, 0);
  EXPECT_EQ(session.log().size(), 8000u);
  EXPECT_EQ(session.agentState().state, InteractionState::Tracing);
}

} // namespace
} // namespace vtouch

#include "vtouchForceSafetyFilter.h"
#include "vtouchVelocityEstimator.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

namespace
{
using vtouch::ForceSafetyFilter;
using vtouch::ForceSafetyParameters;
using vtouch::SafetyFault;
using vtouch::Vec3;
using vtouch::VelocityEstimator;

ForceSafetyFilter engagedFilter(ForceSafetyParameters p = ForceSafetyParameters{})
{
  ForceSafetyFilter filter(p);
  for (int i = 0; i < p.engageTicks; ++i)
  {
    filter.apply(Vec3{}, 0.001);
  }
  return filter;
}

TEST(ForceSafetyFilter, OutputsZeroUntilCommandQuietForEngageTicks)
{
  ForceSafetyParameters p;
  p.engageTicks = 5;
  ForceSafetyFilter filter(p);
  for (int i = 0; i < 20; ++i)
  {
    EXPECT_EQ(filter.apply(Vec3{ 1.0, 0.0, 0.0 }, 0.001).norm(), 0.0);
  }
  EXPECT_FALSE(filter.engaged());
  for (int i = 0; i < 4; ++i)
  {
    filter.apply(Vec3{ 0.01, 0.0, 0.0 }, 0.001);
  }
  EXPECT_FALSE(filter.engaged());
  filter.apply(Vec3{ 0.01, 0.0, 0.0 }, 0.001);
  EXPECT_TRUE(filter.engaged());
}

TEST(ForceSafetyFilter, RestartsQuietCountWhenCommandJumps)
{
  ForceSafetyParameters p;
  p.engageTicks = 3;
  ForceSafetyFilter filter(p);
  filter.apply(Vec3{}, 0.001);
  filter.apply(Vec3{}, 0.001);
  filter.apply(Vec3{ 1.0, 0.0, 0.0 }, 0.001);
  filter.apply(Vec3{}, 0.001);
  filter.apply(Vec3{}, 0.001);
  EXPECT_FALSE(filter.engaged());
  filter.apply(Vec3{}, 0.001);
  EXPECT_TRUE(filter.engaged());
}

TEST(ForceSafetyFilter, ClampsMagnitudeKeepingDirectionWhenCommandTooLarge)
{
  ForceSafetyParameters p;
  p.maxForce_N = 1.0;
  p.maxSlewRate_N_per_s = 1e9;
  ForceSafetyFilter filter = engagedFilter(p);
  const Vec3 out = filter.apply(Vec3{ 3.0, 4.0, 0.0 }, 0.001);
  EXPECT_NEAR(out.norm(), 1.0, 1e-12);
  EXPECT_NEAR(out.x / out.y, 0.75, 1e-12);
  EXPECT_EQ(filter.clampedTicks(), 1u);
}

TEST(ForceSafetyFilter, LimitsSlewRateWhenCommandSteps)
{
  ForceSafetyParameters p;
  p.maxSlewRate_N_per_s = 100.0;
  ForceSafetyFilter filter = engagedFilter(p);
  double previous = 0.0;
  for (int i = 1; i <= 10; ++i)
  {
    const double x = filter.apply(Vec3{ 1.0, 0.0, 0.0 }, 0.001).x;
    EXPECT_NEAR(x - previous, 0.1, 1e-12);
    previous = x;
  }
  EXPECT_NEAR(filter.apply(Vec3{ 1.0, 0.0, 0.0 }, 0.001).x, 1.0, 1e-12);
}

TEST(ForceSafetyFilter, CapsSlewCreditWhenTickIntervalIsLong)
{
  ForceSafetyParameters p;
  p.maxSlewRate_N_per_s = 100.0;
  p.maxTickInterval_s = 0.002;
  ForceSafetyFilter filter = engagedFilter(p);
  EXPECT_NEAR(filter.apply(Vec3{ 2.0, 0.0, 0.0 }, 1.0).x, 0.2, 1e-12);
}

TEST(ForceSafetyFilter, OutputsZeroAndReportsFaultWhenCommandIsNaNOrInf)
{
  ForceSafetyParameters p;
  p.maxSlewRate_N_per_s = 1e9;
  ForceSafetyFilter filter = engagedFilter(p);
  filter.apply(Vec3{ 1.0, 0.0, 0.0 }, 0.001);
  SafetyFault fault = SafetyFault::None;
  const Vec3 out = filter.apply(Vec3{ std::nan(""), 0.0, 0.0 }, 0.001, &fault);
  EXPECT_EQ(out.norm(), 0.0);
  EXPECT_EQ(fault, SafetyFault::NonFiniteForce);
  EXPECT_FALSE(filter.engaged());
  fault = SafetyFault::None;
  filter.apply(Vec3{ 0.0, std::numeric_limits<double>::infinity(), 0.0 }, 0.001, &fault);
  EXPECT_EQ(fault, SafetyFault::NonFiniteForce);
  EXPECT_EQ(filter.nonFiniteTicks(), 2u);
}

TEST(ForceSafetyFilter, NeverExceedsLimitsWhenCommandIsRandom)
{
  ForceSafetyParameters p;
  p.maxForce_N = 1.5;
  p.maxSlewRate_N_per_s = 300.0;
  ForceSafetyFilter filter(p);
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> f(-10.0, 10.0);
  Vec3 previous;
  for (int i = 0; i < 10000; ++i)
  {
    const Vec3 out = filter.apply(Vec3{ f(rng), f(rng), 0.0 } * (i % 7 == 0 ? 0.0 : 1.0), 0.001);
    EXPECT_LE(out.norm(), 1.5 + 1e-12);
    EXPECT_LE((out - previous).norm(), 0.3 + 1e-12);
    previous = out;
  }
}

TEST(VelocityEstimator, RecoversSlopeWhenMotionIsLinear)
{
  VelocityEstimator estimator(8);
  for (int i = 0; i < 20; ++i)
  {
    const double t = 100.0 + 0.001 * i;
    estimator.add(t, Vec3{ 3.0 + 50.0 * (t - 100.0), -20.0 * (t - 100.0), 1.0 });
  }
  EXPECT_NEAR(estimator.velocity_mm_per_s().x, 50.0, 1e-6);
  EXPECT_NEAR(estimator.velocity_mm_per_s().y, -20.0, 1e-6);
  EXPECT_NEAR(estimator.velocity_mm_per_s().z, 0.0, 1e-6);
}

TEST(VelocityEstimator, IgnoresSampleWhenTimestampDoesNotIncrease)
{
  VelocityEstimator estimator;
  EXPECT_TRUE(estimator.add(1.0, Vec3{}));
  EXPECT_FALSE(estimator.add(1.0, Vec3{ 5.0, 0.0, 0.0 }));
  EXPECT_FALSE(estimator.add(0.5, Vec3{ 5.0, 0.0, 0.0 }));
  EXPECT_FALSE(estimator.add(std::nan(""), Vec3{}));
  EXPECT_EQ(estimator.size(), 1u);
  EXPECT_EQ(estimator.velocity_mm_per_s().norm(), 0.0);
}

TEST(VelocityEstimator, SmoothsQuantizationWhenPositionIsStepped)
{
  VelocityEstimator estimator(16);
  double worst = 0.0;
  for (int i = 0; i < 200; ++i)
  {
    const double t = 0.001 * i;
    estimator.add(t, Vec3{ std::round(30.0 * t / 0.01) * 0.01, 0.0, 0.0 });
    if (i > 20)
    {
      worst = std::max(worst, std::abs(estimator.velocity_mm_per_s().x - 30.0));
    }
  }
  // A two-point difference would swing by 0.01 mm / 1 ms = 10 mm/s.
  EXPECT_LT(worst, 3.0);
}

TEST(VelocityEstimator, DropsOldSamplesWhenOutsideTimeWindow)
{
  VelocityEstimator estimator(8, 0.005);
  estimator.add(0.0, Vec3{ 1000.0, 0.0, 0.0 }); // stale outlier, 1 s before the rest
  for (int i = 0; i < 4; ++i)
  {
    estimator.add(1.0 + 0.001 * i, Vec3{ 10.0 * i * 0.001, 0.0, 0.0 });
  }
  EXPECT_NEAR(estimator.velocity_mm_per_s().x, 10.0, 1e-6);
}

} // namespace

// vtouch::ProgressThrottle (h18q): the first rank's stitch reports through it, so a slow listener
// (ParaView's progress handler, which sends at most one report a second to the client) gets a few
// reports a second that never go back. Times are given, not read from a clock.
#include "vtouchProgressThrottle.h"

#include <gtest/gtest.h>

#include <vector>

namespace
{
using vtouch::ProgressThrottle;

TEST(ProgressThrottle, PassesTheFirstOfferThenAtMostOncePerPeriod)
{
  std::vector<double> passed;
  ProgressThrottle throttle([&](double f) { passed.push_back(f); }, 0.25);
  const double times_s[] = { 0.0, 0.1, 0.2, 0.3, 0.5, 0.55, 0.8, 0.81 };
  std::vector<bool> answers;
  double fraction = 0.0;
  for (const double t : times_s)
  {
    fraction += 0.1;
    answers.push_back(throttle.offer(fraction, t));
  }
  EXPECT_EQ(answers, (std::vector<bool>{ true, false, false, true, false, true, true, false }));
  ASSERT_EQ(passed.size(), 4u);
  EXPECT_DOUBLE_EQ(passed[0], 0.1);
  EXPECT_DOUBLE_EQ(passed[1], 0.4);
  EXPECT_DOUBLE_EQ(passed[2], 0.6);
  EXPECT_DOUBLE_EQ(passed[3], 0.7);
}

TEST(ProgressThrottle, NeverPassesLessThanItPassedBefore)
{
  std::vector<double> passed;
  ProgressThrottle throttle([&](double f) { passed.push_back(f); }, 0.25);
  throttle.offer(0.5, 0.0);
  throttle.offer(0.2, 1.0); // a stage that starts its own count again: 0.5 again
  throttle.offer(0.7, 1.1); // too soon: kept as the highest
  throttle.offer(0.6, 1.5); // passes the highest offered, 0.7
  EXPECT_EQ(passed, (std::vector<double>{ 0.5, 0.5, 0.7 }));
  EXPECT_DOUBLE_EQ(throttle.highest(), 0.7);
}

TEST(ProgressThrottle, WithoutASinkOnlyCounts)
{
  ProgressThrottle throttle({}, 0.25);
  EXPECT_TRUE(throttle.offer(0.3, 0.0));
  EXPECT_FALSE(throttle.offer(0.4, 0.1));
  EXPECT_DOUBLE_EQ(throttle.highest(), 0.4);
}

} // namespace

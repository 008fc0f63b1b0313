// The stitch's check points (issue 16 item 6, h18q): on the first rank of a distributed run the
// stitch was the long silent stretch of the 128^3 raw phantom's long runs (21-74 s with no
// progress report, so a Cancel from the client waited for the run's end). Its long passes (the
// overlap's copy search, the attachments, the coverage check) now call SkeletonStitcher::progress
// every few dozen points or paths: the reports rise from 0 to 1, come from each pass, change
// nothing in the result, and a false answer stops the stitch with vtouch::Cancelled at once.
#include "vtouchStitchTestHelpers.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>
#include <vector>

namespace
{
using namespace vtouch;
using namespace vtouch_test;

/// Fifteen vessels across the face x = 10 of twoPieces(), 4 mm apart (farther than the copy
/// reach, so each is its own), with a small wave; ~450 points sent in all.
QSkeleton fifteenVessels()
{
  QSkeleton whole;
  int id = 0;
  for (const double y : { 2.0, 6.0, 10.0, 14.0, 18.0 })
  {
    for (const double z : { 2.0, 5.0, 8.0 })
    {
      std::vector<SkeletonPoint> points;
      for (int i = 0; i < 19; ++i)
      {
        points.push_back(point(1.0 + i, y + 0.2 * std::sin(i + y), z));
      }
      whole.paths.push_back(path(id++, points));
    }
  }
  return whole;
}

/// What the two pieces of twoPieces() send of `whole` (SkeletonClipper, as clipAndStitch).
std::vector<SkeletonFragment> sentByTwoPieces(const QSkeleton& whole)
{
  std::vector<SkeletonFragment> all;
  for (int r = 0; r < 2; ++r)
  {
    for (SkeletonFragment& f :
      SkeletonClipper(twoPieces(), IndexFrame{}, r, kOverlapBandVoxels).clip(whole))
    {
      all.push_back(std::move(f));
    }
  }
  return all;
}

SkeletonStitcher stitcherForTwoPieces()
{
  SkeletonStitcher stitcher;
  stitcher.joinTolerance_mm = 1.5;
  stitcher.ownership = twoPieces();
  return stitcher;
}

TEST(SkeletonStitcher, ReportsRisingProgressFromEachLongPassAndTheSameSkeleton)
{
  const std::vector<SkeletonFragment> sent = sentByTwoPieces(fifteenVessels());
  std::size_t points = 0;
  for (const SkeletonFragment& f : sent)
  {
    points += f.points.size();
  }
  ASSERT_GT(points, 4 * SkeletonOverlapResolver::kPointPeriod);
  StitchReport plainReport, reportedReport;
  const QSkeleton plain = stitcherForTwoPieces().stitch(sent, plainReport);
  SkeletonStitcher reporting = stitcherForTwoPieces();
  std::vector<double> fractions;
  reporting.progress = [&](double f)
  {
    fractions.push_back(f);
    return true;
  };
  const QSkeleton reported = reporting.stitch(sent, reportedReport);
  // The same skeleton, point for point.
  EXPECT_EQ(reported.validate(), "");
  ASSERT_EQ(reported.paths.size(), plain.paths.size());
  ASSERT_EQ(reported.paths.size(), 15u);
  for (std::size_t p = 0; p < plain.paths.size(); ++p)
  {
    ASSERT_EQ(reported.paths[p].points.size(), plain.paths[p].points.size()) << "path " << p;
    for (std::size_t i = 0; i < plain.paths[p].points.size(); ++i)
    {
      EXPECT_EQ(
        (reported.paths[p].points[i].position_World_mm - plain.paths[p].points[i].position_World_mm)
          .norm(),
        0.0);
    }
  }
  EXPECT_EQ(reportedReport.duplicatesRemoved, plainReport.duplicatesRemoved);
  EXPECT_EQ(reportedReport.cutEndsJoined, plainReport.cutEndsJoined);
  // Rising from 0 to 1, with reports inside the copy search (0-0.3 of the stitch: one every
  // kPointPeriod points) and inside the coverage check (0.4-1).
  ASSERT_FALSE(fractions.empty());
  EXPECT_DOUBLE_EQ(fractions.front(), 0.0);
  EXPECT_DOUBLE_EQ(fractions.back(), 1.0);
  int inSearch = 0, inCoverage = 0;
  for (std::size_t k = 0; k < fractions.size(); ++k)
  {
    if (k > 0)
    {
      EXPECT_GE(fractions[k], fractions[k - 1]) << "report " << k;
    }
    inSearch += fractions[k] > 0.0 && fractions[k] < 0.27 ? 1 : 0;
    inCoverage += fractions[k] > 0.4 && fractions[k] < 1.0 ? 1 : 0;
  }
  const int expected = static_cast<int>(points / SkeletonOverlapResolver::kPointPeriod) - 1;
  EXPECT_GE(inSearch, expected) << "of " << fractions.size() << " reports";
  EXPECT_GE(inCoverage, expected / 2) << "of " << fractions.size() << " reports";
}

TEST(SkeletonStitcher, StopsWithCancelledAtTheCheckPointThatAsks)
{
  const std::vector<SkeletonFragment> sent = sentByTwoPieces(fifteenVessels());
  std::size_t calls = 0;
  {
    SkeletonStitcher counting = stitcherForTwoPieces();
    counting.progress = [&](double)
    {
      ++calls;
      return true;
    };
    StitchReport report;
    counting.stitch(sent, report);
  }
  ASSERT_GT(calls, 8u);
  // The first check point, one in the copy search, one in the coverage check, the last.
  for (const std::size_t stopAt : { std::size_t{ 1 }, std::size_t{ 3 }, calls - 2, calls })
  {
    SkeletonStitcher stopping = stitcherForTwoPieces();
    std::size_t asked = 0;
    stopping.progress = [&](double)
    {
      ++asked;
      return asked < stopAt;
    };
    StitchReport report;
    EXPECT_THROW(stopping.stitch(sent, report), Cancelled) << "stopped at call " << stopAt;
    EXPECT_EQ(asked, stopAt) << "no check point after the one that asked to stop";
  }
}

} // namespace

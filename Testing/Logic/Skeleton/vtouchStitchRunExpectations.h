// What the distributed-geometry tests expect of a stitched run against the single run
// (vtouchDistributedStitchRun.h): the same network (paths, free ends, junctions), every cut end
// matched and no point dropped by the stitch.
#pragma once

#include "vtouchDistributedStitchRun.h"

#include <gtest/gtest.h>

namespace vtouch::test
{

inline void expectSameNetwork(const DistributedStitchRun& run)
{
  EXPECT_EQ(run.stitched.paths.size(), run.single.paths.size());
  EXPECT_EQ(freeEnds(run.stitched), freeEnds(run.single));
  EXPECT_EQ(run.stitched.junctions.size(), run.single.junctions.size());
  EXPECT_EQ(run.report.cutEndsUnmatched, 0);
  EXPECT_EQ(run.report.pointsDropped, 0);
}

} // namespace vtouch::test

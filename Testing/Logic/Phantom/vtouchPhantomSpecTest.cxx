#include "vtouchPhantomSpec.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

using vtouch::PhantomSpec;

TEST(PhantomSpec, DefaultsAreValid)
{
  EXPECT_EQ(PhantomSpec().validate(), "");
}

TEST(PhantomSpec, RejectsFlatOrEmptyVolumes)
{
  PhantomSpec spec;
  spec.dimensions = { 64, 64, 1 };
  EXPECT_NE(spec.validate().find("at least 3 voxels"), std::string::npos);
  spec.dimensions = { 0, 64, 64 };
  EXPECT_NE(spec.validate(), "");
  spec.dimensions = { -5, 64, 64 };
  EXPECT_NE(spec.validate(), "");
}

TEST(PhantomSpec, RejectsNonFiniteOrNonPositiveSpacing)
{
  PhantomSpec spec;
  spec.spacing_mm = { 1.0, std::numeric_limits<double>::quiet_NaN(), 1.0 };
  EXPECT_NE(spec.validate().find("spacing"), std::string::npos);
  spec.spacing_mm = { 1.0, 1.0, -0.5 };
  EXPECT_NE(spec.validate().find("spacing"), std::string::npos);
  spec.spacing_mm = { 1.0, 1.0, 0.0 };
  EXPECT_NE(spec.validate(), "");
}

TEST(PhantomSpec, RejectsVesselLargerThanTheVolume)
{
  PhantomSpec spec;
  spec.radiusFraction = 0.9;
  EXPECT_NE(spec.validate().find("radius"), std::string::npos);
  spec.radiusFraction = -0.1;
  EXPECT_NE(spec.validate(), "");
}

TEST(PhantomSpec, RejectsHugeVolumes)
{
  PhantomSpec spec;
  spec.dimensions = { 4096, 4096, 4096 };
  EXPECT_NE(spec.validate().find("voxels"), std::string::npos);
}

TEST(PhantomSpec, ReferenceLengthIsSmallestPhysicalSide)
{
  PhantomSpec spec;
  spec.dimensions = { 101, 51, 201 };
  spec.spacing_mm = { 0.5, 2.0, 0.25 };
  EXPECT_DOUBLE_EQ(spec.referenceLength_mm(), 50.0);
}

// vtouch::computeVoxelValueRange: the ranges the reader hands to VTK's range cache must be the
// ones VTK itself would compute (GetRange skips NaN, GetFiniteRange also skips infinities).
#include "vtouchVoxelValueRange.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <vector>

namespace
{
using vtouch::computeVoxelValueRange;
using vtouch::VoxelType;

TEST(VoxelValueRange, IntegerVoxelsGiveTheirExtremesWhereverTheyStand)
{
  std::vector<std::int16_t> v(1001, 7);
  v[0] = -3;      // first
  v[1000] = 2400; // last
  auto r = computeVoxelValueRange(v.data(), VoxelType::Int16, v.size());
  EXPECT_EQ(r.min, -3.0);
  EXPECT_EQ(r.max, 2400.0);
  EXPECT_EQ(r.finiteMin, -3.0);
  EXPECT_EQ(r.finiteMax, 2400.0);
  v[0] = 7;
  v[500] = -32768;
  r = computeVoxelValueRange(v.data(), VoxelType::Int16, v.size());
  EXPECT_EQ(r.min, -32768.0);
}

TEST(VoxelValueRange, EveryIntegerTypeKeepsItsSignAndWidth)
{
  const std::uint8_t u8[] = { 200, 3, 255 };
  EXPECT_EQ(computeVoxelValueRange(u8, VoxelType::UInt8, 3).max, 255.0);
  const std::int8_t s8[] = { -128, 3, 127 };
  EXPECT_EQ(computeVoxelValueRange(s8, VoxelType::Int8, 3).min, -128.0);
  const std::uint16_t u16[] = { 65535, 0 };
  EXPECT_EQ(computeVoxelValueRange(u16, VoxelType::UInt16, 2).max, 65535.0);
  const std::uint32_t u32[] = { 4000000000U, 1 };
  EXPECT_EQ(computeVoxelValueRange(u32, VoxelType::UInt32, 2).max, 4000000000.0);
  const std::int32_t s32[] = { -2000000000, 5 };
  EXPECT_EQ(computeVoxelValueRange(s32, VoxelType::Int32, 2).min, -2000000000.0);
}

TEST(VoxelValueRange, NaNsAreSkippedAndInfinitiesLeaveOnlyTheFiniteRange)
{
  const float inf = std::numeric_limits<float>::infinity();
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const std::vector<float> v = { nan, 2.5F, -inf, -1.0F, nan, 9.0F, inf };
  const auto r = computeVoxelValueRange(v.data(), VoxelType::Float32, v.size());
  EXPECT_EQ(r.min, -static_cast<double>(inf));
  EXPECT_EQ(r.max, static_cast<double>(inf));
  EXPECT_EQ(r.finiteMin, -1.0);
  EXPECT_EQ(r.finiteMax, 9.0);
  const std::vector<double> d = { 1e300, -4.0 };
  const auto rd = computeVoxelValueRange(d.data(), VoxelType::Float64, d.size());
  EXPECT_EQ(rd.min, -4.0);
  EXPECT_EQ(rd.max, 1e300);
}

TEST(VoxelValueRange, NoValueToCountGivesAnEmptyRangeNotAMadeUpOne)
{
  EXPECT_TRUE(computeVoxelValueRange(nullptr, VoxelType::Int16, 0).empty());
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<double> allNaN = { nan, nan };
  const auto r = computeVoxelValueRange(allNaN.data(), VoxelType::Float64, allNaN.size());
  EXPECT_TRUE(r.empty());
  EXPECT_TRUE(r.finiteEmpty());
  const double inf = std::numeric_limits<double>::infinity();
  const std::vector<double> onlyInf = { inf, -inf };
  const auto ri = computeVoxelValueRange(onlyInf.data(), VoxelType::Float64, onlyInf.size());
  EXPECT_FALSE(ri.empty());
  EXPECT_TRUE(ri.finiteEmpty());
  EXPECT_THROW(computeVoxelValueRange(nullptr, VoxelType::Int16, 4), std::invalid_argument);
}

} // namespace

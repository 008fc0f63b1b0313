// rangeForeground and volumeIntensity (Logic/VTK/vtouchRangeForeground.h): the raw path's
// cross-section foreground (intensity in [lower, upper], both ends included) and intensities,
// read typed for the five native types and through vtkDataArray for any other, with no copy
// (the lookups read the array as it is when they are called).
#include "vtouchRangeForeground.h"

#include "vtkDoubleArray.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkUnsignedShortArray.h"

#include <gtest/gtest.h>

#include <cstdint>

namespace
{

template<class Array>
void fill(Array* a)
{
  for (int v : { 5, 10, 15, 20, 25, 30, 35, 40 })
  {
    a->InsertNextValue(static_cast<typename Array::ValueType>(v));
  }
}

/// Which of the 8 voxels (a 2 x 2 x 2 grid) are inside [10, 30], as bits (voxel 0 lowest).
unsigned insideBits(vtkDataArray* a)
{
  const vtouch::SectionForeground fg = vtouch::rangeForeground(a, { 2, 2, 2 }, 10.0, 30.0);
  EXPECT_EQ(fg.dims, (std::array<std::int64_t, 3>{ 2, 2, 2 }));
  unsigned bits = 0;
  for (std::uint64_t lin = 0; lin < 8; ++lin)
  {
    bits |= fg.inside(lin) ? (1U << lin) : 0U;
  }
  return bits;
}

TEST(RangeForeground, NativeAndOtherTypesGiveTheSameInclusiveRange)
{
  vtkNew<vtkUnsignedShortArray> shorts;
  vtkNew<vtkDoubleArray> doubles;
  vtkNew<vtkIntArray> ints; // not a native type: read through vtkDataArray
  fill(shorts.Get());
  fill(doubles.Get());
  fill(ints.Get());
  const unsigned expected = 0b00111110; // voxels 1-5: 10, 15, 20, 25, 30
  EXPECT_EQ(insideBits(shorts), expected);
  EXPECT_EQ(insideBits(doubles), expected);
  EXPECT_EQ(insideBits(ints), expected);
}

TEST(RangeForeground, IntensitiesAreTheVoxelsOwnAndFollowTheArray)
{
  vtkNew<vtkIntArray> ints;
  vtkNew<vtkUnsignedShortArray> shorts;
  fill(ints.Get());
  fill(shorts.Get());
  const vtouch::SectionIntensity fromInts = vtouch::volumeIntensity(ints, { 2, 2, 2 });
  const vtouch::SectionIntensity fromShorts = vtouch::volumeIntensity(shorts, { 2, 2, 2 });
  for (std::uint64_t lin = 0; lin < 8; ++lin)
  {
    EXPECT_EQ(fromInts.value(lin), 5.0 * static_cast<double>(lin + 1));
    EXPECT_EQ(fromShorts.value(lin), 5.0 * static_cast<double>(lin + 1));
  }
  // No copy was made: a later change of the array is what the lookups read.
  ints->SetValue(3, 99);
  shorts->SetValue(3, 99);
  EXPECT_EQ(fromInts.value(3), 99.0);
  EXPECT_EQ(fromShorts.value(3), 99.0);
}

} // namespace

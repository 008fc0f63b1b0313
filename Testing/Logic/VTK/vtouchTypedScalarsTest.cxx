// withTypedScalars (Logic/VTK/vtouchTypedScalars.h): a run gets the volume's voxels as their own
// type for the five instantiated types, a float copy for any other, and its result back.
#include "vtouchTypedScalars.h"

#include "vtkDoubleArray.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkShortArray.h"
#include "vtkUnsignedCharArray.h"

#include <gtest/gtest.h>

#include <string>
#include <type_traits>

namespace
{

/// The voxel type the run saw, and the sum of the first three voxels.
template<class Array>
std::string seen(Array* a)
{
  for (int i = 0; i < 3; ++i)
  {
    a->InsertNextValue(static_cast<typename Array::ValueType>(i + 1));
  }
  return vtouch::withTypedScalars(a,
    [](const auto* voxels)
    {
      using T = std::remove_cv_t<std::remove_pointer_t<decltype(voxels)>>;
      const std::string type = std::is_same_v<T, float>           ? "float"
                               : std::is_same_v<T, double>        ? "double"
                               : std::is_same_v<T, unsigned char> ? "unsigned char"
                               : std::is_same_v<T, short>         ? "short"
                                                                  : "other";
      return type + " " + std::to_string(static_cast<double>(voxels[0] + voxels[1] + voxels[2]));
    });
}

TEST(TypedScalars, NativeTypesAreSeenAsTheirOwnAndOthersAsAFloatCopy)
{
  vtkNew<vtkUnsignedCharArray> bytes;
  vtkNew<vtkShortArray> shorts;
  vtkNew<vtkDoubleArray> doubles;
  vtkNew<vtkIntArray> ints;
  EXPECT_EQ(seen(bytes.Get()), "unsigned char 6.000000");
  EXPECT_EQ(seen(shorts.Get()), "short 6.000000");
  EXPECT_EQ(seen(doubles.Get()), "double 6.000000");
  EXPECT_EQ(seen(ints.Get()), "float 6.000000"); // int is not instantiated: a float copy
}

} // namespace

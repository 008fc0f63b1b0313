#include "vtouchVoxelValueRange.h"

#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <type_traits>

namespace vtouch
{
namespace
{

template <typename T>
VoxelValueRange rangeOf(const T* v, std::size_t n)
{
  VoxelValueRange r;
  if (n == 0)
  {
    return r;
  }
  if constexpr (std::is_integral_v<T>)
  {
    // Branch-free min/max over plain integers: the compiler vectorizes this loop.
    T lo = v[0], hi = v[0];
    for (std::size_t i = 1; i < n; ++i)
    {
      lo = v[i] < lo ? v[i] : lo;
      hi = v[i] > hi ? v[i] : hi;
    }
    r.min = r.finiteMin = static_cast<double>(lo);
    r.max = r.finiteMax = static_cast<double>(hi);
  }
  else
  {
    // NaN compares false both ways, so it never enters either range; infinities enter only the
    // plain range (as in vtkDataArray::GetRange and GetFiniteRange).
    T lo = INFINITY, hi = -INFINITY, flo = INFINITY, fhi = -INFINITY;
    for (std::size_t i = 0; i < n; ++i)
    {
      const T x = v[i];
      lo = x < lo ? x : lo;
      hi = x > hi ? x : hi;
      const bool finite = x - x == T(0); // false for NaN and for +-inf
      flo = finite && x < flo ? x : flo;
      fhi = finite && x > fhi ? x : fhi;
    }
    if (lo <= hi)
    {
      r.min = lo;
      r.max = hi;
    }
    if (flo <= fhi)
    {
      r.finiteMin = flo;
      r.finiteMax = fhi;
    }
  }
  return r;
}

} // namespace

VoxelValueRange computeVoxelValueRange(const void* voxels, VoxelType type, std::size_t count)
{
  if (count > 0 && !voxels)
  {
    throw std::invalid_argument("computeVoxelValueRange: no voxels");
  }
  switch (type)
  {
    case VoxelType::Int8:
      return rangeOf(static_cast<const std::int8_t*>(voxels), count);
    case VoxelType::UInt8:
      return rangeOf(static_cast<const std::uint8_t*>(voxels), count);
    case VoxelType::Int16:
      return rangeOf(static_cast<const std::int16_t*>(voxels), count);
    case VoxelType::UInt16:
      return rangeOf(static_cast<const std::uint16_t*>(voxels), count);
    case VoxelType::Int32:
      return rangeOf(static_cast<const std::int32_t*>(voxels), count);
    case VoxelType::UInt32:
      return rangeOf(static_cast<const std::uint32_t*>(voxels), count);
    case VoxelType::Float32:
      return rangeOf(static_cast<const float*>(voxels), count);
    case VoxelType::Float64:
      return rangeOf(static_cast<const double*>(voxels), count);
  }
  throw std::invalid_argument("computeVoxelValueRange: unknown voxel type");
}

} // namespace vtouch

#include "vtouchRangeForeground.h"

#include "vtkDataArray.h"
#include "vtkType.h"

namespace vtouch
{
namespace
{
/// Component 0 of a voxel through vtkDataArray: the lookup for the types not read typed.
struct ComponentLookup
{
  vtkDataArray* scalars;
  double operator[](std::uint64_t lin) const
  {
    return this->scalars->GetComponent(static_cast<vtkIdType>(lin), 0);
  }
};

/// `make(data)` with `data` the voxels as `const T*` for float, double, unsigned char, short and
/// unsigned short, else as a ComponentLookup (indexed like a pointer). Unlike withTypedScalars
/// (vtouchTypedScalars.h) it makes no copy: what `make` returns may keep `data` past the call.
template<class Make>
auto withVoxelLookup(vtkDataArray* scalars, Make&& make)
{
  const void* data = scalars->GetVoidPointer(0);
  switch (scalars->GetDataType())
  {
    case VTK_FLOAT:
      return make(static_cast<const float*>(data));
    case VTK_DOUBLE:
      return make(static_cast<const double*>(data));
    case VTK_UNSIGNED_CHAR:
      return make(static_cast<const unsigned char*>(data));
    case VTK_SHORT:
      return make(static_cast<const short*>(data));
    case VTK_UNSIGNED_SHORT:
      return make(static_cast<const unsigned short*>(data));
    default:
      return make(ComponentLookup{ scalars });
  }
}
} // namespace

SectionForeground rangeForeground(vtkDataArray* scalars,
  std::array<std::int64_t, 3> dims,
  double lower,
  double upper)
{
  return { dims,
    withVoxelLookup(scalars,
      [lower, upper](auto data) -> std::function<bool(std::uint64_t)>
      {
        return [data, lower, upper](std::uint64_t lin)
        { return inIntensityRange(static_cast<double>(data[lin]), lower, upper); };
      }) };
}

SectionIntensity volumeIntensity(vtkDataArray* scalars, std::array<std::int64_t, 3> dims)
{
  return { dims,
    withVoxelLookup(scalars,
      [](auto data) -> std::function<double(std::uint64_t)>
      { return [data](std::uint64_t lin) { return static_cast<double>(data[lin]); }; }) };
}
} // namespace vtouch

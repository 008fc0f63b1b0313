#include "vtouchRangeForeground.h"

#include "vtkDataArray.h"
#include "vtkType.h"

namespace vtouch
{
SectionForeground rangeForeground(vtkDataArray* scalars,
  std::array<std::int64_t, 3> dims,
  double lower,
  double upper)
{
  SectionForeground fg;
  fg.dims = dims;
  const auto typed = [&](auto* data)
  {
    fg.inside = [data, lower, upper](std::uint64_t lin)
    {
      const double v = static_cast<double>(data[lin]);
      return v >= lower && v <= upper;
    };
  };
  void* data = scalars->GetVoidPointer(0);
  switch (scalars->GetDataType())
  {
    case VTK_FLOAT:
      typed(static_cast<const float*>(data));
      break;
    case VTK_DOUBLE:
      typed(static_cast<const double*>(data));
      break;
    case VTK_UNSIGNED_CHAR:
      typed(static_cast<const unsigned char*>(data));
      break;
    case VTK_SHORT:
      typed(static_cast<const short*>(data));
      break;
    case VTK_UNSIGNED_SHORT:
      typed(static_cast<const unsigned short*>(data));
      break;
    default:
      fg.inside = [scalars, lower, upper](std::uint64_t lin)
      {
        const double v = scalars->GetComponent(static_cast<vtkIdType>(lin), 0);
        return v >= lower && v <= upper;
      };
  }
  return fg;
}

SectionIntensity volumeIntensity(vtkDataArray* scalars, std::array<std::int64_t, 3> dims)
{
  SectionIntensity in;
  in.dims = dims;
  const auto typed = [&](auto* data)
  { in.value = [data](std::uint64_t lin) { return static_cast<double>(data[lin]); }; };
  void* data = scalars->GetVoidPointer(0);
  switch (scalars->GetDataType())
  {
    case VTK_FLOAT:
      typed(static_cast<const float*>(data));
      break;
    case VTK_DOUBLE:
      typed(static_cast<const double*>(data));
      break;
    case VTK_UNSIGNED_CHAR:
      typed(static_cast<const unsigned char*>(data));
      break;
    case VTK_SHORT:
      typed(static_cast<const short*>(data));
      break;
    case VTK_UNSIGNED_SHORT:
      typed(static_cast<const unsigned short*>(data));
      break;
    default:
      in.value = [scalars](std::uint64_t lin)
      { return scalars->GetComponent(static_cast<vtkIdType>(lin), 0); };
  }
  return in;
}
} // namespace vtouch

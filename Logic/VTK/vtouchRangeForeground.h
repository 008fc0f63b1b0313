// The voxels of a volume whose intensity lies in [lower, upper], as the foreground the raw path's
// cross-sections are taken of (issue 16: the tube-section tracker and the tube-likeness pruner),
// and the volume's intensities (the turned dim tip rule).
#pragma once

#include "vtouchSectionSampler.h"

#include <array>
#include <cstdint>

class vtkDataArray;

namespace vtouch
{
/// `scalars` over a grid of `dims` (x fastest); typed lookups for float, double, unsigned char,
/// short and unsigned short, other types through vtkDataArray. `scalars` must outlive the result.
SectionForeground rangeForeground(vtkDataArray* scalars,
  std::array<std::int64_t, 3> dims,
  double lower,
  double upper);

/// `scalars` over a grid of `dims` (x fastest) as intensities (component 0), typed as above.
/// `scalars` must outlive the result.
SectionIntensity volumeIntensity(vtkDataArray* scalars, std::array<std::int64_t, 3> dims);
} // namespace vtouch

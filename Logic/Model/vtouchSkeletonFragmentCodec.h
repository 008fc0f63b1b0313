// Skeleton fragments as a flat array of doubles, what one rank sends to the first (issue 19).
#pragma once

#include "vtouchSkeletonFragment.h"

#include <string>
#include <vector>

namespace vtouch
{

/// Layout: fragment count, then per fragment: piece, point count, head (kind, x, y, z,
/// neighbour), tail (same), then per point: position (3), tangent (3), curvature, torsion,
/// radius, label. Exact (doubles), about 80 bytes per point: the skeleton, not the mask.
class SkeletonFragmentCodec
{
public:
  static std::vector<double> encode(const std::vector<SkeletonFragment>& fragments);
  /// Appends the fragments in `data[0, size)` to `out`; false with the reason in `error` when the
  /// array is truncated or holds impossible values.
  static bool decode(const double* data,
    std::size_t size,
    std::vector<SkeletonFragment>& out,
    std::string& error);
};

} // namespace vtouch

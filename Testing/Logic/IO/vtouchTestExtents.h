// Voxel boxes written as the six bounds a test reads best: i0..i1, j0..j1, k0..k1 (inclusive).
#ifndef vtouchTestExtents_h
#define vtouchTestExtents_h

#include "vtouchVolumeIO.h"

#include <cstddef>

namespace vtouch
{
namespace test
{
inline VoxelExtent box(std::size_t i0,
  std::size_t i1,
  std::size_t j0,
  std::size_t j1,
  std::size_t k0,
  std::size_t k1)
{
  VoxelExtent e;
  e.first = { { i0, j0, k0 } };
  e.last = { { i1, j1, k1 } };
  return e;
}
} // namespace test
} // namespace vtouch

#endif

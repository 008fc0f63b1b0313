// Explicit instantiations for the pixel types the hosts hand over, so clients link instead of
// recompiling the filter.
#include "vtouchVoxelCodingSkeletonFilter.h"

namespace vtouch
{
template class VoxelCodingSkeletonFilter<itk::Image<float, 3>>;
template class VoxelCodingSkeletonFilter<itk::Image<unsigned char, 3>>;
template class VoxelCodingSkeletonFilter<itk::Image<short, 3>>;
template class VoxelCodingSkeletonFilter<itk::Image<unsigned short, 3>>;
} // namespace vtouch

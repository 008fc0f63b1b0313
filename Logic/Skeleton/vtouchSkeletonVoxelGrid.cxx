#include "vtouchSkeletonVoxelGrid.h"

namespace vtouch
{
namespace skeleton
{

VoxelGrid::VoxelGrid(const SparseVesselMask& m,
  const std::array<double, 3>& spacing_mm,
  double clusterWidth_mm,
  const std::array<std::int64_t, 3>& pieceFirst_Whole)
  : mask(m)
{
  nx = m.dims()[0];
  ny = m.dims()[1];
  nz = m.dims()[2];
  nx32 = static_cast<std::uint32_t>(nx);
  ny32 = static_cast<std::uint32_t>(ny);
  inverseNx = 1.0 / static_cast<double>(nx32);
  inverseNy = 1.0 / static_cast<double>(ny32);
  for (int a = 0; a < 3; ++a)
  {
    sp[a] = spacing_mm[a];
    first_Whole[a] = pieceFirst_Whole[a];
  }
  minSpacing = std::min({ sp[0], sp[1], sp[2] });
  maxSpacing = std::max({ sp[0], sp[1], sp[2] });
  bandWidth = clusterWidth_mm > 0.0 ? clusterWidth_mm : maxSpacing;
  inverseBandWidth = static_cast<float>(1.0 / bandWidth);
  int n = 0;
  for (int dk = -1; dk <= 1; ++dk)
    for (int dj = -1; dj <= 1; ++dj)
      for (int di = -1; di <= 1; ++di)
      {
        if (di == 0 && dj == 0 && dk == 0)
        {
          continue;
        }
        off[n][0] = di;
        off[n][1] = dj;
        off[n][2] = dk;
        offLin[n] = di + nx * (dj + ny * dk);
        offLen[n] =
          std::sqrt(di * di * sp[0] * sp[0] + dj * dj * sp[1] * sp[1] + dk * dk * sp[2] * sp[2]);
        offLenF[n] = static_cast<float>(offLen[n]);
        offMm[n][0] = di * sp[0];
        offMm[n][1] = dj * sp[1];
        offMm[n][2] = dk * sp[2];
        ++n;
      }
  for (int q = 0; q < 9; ++q)
  {
    rowOffset[q] = nx * ((q % 3 - 1) + ny * (q / 3 - 1));
  }
}

} // namespace skeleton
} // namespace vtouch

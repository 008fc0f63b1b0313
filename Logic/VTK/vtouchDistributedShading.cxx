#include "vtouchDistributedShading.h"

#include "vtouchControllerCollectives.h"
#include "vtouchDistributedGlobalField.h"

#include <algorithm>

namespace vtouch
{

ShadingCorrection DistributedShading::run(vtkMultiProcessController* controller,
  vtkImageData* input,
  vtkDataArray* scalars,
  const VoxelExtent6& whole,
  bool useSeed,
  const double seed_World_mm[3])
{
  ControllerCollectives c(controller);
  ShadingCorrection out;
  const bool usable = input && scalars && scalars->GetNumberOfComponents() == 1 &&
                      scalars->GetNumberOfTuples() == input->GetNumberOfPoints() &&
                      input->GetNumberOfPoints() > 0;
  const std::array<std::int64_t, 3> wholeDims{
    whole[1] - whole[0] + 1, whole[3] - whole[2] + 1, whole[5] - whole[4] + 1
  };
  const std::uint64_t voxels = static_cast<std::uint64_t>(
    std::max<std::int64_t>(0, wholeDims[0] * wholeDims[1] * wholeDims[2]));
  const std::uint64_t stride = IntensityRangeEstimator::sampleStride(voxels);
  // This rank's voxels on the single run's lattice: (linear index, value) pairs.
  std::vector<double> lattice;
  std::array<std::int64_t, 3> origin{ 0, 0, 0 }, dims{ 0, 0, 0 };
  if (usable)
  {
    int e[6];
    input->GetExtent(e);
    for (std::size_t a = 0; a < 3; ++a)
    {
      origin[a] = e[2 * a] - whole[2 * a];
      dims[a] = e[2 * a + 1] - e[2 * a] + 1;
    }
    withVolumeView(scalars,
      dims,
      [&](const auto& view)
      {
        for (std::int64_t k = 0; k < dims[2]; ++k)
          for (std::int64_t j = 0; j < dims[1]; ++j)
          {
            const std::uint64_t rowStart = static_cast<std::uint64_t>(
              origin[0] + wholeDims[0] * (j + origin[1] + wholeDims[1] * (k + origin[2])));
            // The first i of the row on the lattice (rowStart + i a multiple of the stride).
            std::uint64_t i = (stride - rowStart % stride) % stride;
            for (; i < static_cast<std::uint64_t>(dims[0]); i += stride)
            {
              lattice.push_back(static_cast<double>(rowStart + i));
              lattice.push_back(view.at(static_cast<std::int64_t>(i), j, k));
            }
          }
      });
  }
  const std::vector<std::vector<double>> pieces = c.allGather(lattice);
  // The union of the ranks' lattice voxels, each once (ghost layers are held twice).
  std::vector<ShadingField::Sample> samples;
  for (const std::vector<double>& p : pieces)
  {
    for (std::size_t n = 0; n + 1 < p.size(); n += 2)
    {
      samples.push_back({ static_cast<std::uint64_t>(p[n]), p[n + 1] });
    }
  }
  std::sort(samples.begin(),
    samples.end(),
    [](const ShadingField::Sample& a, const ShadingField::Sample& b)
    { return a.linear < b.linear; });
  samples.erase(std::unique(samples.begin(),
                  samples.end(),
                  [](const ShadingField::Sample& a, const ShadingField::Sample& b)
                  { return a.linear == b.linear; }),
    samples.end());
  out.field = ShadingField::fit(wholeDims, stride, std::move(samples));
  if (useSeed && input)
  {
    const std::array<std::int64_t, 3> seed =
      DistributedGlobalField::seedVoxel_Whole(input, seed_World_mm, whole);
    if (seed[0] >= 0 && seed[1] >= 0 && seed[2] >= 0 && seed[0] < wholeDims[0] &&
        seed[1] < wholeDims[1] && seed[2] < wholeDims[2])
    {
      out.field.setReference(seed);
    }
  }
  out.summary = out.field.summary();
  if (!out.field.active() || !usable)
  {
    return out;
  }
  out.scalars = correctedScalars(out.field, scalars, dims, origin);
  return out;
}

} // namespace vtouch

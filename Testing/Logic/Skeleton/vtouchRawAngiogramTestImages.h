// Tiny synthetic raw angiograms for the raw-intensity stages' tests: bright tubes, plates and
// blobs with partial-volume intensities (each voxel averages 4^3 sub-samples), on a background
// with Gaussian noise.
#pragma once

#include "vtouchVolumeView.h"

#include <array>
#include <cstdint>
#include <vector>

namespace vtouch::test
{

struct SyntheticAngiogram
{
  std::array<std::int64_t, 3> dims{ 48, 48, 48 };
  std::vector<float> voxels;
  double background = 100.0;

  explicit SyntheticAngiogram(std::array<std::int64_t, 3> d, double background = 100.0);
  /// Adds `contrast` times the fraction of each voxel inside the capsule a-b of radius r (voxels).
  void addTube(std::array<double, 3> a, std::array<double, 3> b, double r, double contrast);
  /// Axis-aligned box [lo, hi] (voxel coordinates), partial volume at its faces.
  void addBox(std::array<double, 3> lo, std::array<double, 3> hi, double contrast);
  void addBall(std::array<double, 3> c, double r, double contrast);
  void addNoise(double sigma, unsigned seed);
  VolumeView<float> view() const
  {
    VolumeView<float> v;
    v.voxels = this->voxels.data();
    v.dims = this->dims;
    return v;
  }
  float& at(std::int64_t i, std::int64_t j, std::int64_t k)
  {
    return this->voxels[static_cast<std::size_t>(i + dims[0] * (j + dims[1] * k))];
  }
};

} // namespace vtouch::test

// VesselPhantom's raw angiogram (issue 16 item 4) as a whole float volume, for the tests that run
// the raw path on it in one process and across pieces (ranks as threads): the distributed
// tubularity, region and stitch tests. One recipe, so that they judge the same kind of volume.
#pragma once

#include "vtouchPhantomGenerator.h"
#include "vtouchVolumeView.h"

#include <array>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace vtouch::test
{

/// A volume of float voxels (x fastest), unit spacing at the origin (VolumeView's defaults).
struct FloatVolume
{
  std::array<std::int64_t, 3> dims{ 0, 0, 0 };
  std::vector<float> voxels;
  bool ok = true;    ///< false: the phantom could not be made (`error` says why)
  std::string error;

  FloatVolume() = default;
  FloatVolume(const std::array<std::int64_t, 3>& d, std::vector<float> v)
    : dims(d)
    , voxels(std::move(v))
  {
  }

  VolumeView<float> view() const
  {
    VolumeView<float> v;
    v.voxels = this->voxels.data();
    v.dims = this->dims;
    return v;
  }
};

/// The raw angiogram of n^3 voxels: `segments` vessel segments, 4 clutter objects (plates and
/// blobs at vessel intensity), Gaussian noise of `noiseStdDev`, random tree `seed`.
inline FloatVolume rawPhantomVolume(int n, std::uint32_t seed, int segments, double noiseStdDev)
{
  PhantomSpec spec;
  spec.shape = PhantomShape::RawAngiogram;
  spec.dimensions = { n, n, n };
  spec.angiogramSegments = segments;
  spec.clutterCount = 4;
  spec.noiseStdDev = noiseStdDev;
  spec.seed = seed;
  const PhantomGenerator generator(spec);
  FloatVolume v;
  v.dims = { n, n, n };
  v.voxels.resize(static_cast<std::size_t>(n) * n * n);
  v.ok = generator.ok() && generator.fill(v.voxels.data());
  v.error = generator.ok() ? std::string(v.ok ? "" : "the phantom's voxels were not filled")
                           : generator.error();
  return v;
}

} // namespace vtouch::test

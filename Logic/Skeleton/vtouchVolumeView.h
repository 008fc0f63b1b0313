// A read-only view of a dense 3D scalar volume (x fastest), for the raw-intensity stages that run
// before the voxel coder (range estimation, region growing, tubularity).
#pragma once

#include <array>
#include <cstdint>

namespace vtouch
{

template<typename T>
struct VolumeView
{
  const T* voxels = nullptr;
  std::array<std::int64_t, 3> dims{ 0, 0, 0 };
  std::array<double, 3> spacing_mm{ 1.0, 1.0, 1.0 };

  std::uint64_t size() const { return static_cast<std::uint64_t>(dims[0] * dims[1] * dims[2]); }
  bool inside(std::int64_t i, std::int64_t j, std::int64_t k) const
  {
    return i >= 0 && j >= 0 && k >= 0 && i < dims[0] && j < dims[1] && k < dims[2];
  }
  std::uint64_t linear(std::int64_t i, std::int64_t j, std::int64_t k) const
  {
    return static_cast<std::uint64_t>(i + dims[0] * (j + dims[1] * k));
  }
  double at(std::int64_t i, std::int64_t j, std::int64_t k) const
  {
    return static_cast<double>(this->voxels[this->linear(i, j, k)]);
  }
  std::array<std::int64_t, 3> index(std::uint64_t lin) const
  {
    const auto l = static_cast<std::int64_t>(lin);
    return { l % dims[0], (l / dims[0]) % dims[1], l / (dims[0] * dims[1]) };
  }
};

} // namespace vtouch

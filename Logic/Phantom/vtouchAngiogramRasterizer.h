// Intensities of the RawAngiogram phantom: partial volume of the tree and the clutter over
// textured tissue, a smooth multiplicative bias field, Gaussian or Rician noise.
#pragma once

#include "vtouchPhantomClutter.h"
#include "vtouchPhantomSpec.h"
#include "vtouchQSkeleton.h"

#include <array>
#include <cstdint>
#include <vector>

namespace vtouch
{

/// I(x) = bias(x) * (base(x) + (peak - base(x)) * f(x)) + noise, where
/// - f(x) in [0, 1] is the fraction of the voxel (a box of one spacing around x) inside the
///   union of the vessels and the clutter, from 4x4x4 supersampling of the voxels that the
///   surface crosses (voxels whose centre is deeper than the half diagonal count 1, farther
///   outside 0); the vessels are capsules between samples of the centerline one voxel apart;
/// - base(x) = tissueIntensity * (1 + 0.1 T(x)) is soft tissue with a smooth texture T in [-1, 1]
///   (three random plane-wave products, wavelengths 0.3..0.6 of the volume);
/// - bias(x) = 1 + biasAmplitude B(x), B in [-1, 1] the same construction with wavelengths 1..2
///   volumes (coil sensitivity, beam hardening);
/// - Gaussian noise adds sigma n1; Rician noise returns |(s + sigma n1) + i sigma n2| (the
///   magnitude image of MR, H. Gudbjartsson & S. Patz, MRM 34:910, 1995, eq. 2).
/// backgroundIntensity is not used (the background is tissue). Noise is a counter-based
/// function of (seed, voxel index): the same for any number of threads.
class AngiogramRasterizer
{
public:
  AngiogramRasterizer(const PhantomSpec& spec, const QSkeleton& tree);

  const PhantomClutter& clutter() const { return this->Clutter; }

  /// Writes the intensities of slices [k0, k1) into out (indexed like the whole volume, x
  /// fastest). Thread-safe for disjoint slabs.
  void fillSlab(float* out, int k0, int k1) const;

  /// Partial-volume fractions f of slices [k0, k1) (no tissue, bias or noise), for tests.
  void fractions(float* out, int k0, int k1) const;

private:
  struct Capsule
  {
    Vec3 a;
    Vec3 b;
    double radius_mm = 0.0;
    double zLo_mm = 0.0;
    double zHi_mm = 0.0;
  };
  /// A smooth field: the mean of three products of cosines along x, y and z, tabulated per axis.
  struct SmoothField
  {
    std::array<std::vector<float>, 9> table; ///< term * 3 + axis
    double at(int i, int j, int k) const;
  };

  void occupancy(std::vector<std::uint64_t>& bits, int k0, int k1) const;
  void rasterizeCapsule(const Capsule& c, std::vector<std::uint64_t>& bits, int k0, int k1) const;
  void rasterizeObject(const PhantomClutter::Object& o,
    std::vector<std::uint64_t>& bits,
    int k0,
    int k1) const;
  SmoothField makeField(std::uint64_t seed, double minWavelength, double maxWavelength) const;
  Vec3 world(int i, int j, int k) const;

  const PhantomSpec& Spec;
  PhantomClutter Clutter;
  std::vector<Capsule> Capsules;
  SmoothField Bias;
  SmoothField Texture;
  double HalfDiagonal_mm = 0.0;
  std::array<Vec3, 64> SubOffsets; ///< 4x4x4 sub-voxel centres relative to the voxel centre
};

} // namespace vtouch

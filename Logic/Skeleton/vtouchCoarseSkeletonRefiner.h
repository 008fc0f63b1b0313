// Moves a skeleton coded on a block-maximum downsampled mask (SparseVesselMask::downsampled) back
// onto the full-resolution mask: each coarse point is re-centred on the fine cross-section of the
// vessel, its radius is measured on the fine mask, and every path becomes a 26-connected chain of
// fine voxels again. The topology (paths, junctions, loops) is the coarse one.
#pragma once

#include "vtouchSparseVesselMask.h"
#include "vtouchVoxelCoding.h"

#include <array>
#include <cstdint>
#include <vector>

namespace vtouch
{

class CoarseSkeletonRefiner
{
public:
  /// `fine` is the full-resolution mask, `fineSpacing_mm` its voxel size, `factor` the block size
  /// of the coarse mask the skeleton was coded on (>= 1).
  CoarseSkeletonRefiner(const SparseVesselMask& fine,
    const std::array<double, 3>& fineSpacing_mm,
    unsigned int factor);

  /// The skeleton in the fine scaled index frame (fine index * fine spacing, mm). Its peakBytes
  /// and stageSeconds are the coarse run's plus the refinement's.
  RawSkeleton refine(const RawSkeleton& coarse);

  /// Largest extra memory of the last refine(), bytes.
  std::size_t peakBytes() const { return this->PeakBytes; }

private:
  using P3 = std::array<double, 3>;
  struct Section
  {
    P3 center_mm;
    double radius_mm = 0.0;
  };

  /// The cross-section of the vessel through `p_mm` normal to `tangent`: its centroid (when it is
  /// a closed section no larger than a junction-free tube of the coarse radius would give, else
  /// p_mm) and the distance to the nearest background voxel centre found in its plane.
  Section crossSection(const P3& p_mm, const P3& tangent, double coarseRadius_mm);
  bool vesselAt(const P3& p_mm) const;
  /// Centre of the voxel that vesselAt(p_mm) tests (p_mm inside the volume).
  P3 voxelCentre(const P3& p_mm) const;
  /// Distance from p_mm to the centre of the first background voxel along an in-plane ray.
  double rayToBackground(const P3& p_mm,
    const P3& direction,
    double step_mm,
    double limit_mm) const;
  std::vector<Section> refinePath(const RawSkeletonPath& path);
  const SparseVesselMask& Fine;
  P3 Spacing_mm;
  double MinSpacing_mm;
  double MaxSpacing_mm;
  unsigned int Factor;
  std::vector<std::uint8_t> Visited; // flood-fill scratch of one cross-section's sample grid
  std::vector<std::int32_t> Queue;
  std::vector<std::array<double, 2>> SectionPoints; // in-plane (u, w) position of each sample, mm
  std::size_t PeakBytes = 0;
};

} // namespace vtouch

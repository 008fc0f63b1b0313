// Cuts the non-tubular parts of a candidate region (bone plates, blobs, sinuses, tissue at vessel
// intensity) off at their necks, before the voxel coding.
//
// Tube cores are the voxels whose multi-scale tubularity (RestrictedTubularity: Frangi et al. 1998
// objectness, bright tubes) reaches `coreTubularity` (thin structures: `thinCoreTubularity`). The
// kept region is the union of the balls of the cores: each core reaches as many 26-connected layers
// as its own depth in the region plus one (RegionDepth: a core at the centre of a vessel reaches
// its wall; a neighbour structure is cut where it leaves the vessel's cross-section, its neck).
// Then, with a seed, only the kept component of the seed remains. Linear in the region's voxels (a
// bucket queue on the reach). The reconstruction is the product's rule; the paper (Yi & Hayward
// §3.1) codes the region as given.
#pragma once

#include "vtouchProgress.h"
#include "vtouchSparseVesselMask.h"

#include <array>
#include <cstdint>
#include <vector>

namespace vtouch
{

class TubeNeckCutter
{
public:
  struct Result
  {
    SparseVesselMask mask;        ///< kept voxels (finalized)
    std::uint64_t coreVoxels = 0; ///< voxels whose tubularity reached the core level
    bool seedKept = false;        ///< a seed was given and lies in (or next to) the kept region
    std::array<std::int64_t, 3> seed{ -1, -1, -1 }; ///< the kept voxel nearest the seed
  };

  /// `depth` and `tubularity` are indexed by `region.rank()`. `seed` may be null.
  /// A voxel of a structure one voxel thin (depth 1 and no deeper neighbour: a vessel of radius
  /// 0.5-1 voxel; no plate or blob is that thin) is a core from `thinCoreTubularity` on, since
  /// the Hessian of a partial-volume line is weak and noisy at the grid's finest scale.
  static Result cut(const SparseVesselMask& region,
    const std::vector<std::uint16_t>& depth,
    const std::vector<float>& tubularity,
    float coreTubularity,
    float thinCoreTubularity,
    const std::array<std::int64_t, 3>* seed,
    const ProgressSpan& progress = ProgressSpan());

  /// The voxel of `kept` nearest `seed` within the seed's cube of half size depth + 2 (`depth`
  /// indexed by `region.rank()`, as in cut()): true and `found` set, or false when none is.
  static bool nearestKept(const SparseVesselMask& kept,
    const SparseVesselMask& region,
    const std::vector<std::uint16_t>& depth,
    const std::array<std::int64_t, 3>& seed,
    std::array<std::int64_t, 3>& found);

  /// The 26-connected component of `seed` in `mask` (empty when the seed is not in it).
  /// `progress`: check points every 2^16 voxels (may throw Cancelled), as in cut().
  static SparseVesselMask component(const SparseVesselMask& mask,
    const std::array<std::int64_t, 3>& seed,
    const ProgressSpan& progress = ProgressSpan());
};

} // namespace vtouch

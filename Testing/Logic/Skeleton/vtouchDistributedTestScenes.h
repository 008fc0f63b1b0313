// Scenes of the distributed stages' tests (ranks as threads, issue 19 item 2): capsules made a
// mask, the random capsule trees the tests split into pieces, and a random vessel voxel. One
// place for the trees that vtouchDistributedSeedCodeTest and vtouchDistributedRootChoiceTest
// each grew with a copy of the same loop (duplicates --change; branch hdup): each test's trees
// are the ones it was measured on, voxel for voxel (RandomTreeRecipe keeps each recipe's draws
// in their order).
#pragma once

#include "vtouchSkeletonStageTestSupport.h"
#include "vtouchSparseVesselMask.h"

#include <array>
#include <cstdint>
#include <functional>
#include <random>
#include <vector>

namespace vtouch::test
{

using skeleton::test::Dims;
using VoxelIndex = std::array<std::int64_t, 3>;

/// A capsule in the voxel index frame (1 mm voxels: index = position in mm); a = b is a ball.
struct Capsule
{
  skeleton::Point_mm a, b; ///< its axis' ends (voxel indices)
  double radius;           ///< voxels
};

/// The voxels of `d` within some capsule's radius of its axis (or of its centre, a ball).
SparseVesselMask capsuleMask(const Dims& d, const std::vector<Capsule>& capsules);

/// The same capsules as an intensity volume (x fastest): `inside` in the mask, 0 elsewhere (the
/// thresholded input of VesselCenterline, for the harnesses that start from a volume).
std::vector<float> capsuleVolume(const Dims& d,
  const std::vector<Capsule>& capsules,
  float inside = 1000.0F);

/// How randomCapsuleTree grows a tree: a trunk, then 3 levels in which each capsule so far may
/// get a branch from a point 20-80 % along its axis to a random point inside the volume, of
/// 60-90 % of its radius (at least 1 voxel); then a ball of radius 1.2 at (2, 2, 2) (apart from
/// the tree, or touching it: either way).
struct RandomTreeRecipe
{
  /// The trunk's radius (voxels) from a uniform draw u in [0, 1).
  std::function<double(double u)> trunkRadius_voxels;
  /// The trunk's ends lie this far inside the volume's faces at least (voxels).
  double trunkMargin_voxels = 4.0;
  /// A capsule gets no branch in a level with this probability.
  double noBranchProbability = 0.35;
  /// Where a branch ends: false, `branchEndMargin_voxels` inside the faces, drawn before the
  /// branch's radius; true, its radius + 2 voxels inside, drawn after the radius (a thick
  /// branch stays whole in the volume).
  bool branchEndMarginFollowsRadius = false;
  double branchEndMargin_voxels = 3.0;
};

/// A random tree of capsules in `d` grown by `recipe`; `seed` makes it.
std::vector<Capsule> randomCapsuleTree(const Dims& d,
  unsigned seed,
  const RandomTreeRecipe& recipe);

/// vtouchDistributedSeedCodeTest's trees: a trunk of 1.5-2.5 voxels 4 inside the faces, 65 %
/// branching, branch ends 3 inside; the mask.
SparseVesselMask randomTree(const Dims& d, unsigned seed);

/// vtouchDistributedRootChoiceTest's trees: a trunk of `trunkRadius` to 1.3 `trunkRadius` voxels
/// (its ends its radius + 2 inside the faces), 70 % branching, branch ends their radius + 2
/// inside; the mask.
SparseVesselMask randomTree(const Dims& d, unsigned seed, double trunkRadius);

/// A vessel voxel of `mask` (whole index) picked by `random`.
VoxelIndex randomVesselVoxel(const SparseVesselMask& mask, std::mt19937& random);

} // namespace vtouch::test

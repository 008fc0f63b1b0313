#include "vtouchDistributedTestScenes.h"

#include <algorithm>
#include <stdexcept>

namespace vtouch::test
{
using skeleton::Point_mm;

SparseVesselMask capsuleMask(const Dims& d, const std::vector<Capsule>& capsules)
{
  return skeleton::test::makeMask(d,
    [&](const Point_mm& p)
    {
      for (const Capsule& c : capsules)
      {
        const bool point = c.a == c.b;
        if ((point ? skeleton::distance(p, c.a) : skeleton::test::distanceToSegment(p, c.a, c.b)) <=
            c.radius)
        {
          return true;
        }
      }
      return false;
    });
}

std::vector<float> capsuleVolume(const Dims& d, const std::vector<Capsule>& capsules, float inside)
{
  const SparseVesselMask mask = capsuleMask(d, capsules);
  std::vector<float> volume(static_cast<std::size_t>(d[0] * d[1] * d[2]), 0.0F);
  mask.forEach([&](std::uint64_t lin) { volume[static_cast<std::size_t>(lin)] = inside; });
  return volume;
}

std::vector<Capsule> randomCapsuleTree(const Dims& d, unsigned seed, const RandomTreeRecipe& recipe)
{
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const auto inside = [&](double margin)
  {
    return Point_mm{ margin + unit(random) * (static_cast<double>(d[0]) - 2 * margin),
      margin + unit(random) * (static_cast<double>(d[1]) - 2 * margin),
      margin + unit(random) * (static_cast<double>(d[2]) - 2 * margin) };
  };
  // The draws in each recipe's order: both ends, then the radius.
  const Point_mm trunkA = inside(recipe.trunkMargin_voxels);
  const Point_mm trunkB = inside(recipe.trunkMargin_voxels);
  std::vector<Capsule> tree{ { trunkA, trunkB, recipe.trunkRadius_voxels(unit(random)) } };
  for (int level = 0; level < 3; ++level)
  {
    const std::size_t parents = tree.size();
    for (std::size_t p = 0; p < parents; ++p)
    {
      if (unit(random) < recipe.noBranchProbability)
      {
        continue;
      }
      const Capsule c = tree[p];
      const double t = 0.2 + 0.6 * unit(random);
      const Point_mm from{ c.a[0] + t * (c.b[0] - c.a[0]),
        c.a[1] + t * (c.b[1] - c.a[1]),
        c.a[2] + t * (c.b[2] - c.a[2]) };
      if (recipe.branchEndMarginFollowsRadius)
      {
        const double r = std::max(1.0, c.radius * (0.6 + 0.3 * unit(random)));
        tree.push_back({ from, inside(r + 2), r });
      }
      else
      {
        const Point_mm to = inside(recipe.branchEndMargin_voxels);
        tree.push_back({ from, to, std::max(1.0, c.radius * (0.6 + 0.3 * unit(random))) });
      }
    }
  }
  tree.push_back({ { 2, 2, 2 }, { 2, 2, 2 }, 1.2 });
  return tree;
}

SparseVesselMask randomTree(const Dims& d, unsigned seed)
{
  RandomTreeRecipe recipe;
  recipe.trunkRadius_voxels = [](double u) { return 1.5 + u; };
  return capsuleMask(d, randomCapsuleTree(d, seed, recipe));
}

SparseVesselMask randomTree(const Dims& d, unsigned seed, double trunkRadius)
{
  RandomTreeRecipe recipe;
  recipe.trunkRadius_voxels = [trunkRadius](double u) { return trunkRadius * (1.0 + 0.3 * u); };
  recipe.trunkMargin_voxels = trunkRadius + 2;
  recipe.noBranchProbability = 0.3;
  recipe.branchEndMarginFollowsRadius = true;
  return capsuleMask(d, randomCapsuleTree(d, seed, recipe));
}

VoxelIndex randomVesselVoxel(const SparseVesselMask& mask, std::mt19937& random)
{
  std::vector<std::uint64_t> all;
  mask.forEach([&](std::uint64_t lin) { all.push_back(lin); });
  if (all.empty())
  {
    throw std::invalid_argument("randomVesselVoxel: the mask has no vessel voxel");
  }
  const std::uint64_t lin =
    all[std::uniform_int_distribution<std::size_t>(0, all.size() - 1)(random)];
  const Dims& d = mask.dims();
  return { static_cast<std::int64_t>(lin) % d[0],
    (static_cast<std::int64_t>(lin) / d[0]) % d[1],
    static_cast<std::int64_t>(lin) / (d[0] * d[1]) };
}

} // namespace vtouch::test

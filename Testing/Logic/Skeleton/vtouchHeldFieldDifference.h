// A rank's SS field against the single run's, voxel by voxel (the distributed stages' tests and
// benchmarks, issue 19 item 2): one place for the comparison loop that
// vtouchDistributedSeedCodeTest, vtouchSeededDistributedCodingTest,
// vtouchDistributedRootChoiceTest and the two distributed benchmarks each carried
// (duplicates --change; branch hdup).
#pragma once

#include "vtouchPieceLayout.h"
#include "vtouchSparseVesselMask.h"

#include <string>
#include <vector>

namespace vtouch::test
{

struct HeldFieldDifference
{
  int differing = 0;       ///< compared vessel voxels whose code differs from the single run's
  int reached = 0;         ///< compared vessel voxels with a finite code
  std::string firstDiffer; ///< "(i,j,k): got vs expected" of the first differing one, for messages
};

/// Compares rank `l`'s field `pieceField` (indexed by its piece mask `piece`'s rank) with the
/// single run's `wholeField` (indexed by `whole`'s rank) on the piece's vessel voxels inside
/// `box` (whole index; l.mine() for all it holds). Throws std::invalid_argument when a field's
/// size is not its mask's vessel count.
HeldFieldDifference compareWithSingleRun(const SparseVesselMask& whole,
  const std::vector<float>& wholeField,
  const PieceLayout& l,
  const SparseVesselMask& piece,
  const std::vector<float>& pieceField,
  const VoxelBox& box);

} // namespace vtouch::test

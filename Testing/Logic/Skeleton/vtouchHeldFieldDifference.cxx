#include "vtouchHeldFieldDifference.h"

#include "vtouchSkeletonVoxelCodes.h"

#include <array>
#include <cstdint>
#include <stdexcept>

namespace vtouch::test
{

HeldFieldDifference compareWithSingleRun(const SparseVesselMask& whole,
  const std::vector<float>& wholeField,
  const PieceLayout& l,
  const SparseVesselMask& piece,
  const std::vector<float>& pieceField,
  const VoxelBox& box)
{
  if (wholeField.size() != whole.vesselCount() || pieceField.size() != piece.vesselCount())
  {
    throw std::invalid_argument(
      "compareWithSingleRun: a field's size is not its mask's vessel "
      "voxel count (" +
      std::to_string(wholeField.size()) + " for " + std::to_string(whole.vesselCount()) + ", " +
      std::to_string(pieceField.size()) + " for " + std::to_string(piece.vesselCount()) + ")");
  }
  HeldFieldDifference out;
  const std::array<std::int64_t, 3> d = l.pieceDims();
  piece.forEach(
    [&](std::uint64_t lin)
    {
      const auto li = static_cast<std::int64_t>(lin);
      const std::array<std::int64_t, 3> w =
        l.toWhole({ li % d[0], (li / d[0]) % d[1], li / (d[0] * d[1]) });
      if (!box.contains(w))
      {
        return;
      }
      const float expected = wholeField[whole.rank(static_cast<std::uint64_t>(l.wholeLinear(w)))];
      const float got = pieceField[piece.rank(lin)];
      out.reached += got != skeleton::VoxelCodes::kInf;
      if (got != expected && out.differing++ == 0)
      {
        out.firstDiffer = "(" + std::to_string(w[0]) + "," + std::to_string(w[1]) + "," +
                          std::to_string(w[2]) + "): " + std::to_string(got) + " vs " +
                          std::to_string(expected);
      }
    });
  return out;
}

} // namespace vtouch::test

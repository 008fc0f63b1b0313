// Where a distributed run's piece lies in the whole volume, so that its rank computes every
// position as the single run does (issue 19 item 2, Docs/CLIENT-SERVER.md "Departures and what
// is still to come", positions).
#pragma once

#include <array>
#include <cstdint>

namespace vtouch
{

/// A piece's place in the whole volume's frame. A rank that computed a position from its piece's
/// origin (the whole origin plus its first voxel's offset, rounded once) plus its index in the
/// piece got another double than the single run's whole origin plus the whole index (1e-13 to
/// 6e-7 mm apart), and that decided exact ties downstream (the tube-likeness pruner's mid-line
/// test on the TOF-MRA, h19m). With this frame the coder computes a voxel's centre as
/// (first_Whole + local index) * spacing, whole-lattice mm, the single run's numbers, and the
/// world position as wholeOrigin_World_mm + direction * that, the single run's operations in
/// the single run's order. The default (index 0 at the piece's own origin) is the single run.
struct PieceInWhole
{
  /// The whole volume's voxel index of the piece's voxel (0, 0, 0).
  std::array<std::int64_t, 3> first_Whole{ 0, 0, 0 };
  /// The world position of the whole volume's voxel (0, 0, 0), mm.
  std::array<double, 3> wholeOrigin_World_mm{ 0.0, 0.0, 0.0 };
};

} // namespace vtouch

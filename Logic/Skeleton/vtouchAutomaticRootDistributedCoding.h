// The unseeded modes' global SS code on one rank's piece, for the voxel coder (issue 19 item 2,
// Docs/CLIENT-SERVER.md "The automatic root across the ranks, wired"): the single run's automatic
// roots and SS field from vtouch::DistributedRootChoice, joined exactly once per run by every
// rank, as vtouch::SeededDistributedCoding is for the seeded modes.
//
// The collective steps, the same on every rank whichever way it joins:
//  1. one AllGather of whether each rank can take part: a rank joins from inside its coder
//     (code(), with the final mask: it can) or, when its run stopped before the coder (an error,
//     a cancel, no input), from the caller afterwards (join(): it cannot: an empty mask is not
//     its piece of the whole mask, and DistributedRootChoice needs every rank's piece exact);
//  2. a common verdict: any rank that cannot take part stops every rank with one message naming
//     the first such rank, before any other exchange;
//  3. DistributedRootChoice::choose on every rank (its own verdicts are common too).
// A piece without vessel voxels reaches its coder with an empty mask and takes part (its empty
// mask is its piece of the whole mask).
//
// Not yet the single run's move of the root to the thickest end (ClusterStage::thickerRoot):
// choose() gives the extremity the single run first codes from (see its header).
//
// Plain C++ over vtouch::RankCollectives (the filter: vtkMultiProcessController; the tests:
// threads).
#pragma once

#include "vtouchDistributedRootChoice.h"
#include "vtouchPieceLayout.h"
#include "vtouchRankCollectives.h"
#include "vtouchSparseVesselMask.h"

#include <array>
#include <stdexcept>
#include <vector>

namespace vtouch
{

/// Thrown by code() and join() on every rank together, with the same message.
class AutomaticRootCodingError : public std::runtime_error
{
public:
  using std::runtime_error::runtime_error;
};

class AutomaticRootDistributedCoding
{
public:
  /// `layout`: the pieces, the same on every rank (gathered), `layout.rank` this rank.
  /// `spacing_mm`: the voxel size. `parameters`: the coder's MinimumComponentSize (input voxels:
  /// the global field is coded at full resolution) and cluster width, and the round cap.
  AutomaticRootDistributedCoding(RankCollectives& collectives,
    PieceLayout layout,
    const std::array<double, 3>& spacing_mm,
    const DistributedRootChoice::Parameters& parameters);

  /// Collective, once per run: the single run's SS field on `mask` (this rank's vessel voxels on
  /// its held box, local linear index, finalized: its piece of the whole mask), indexed by
  /// `mask`'s rank, mm; infinite on components below the minimum size. Throws
  /// AutomaticRootCodingError (every rank together) when a rank cannot take part or the choice
  /// fails; std::logic_error when called twice.
  std::vector<float> code(const SparseVesselMask& mask);

  /// Collective: takes part as a rank that cannot (its run stopped before its coder): every
  /// rank then stops with one message. Throws as code() does.
  void join();

  bool joined() const { return this->Joined; }
  /// The choice (roots per component, propagations, rounds; ss_mm emptied after code()).
  const DistributedRootChoice::Result& report() const { return this->Result; }

private:
  std::vector<float> take(const SparseVesselMask* mask);

  RankCollectives& Collectives;
  PieceLayout Layout;
  std::array<double, 3> Spacing_mm;
  DistributedRootChoice::Parameters Parameters;
  bool Joined = false;
  DistributedRootChoice::Result Result;
};

} // namespace vtouch

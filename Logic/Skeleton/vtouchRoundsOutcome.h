// What a run of collective rounds did (vtouch::CollectiveRounds): the outcome
// DistributedRegionGrowth and DistributedSeedCode return (issue 19 item 2).
#pragma once

#include <cstdint>
#include <string>

namespace vtouch
{

struct RoundsOutcome
{
  int rounds = 0;                   ///< exchanges made (the same on every rank)
  std::uint64_t reportedVoxels = 0; ///< voxels this rank reported, all rounds
  bool settled = false;             ///< false: stopped at the round cap
  std::string message;              ///< why it did not settle
};

} // namespace vtouch

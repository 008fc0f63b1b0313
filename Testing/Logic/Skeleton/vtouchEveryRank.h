// The thread-rank harness of the distributed stages' tests and benchmarks (issue 19 item 2):
// every rank of a split run on a thread of its own (InProcessWorld), each with its layout and an
// element of its own of the result. One place for the set-up each test carried (a world, a
// vector of results sized to the ranks, the rank's layout picked in the body; branch hdup).
#pragma once

#include "vtouchInProcessCollectives.h"
#include "vtouchPieceLayout.h"

#include <cstddef>
#include <vector>

namespace vtouch::test
{

/// Runs `body(layout, collectives, result)` on every rank of `pieces` (rank r gets pieces[r] and
/// element r of the returned vector, PerRank default-constructed before); rethrows the first
/// exception a rank threw.
template<class PerRank, class Body>
std::vector<PerRank> onEveryRank(const std::vector<PieceLayout>& pieces, const Body& body)
{
  std::vector<PerRank> results(pieces.size());
  InProcessWorld world(static_cast<int>(pieces.size()));
  world.run([&](int r, RankCollectives& c)
    { body(pieces[static_cast<std::size_t>(r)], c, results[static_cast<std::size_t>(r)]); });
  return results;
}

} // namespace vtouch::test

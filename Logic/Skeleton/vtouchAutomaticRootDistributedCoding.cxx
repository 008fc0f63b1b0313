// vtouch::AutomaticRootDistributedCoding: the agreement before the automatic root's choice, and
// the choice, for one rank's coder (see the header for why every rank takes the same steps).
#include "vtouchAutomaticRootDistributedCoding.h"

#include <string>
#include <utility>

namespace vtouch
{

AutomaticRootDistributedCoding::AutomaticRootDistributedCoding(RankCollectives& collectives,
  PieceLayout layout,
  const std::array<double, 3>& spacing_mm,
  const DistributedRootChoice::Parameters& parameters)
  : Collectives(collectives)
  , Layout(std::move(layout))
  , Spacing_mm(spacing_mm)
  , Parameters(parameters)
{
}

std::vector<float> AutomaticRootDistributedCoding::code(const SparseVesselMask& mask)
{
  return this->take(&mask);
}

void AutomaticRootDistributedCoding::join()
{
  this->take(nullptr);
}

std::vector<float> AutomaticRootDistributedCoding::take(const SparseVesselMask* mask)
{
  if (this->Joined)
  {
    throw std::logic_error(
      "AutomaticRootDistributedCoding: a rank joins the automatic root's choice once per run");
  }
  this->Joined = true;
  // Step 1: can every rank take part? (A rank without its mask would give the others a field
  // from a wrong whole mask: no rank codes with it.)
  const std::vector<std::vector<std::int64_t>> all =
    this->Collectives.allGather(std::vector<std::int64_t>{ mask ? 1 : 0 });
  for (std::size_t r = 0; r < all.size(); ++r)
  {
    if (all[r].size() != 1 || all[r][0] != 1)
    {
      throw AutomaticRootCodingError(
        "VesselCenterline (distributed): rank " + std::to_string(r) +
        " stopped before its coder (no piece, an error or a cancel: its own message says "
        "which), so no rank can code with the automatic root across the pieces; extract on "
        "one rank or fix that rank's input.");
    }
  }
  // Steps 2-3: the choice (its verdicts are every rank's together).
  this->Result = DistributedRootChoice::choose(
    this->Layout, *mask, this->Spacing_mm, this->Collectives, this->Parameters);
  if (!this->Result.ok)
  {
    throw AutomaticRootCodingError("VesselCenterline (distributed): the automatic root across "
                                   "the pieces failed: " +
                                   this->Result.message + "; extract on one rank.");
  }
  return std::exchange(this->Result.ss_mm, {});
}

} // namespace vtouch

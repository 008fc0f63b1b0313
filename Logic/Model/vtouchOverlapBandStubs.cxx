#include "vtouchOverlapBandStubs.h"

#include <algorithm>

namespace vtouch
{

OverlapBandStubs::OverlapBandStubs(const PieceOwnership& ownership, const IndexFrame& frame)
  : ownership_(ownership)
  , frame_(frame)
{
}

bool OverlapBandStubs::onlyBandPoints(const SkeletonFragment& run) const
{
  return !run.points.empty() &&
         std::none_of(run.points.begin(),
           run.points.end(),
           [&](const SkeletonPoint& p)
           { return ownership_.owner(frame_.toIndex(p.position_World_mm)) == run.piece; });
}

std::vector<char> OverlapBandStubs::find(const std::vector<SkeletonFragment>& runs,
  const std::vector<long>& partner) const
{
  std::vector<char> stub(runs.size(), 0);
  if (ownership_.pieceCount() == 0 || partner.size() != 2 * runs.size())
  {
    return stub; // no pieces: nothing was sent as a band
  }
  for (std::size_t i = 0; i < runs.size(); ++i)
  {
    const SkeletonFragment& run = runs[i];
    const bool headCut = run.head.kind == FragmentEnd::Kind::Cut;
    const bool tailCut = run.tail.kind == FragmentEnd::Kind::Cut;
    const bool headJoined = headCut && partner[2 * i] >= 0;
    const bool tailJoined = tailCut && partner[2 * i + 1] >= 0;
    const bool unmatched = (headCut && !headJoined) || (tailCut && !tailJoined);
    stub[i] = unmatched && !headJoined && !tailJoined && onlyBandPoints(run) ? 1 : 0;
  }
  return stub;
}

} // namespace vtouch

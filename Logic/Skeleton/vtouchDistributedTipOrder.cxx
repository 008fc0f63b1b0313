// vtouch::DistributedTipOrder: the true tips gathered from every rank, sorted as the single run
// sorts its tips.
#include "vtouchDistributedTipOrder.h"
#include "vtouchFloatWords.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <string>
#include <utility>

namespace vtouch
{
std::int64_t DistributedTipOrder::rankKey(std::uint32_t band, std::int64_t place)
{
  return (static_cast<std::int64_t>(band) << kPlaceBits) | (kPlaceMask - place);
}

void DistributedTipOrder::gather(RankCollectives& collectives, const std::vector<Tip>& mine)
{
  std::vector<std::int64_t> flat;
  for (const Tip& t : mine)
  {
    flat.insert(flat.end(), { t.band, floatToWord(t.firstSs_mm), t.firstWhole });
  }
  std::vector<Tip> all;
  for (const std::vector<std::int64_t>& theirs : collectives.allGather(flat))
  {
    for (std::size_t i = 0; i + 2 < theirs.size(); i += 3)
    {
      all.push_back(
        { static_cast<std::uint32_t>(theirs[i]), wordToFloat(theirs[i + 1]), theirs[i + 2] });
    }
  }
  // The single run's tip order (TraceStage::run without answers): the band, higher first, then
  // the cluster's number, which is the key order (ClusterStage::build).
  std::sort(all.begin(),
    all.end(),
    [](const Tip& a, const Tip& b)
    {
      if (a.band != b.band)
      {
        return a.band > b.band;
      }
      if (a.firstSs_mm != b.firstSs_mm)
      {
        return a.firstSs_mm < b.firstSs_mm;
      }
      return a.firstWhole < b.firstWhole;
    });
  if (!all.empty() && static_cast<std::int64_t>(all.front().band) >= kBandLimit)
  {
    throw std::runtime_error("VesselCenterline (distributed): a tip's band (" +
                             std::to_string(all.front().band) +
                             ") exceeds the tips' order's limit (" + std::to_string(kBandLimit) +
                             "); extract on one rank.");
  }
  this->PlaceOf.clear();
  for (std::size_t p = 0; p < all.size(); ++p)
  {
    this->PlaceOf.emplace(
      all[p].firstWhole, std::make_pair(all[p].band, static_cast<std::int64_t>(p)));
  }
}

std::int64_t DistributedTipOrder::rankKeyOf(std::int64_t firstWhole, std::uint32_t band) const
{
  const auto hit = this->PlaceOf.find(firstWhole);
  if (hit == this->PlaceOf.end() || hit->second.first != band)
  {
    return unplacedRankKey(band);
  }
  return rankKey(band, hit->second.second);
}

} // namespace vtouch

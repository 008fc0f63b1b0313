// vtouch::CancellableCollectives: a cancel carried in every exchange (see the header).
#include "vtouchCancellableCollectives.h"

#include "vtouchProgress.h"

#include <stdexcept>

#include <utility>

namespace vtouch
{
namespace
{
/// Strips the status word each rank appended; true when any rank's word asks to cancel. A rank
/// that appended none is not running the same exchange (a programming error, reported).
template<typename T>
bool stripCancelWords(std::vector<std::vector<T>>& all)
{
  bool any = false;
  for (std::vector<T>& theirs : all)
  {
    if (theirs.empty())
    {
      throw std::logic_error("CancellableCollectives: a rank sent no cancel word");
    }
    any = any || theirs.back() != T{ 0 };
    theirs.pop_back();
  }
  return any;
}
} // namespace

CancellableCollectives::CancellableCollectives(RankCollectives& inner, CancelCheck cancelRequested)
  : Inner(inner)
  , CancelRequested(std::move(cancelRequested))
{
}

int CancellableCollectives::rank() const
{
  return this->Inner.rank();
}

int CancellableCollectives::ranks() const
{
  return this->Inner.ranks();
}

void CancellableCollectives::throwIfCancelled() const
{
  if (this->Cancelled)
  {
    throw vtouch::Cancelled();
  }
}

std::vector<std::vector<double>> CancellableCollectives::allGather(const std::vector<double>& mine)
{
  this->throwIfCancelled();
  std::vector<double> sent = mine;
  sent.push_back(this->asked() ? 1.0 : 0.0);
  std::vector<std::vector<double>> all = this->Inner.allGather(sent);
  this->Cancelled = stripCancelWords(all);
  this->throwIfCancelled();
  return all;
}

std::vector<std::vector<std::int64_t>> CancellableCollectives::allGather(
  const std::vector<std::int64_t>& mine)
{
  this->throwIfCancelled();
  std::vector<std::int64_t> sent = mine;
  sent.push_back(this->asked() ? 1 : 0);
  std::vector<std::vector<std::int64_t>> all = this->Inner.allGather(sent);
  this->Cancelled = stripCancelWords(all);
  this->throwIfCancelled();
  return all;
}

std::vector<std::vector<std::int64_t>> CancellableCollectives::gather(
  const std::vector<std::int64_t>& mine,
  int root)
{
  this->throwIfCancelled();
  return this->Inner.gather(mine, root);
}

void CancellableCollectives::agree()
{
  this->allGather(std::vector<std::int64_t>{});
}

} // namespace vtouch
